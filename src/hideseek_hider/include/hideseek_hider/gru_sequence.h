// The hider's GRU over a sequence, with the state zeroed where an episode starts, as one autograd
// operation. torch::nn::GRUCell's equations (gates r, z, n; h' = n + z (h - n)) stepped by ATen
// operators record about ten autograd nodes per step and, in the backward pass, one small weight
// gradient product per step. On the CPU this operation runs the forward pass without recording,
// keeps the gates, and runs backpropagation through time by hand: the elementwise work of a step
// in one pass, and the recurrent weights' gradient as one product over all steps.
#pragma once

#include <torch/torch.h>

namespace hideseek_hider {

// input_gates: [T, B, 3H], the input side of the gates (x W_ih^T + b_ih) in GRUCell's order
// (r, z, n); keep: [T, B], 0 where step t starts an episode (the state is zeroed before it), else
// 1; h0: [B, H], the state before step 0; weight_hh: [3H, H], bias_hh: [3H]. Returns the state
// after every step, [T, B, H]. Differentiable in input_gates, h0, weight_hh and bias_hh. fp32 CPU
// tensors take the fused path; anything else (another device or type) the same equations stepped
// by ATen operators under autograd. gru_test checks both against torch::nn::GRUCell.
torch::Tensor gruSequence(const torch::Tensor& input_gates, const torch::Tensor& keep, const torch::Tensor& h0,
                          const torch::Tensor& weight_hh, const torch::Tensor& bias_hh);

}  // namespace hideseek_hider
