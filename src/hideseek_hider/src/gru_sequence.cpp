#include "hideseek_hider/gru_sequence.h"

#include <ATen/Parallel.h>

#include <cmath>
#include <vector>

namespace hideseek_hider {

namespace {

using torch::autograd::AutogradContext;
using torch::autograd::variable_list;

inline float sigmoid(float x) { return 1.0f / (1.0f + std::exp(-x)); }

// Rows [begin, end) of a [B, ...] batch, in chunks the intra-op threads share.
template <typename F>
void forRows(int64_t rows, int64_t columns, const F& f) {
  // At least about 4k elements a thread: below that a second thread costs more than it saves.
  const int64_t grain = std::max<int64_t>(1, 4096 / std::max<int64_t>(columns, 1));
  at::parallel_for(0, rows, grain, f);
}

class GruSequenceFunction : public torch::autograd::Function<GruSequenceFunction> {
 public:
  static torch::Tensor forward(AutogradContext* ctx, const torch::Tensor& input_gates, const torch::Tensor& keep,
                               const torch::Tensor& h0, const torch::Tensor& weight_hh, const torch::Tensor& bias_hh) {
    const int64_t steps = input_gates.size(0), batch = input_gates.size(1), hidden = h0.size(1);
    const torch::Tensor gi = input_gates.contiguous(), kp = keep.contiguous();
    const torch::Tensor w_t = weight_hh.t();
    const auto opts = input_gates.options();
    torch::Tensor states = torch::empty({steps, batch, hidden}, opts);
    torch::Tensor masked = torch::empty({steps, batch, hidden}, opts);     // each step's state after the reset
    torch::Tensor gates = torch::empty({steps, batch, 3 * hidden}, opts);  // r, z, n after their activations
    torch::Tensor hidden_n = torch::empty({steps, batch, hidden}, opts);   // the recurrent side of n
    torch::Tensor hg = torch::empty({batch, 3 * hidden}, opts);
    torch::Tensor h = h0.contiguous();
    for (int64_t t = 0; t < steps; ++t) {
      const float* hp = h.data_ptr<float>();
      const float* kt = kp.data_ptr<float>() + t * batch;
      float* mt = masked.data_ptr<float>() + t * batch * hidden;
      for (int64_t i = 0; i < batch * hidden; ++i) mt[i] = hp[i] * kt[i / hidden];
      at::addmm_out(hg, bias_hh, masked[t], w_t);
      const float* git = gi.data_ptr<float>() + t * batch * 3 * hidden;
      const float* hgp = hg.data_ptr<float>();
      float* gt = gates.data_ptr<float>() + t * batch * 3 * hidden;
      float* hnt = hidden_n.data_ptr<float>() + t * batch * hidden;
      float* st = states.data_ptr<float>() + t * batch * hidden;
      forRows(batch, 3 * hidden, [&](int64_t begin, int64_t end) {
        for (int64_t b = begin; b < end; ++b) {
          const float* x = git + b * 3 * hidden;
          const float* y = hgp + b * 3 * hidden;
          float* g = gt + b * 3 * hidden;
          for (int64_t j = 0; j < hidden; ++j) {
            const float r = sigmoid(x[j] + y[j]);
            const float z = sigmoid(x[hidden + j] + y[hidden + j]);
            const float hn = y[2 * hidden + j];
            const float n = std::tanh(x[2 * hidden + j] + r * hn);
            const float m = mt[b * hidden + j];
            g[j] = r;
            g[hidden + j] = z;
            g[2 * hidden + j] = n;
            hnt[b * hidden + j] = hn;
            st[b * hidden + j] = n + z * (m - n);
          }
        }
      });
      h = states[t];
    }
    ctx->saved_data["keep"] = kp;
    ctx->saved_data["masked"] = masked;
    ctx->saved_data["gates"] = gates;
    ctx->saved_data["hidden_n"] = hidden_n;
    ctx->save_for_backward({weight_hh});  // as a saved variable: changed in place before backward() is an error
    return states;
  }

