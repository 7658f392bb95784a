// The heap of the processes that move image batches every step: the hider and the world. The
// hider allocates and frees image-sized buffers every step (each observation message is 16 x 84 x
// 84 x 3 bytes, and the tensors built from it) and large tensors every update. glibc's malloc
// serves blocks above its mmap threshold with fresh mappings and trims the heap's top after frees,
// so memory goes back to the kernel and is faulted in again page by page. On a 2-core virtual
// machine a fifth of the hider's time was in the page-fault path and a run through the graph
// trained 2.5x faster with freed memory kept (docs/performance.md); the training floor, which has
// no messages, gained 1.08x. The world builds the same batch every step and roscpp serialises a
// copy of it: kept in its heap, the world's CPU time per PPO update fell by about 15 % and the
// hider's wait for it by about 10 %.
#pragma once

namespace hideseek_game {

// Serves every allocation from the heap (no mmap) and never trims it. The process then keeps its
// peak memory until it exits: call it only in processes whose peak is their working set (the
// hider, the world).
// Returns false when the allocator refused a setting.
bool keepFreedMemoryInHeap();

}  // namespace hideseek_game
