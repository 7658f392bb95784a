// The training process's heap. The hider allocates and frees image-sized buffers every step (each
// observation message is 16 x 84 x 84 x 3 bytes, and the tensors built from it) and large tensors
// every update. glibc's malloc serves blocks above its mmap threshold with fresh mappings and
// trims the heap's top after frees, so memory goes back to the kernel and is faulted in again page
// by page. On a 2-core virtual machine a fifth of the hider's time was in the page-fault path and
// a run through the graph trained 2.5x faster with freed memory kept (docs/performance.md); the
// training floor, which has no messages, gained 1.08x.
#pragma once

namespace hideseek_hider {

// Serves every allocation from the heap (no mmap) and never trims it. The process then keeps its
// peak memory until it exits: call it only in processes that train or evaluate the network.
// Returns false when the allocator refused a setting.
bool keepFreedMemoryInHeap();

}  // namespace hideseek_hider
