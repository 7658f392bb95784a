// The training process's heap. Each PPO update allocates the same large tensors (the rollout's
// image batch, activations, gradients), frees them and allocates them again. glibc's malloc serves
// blocks above its mmap threshold with fresh mappings and trims the heap's top after each free,
// so every update hands hundreds of megabytes back to the kernel and faults them in again page by
// page: on a 2-core virtual machine that was 27 % of the training process's time, in the kernel
// (docs/performance.md). Keeping freed memory in the heap makes the next update reuse it.
#pragma once

namespace hideseek_hider {

// Serves every allocation from the heap (no mmap) and never trims it. The process then keeps its
// peak memory until it exits: call it only in processes that train or evaluate the network.
// Returns false when the allocator refused a setting.
bool keepFreedMemoryInHeap();

}  // namespace hideseek_hider
