// A uniform number in [0, 1) that is a pure function of (episode seed, step, salt): agents that
// draw their random actions from it answer a re-sent batch identically and replay a seeded
// episode exactly, whatever the timing and however many arenas run beside it. A splitmix64
// finaliser over the packed inputs.
#pragma once

#include <cstdint>

#include "hideseek_game/agent.h"

namespace hideseek_game {

// Salts of the draws, one per purpose, so that two agents never share a stream.
constexpr uint32_t kSaltRandomHider = 1;
constexpr uint32_t kSaltSampledPolicy = 2;
constexpr uint32_t kSaltRandomSeeker = 3;         // the seeker node's random mode
constexpr uint32_t kSaltSampledSeekerPolicy = 4;  // a learning seeker's sampled actions

inline double hashUniform(uint32_t seed, uint32_t step, uint32_t salt) {
  uint64_t z = (static_cast<uint64_t>(seed) << 32 | step) ^ static_cast<uint64_t>(salt) * 0x632be59bd9b4e019ULL;
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);
}

// A uniformly random action for this seed, step and salt, among the first `count` (the hider's five).
inline uint8_t hashAction(uint32_t seed, uint32_t step, uint32_t salt, int count = kNumActions) {
  return static_cast<uint8_t>(hashUniform(seed, step, salt) * count);
}

}  // namespace hideseek_game
