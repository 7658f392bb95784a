#include "hideseek_game/heap.h"

#include <malloc.h>

#include <climits>

namespace hideseek_game {

bool keepFreedMemoryInHeap() {
  constexpr int kTopPad = 256 << 20;  // bytes the heap grows by beyond a request, so growth is rare
  return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1 && mallopt(M_TOP_PAD, kTopPad) == 1;
}

}  // namespace hideseek_game