  static variable_list backward(AutogradContext* ctx, variable_list grad_outputs) {
    const torch::Tensor kp = ctx->saved_data["keep"].toTensor();
    const torch::Tensor masked = ctx->saved_data["masked"].toTensor();
    const torch::Tensor gates = ctx->saved_data["gates"].toTensor();
    const torch::Tensor hidden_n = ctx->saved_data["hidden_n"].toTensor();
    const torch::Tensor weight_hh = ctx->get_saved_variables()[0];
    const int64_t steps = masked.size(0), batch = masked.size(1), hidden = masked.size(2);
    const auto opts = masked.options();
    const torch::Tensor grad =
        grad_outputs[0].defined() ? grad_outputs[0].contiguous() : torch::zeros({steps, batch, hidden}, opts);
    torch::Tensor d_input = torch::empty({steps, batch, 3 * hidden}, opts);   // of the input side of the gates
    torch::Tensor d_hidden = torch::empty({steps, batch, 3 * hidden}, opts);  // of the recurrent side
    torch::Tensor carry = torch::zeros({batch, hidden}, opts);  // dL/d(state after step t) from later steps
    torch::Tensor d_masked = torch::empty({batch, hidden}, opts);
    for (int64_t t = steps - 1; t >= 0; --t) {
      const float* gt = gates.data_ptr<float>() + t * batch * 3 * hidden;
      const float* hnt = hidden_n.data_ptr<float>() + t * batch * hidden;
      const float* mt = masked.data_ptr<float>() + t * batch * hidden;
      const float* dst = grad.data_ptr<float>() + t * batch * hidden;
      const float* cp = carry.data_ptr<float>();
      float* dit = d_input.data_ptr<float>() + t * batch * 3 * hidden;
      float* dht = d_hidden.data_ptr<float>() + t * batch * 3 * hidden;
      float* dm = d_masked.data_ptr<float>();
      forRows(batch, 3 * hidden, [&](int64_t begin, int64_t end) {
        for (int64_t b = begin; b < end; ++b) {
          const float* g = gt + b * 3 * hidden;
          float* di = dit + b * 3 * hidden;
          float* dh = dht + b * 3 * hidden;
          for (int64_t j = 0; j < hidden; ++j) {
            const int64_t k = b * hidden + j;
            const float r = g[j], z = g[hidden + j], n = g[2 * hidden + j];
            const float d = dst[k] + cp[k];
            const float dn = d * (1.0f - z) * (1.0f - n * n);   // through tanh
            const float dz = d * (mt[k] - n) * z * (1.0f - z);  // through the sigmoid
            const float dr = dn * hnt[k] * r * (1.0f - r);
            di[j] = dr;
            di[hidden + j] = dz;
            di[2 * hidden + j] = dn;
            dh[j] = dr;
            dh[hidden + j] = dz;
            dh[2 * hidden + j] = dn * r;
            dm[k] = d * z;
          }
        }
      });
      d_masked.addmm_(d_hidden[t], weight_hh);
      const float* kt = kp.data_ptr<float>() + t * batch;
      float* c = carry.data_ptr<float>();
      for (int64_t i = 0; i < batch * hidden; ++i) c[i] = dm[i] * kt[i / hidden];
    }
    const torch::Tensor flat = d_hidden.view({steps * batch, 3 * hidden});
    const torch::Tensor d_weight = flat.t().mm(masked.view({steps * batch, hidden}));
    const torch::Tensor d_bias = flat.sum(0);
    return {d_input, torch::Tensor(), carry, d_weight, d_bias};
  }
};

// The same equations stepped by ATen operators under autograd: the path off the CPU.
torch::Tensor gruSequenceByOperators(const torch::Tensor& input_gates, const torch::Tensor& keep,
                                     const torch::Tensor& h0, const torch::Tensor& weight_hh,
                                     const torch::Tensor& bias_hh) {
  const std::vector<torch::Tensor> in = input_gates.chunk(3, 2);  // 3 x [T, B, H]
  const torch::Tensor k = keep.unsqueeze(2);                      // [T, B, 1]
  torch::Tensor h = h0;
  std::vector<torch::Tensor> states;
  states.reserve(input_gates.size(0));
  for (int64_t t = 0; t < input_gates.size(0); ++t) {
    h = h * k[t];
    const std::vector<torch::Tensor> hg = torch::nn::functional::linear(h, weight_hh, bias_hh).chunk(3, 1);
    const torch::Tensor reset = torch::sigmoid(in[0][t] + hg[0]);
    const torch::Tensor update = torch::sigmoid(in[1][t] + hg[1]);
    const torch::Tensor candidate = torch::tanh(in[2][t] + reset * hg[2]);
    h = candidate + update * (h - candidate);
    states.push_back(h);
  }
  return torch::stack(states);
}

}  // namespace

torch::Tensor gruSequence(const torch::Tensor& input_gates, const torch::Tensor& keep, const torch::Tensor& h0,
                          const torch::Tensor& weight_hh, const torch::Tensor& bias_hh) {
  TORCH_CHECK(input_gates.dim() == 3 && input_gates.size(2) == 3 * h0.size(1), "input_gates must be [T, B, ",
              3 * h0.size(1), "], got ", input_gates.sizes());
  TORCH_CHECK(keep.dim() == 2 && keep.size(0) == input_gates.size(0) && keep.size(1) == input_gates.size(1),
              "keep must be [T, B], got ", keep.sizes());
  TORCH_CHECK(h0.dim() == 2 && h0.size(0) == input_gates.size(1), "h0 must be [B, H], got ", h0.sizes());
  const bool fused = input_gates.device().is_cpu() && input_gates.scalar_type() == torch::kFloat32 &&
                     keep.scalar_type() == torch::kFloat32 && h0.scalar_type() == torch::kFloat32 &&
                     weight_hh.scalar_type() == torch::kFloat32 && bias_hh.scalar_type() == torch::kFloat32;
  if (!fused) return gruSequenceByOperators(input_gates, keep, h0, weight_hh, bias_hh);
  return GruSequenceFunction::apply(input_gates, keep, h0, weight_hh, bias_hh);
}

}  // namespace hideseek_hider
