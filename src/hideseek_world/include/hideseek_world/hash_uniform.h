// A uniform number in [0, 1) that is a pure function of (episode seed, step, arena, salt): agents
// that draw their random actions from it answer a re-sent batch identically and replay a seeded
// episode exactly, whatever the timing. A splitmix64 finaliser over the packed inputs.
#pragma once

#include <cstdint>

namespace hideseek_world {

inline double hashUniform(uint32_t seed, uint32_t step, uint32_t arena, uint32_t salt) {
  uint64_t z = (static_cast<uint64_t>(seed) << 32 | step) ^
               (static_cast<uint64_t>(arena) << 17 | salt) * 0x632be59bd9b4e019ULL;
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);
}

}  // namespace hideseek_world
