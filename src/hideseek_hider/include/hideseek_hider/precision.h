// Numeric precision of the hider network's forward and backward passes. bf16 runs under
// autocast: convolutions and matrix products in bfloat16, while the weights, Adam's state, GAE,
// the losses and every checkpoint stay fp32, so a checkpoint works in either precision.
#pragma once

#include <torch/torch.h>

#include <string>

namespace hideseek_hider {

enum class Precision { kFp32, kBf16 };
// What the user asks for: `auto` picks bf16 only where the hardware executes it natively.
enum class PrecisionRequest { kAuto, kFp32, kBf16 };

// Parses "auto", "fp32" or "bf16"; throws std::invalid_argument naming `param` and the choices.
PrecisionRequest parsePrecision(const std::string& text, const std::string& param);
const char* precisionName(Precision precision);

// The CPU's native bfloat16 instructions (x86 CPUID): AVX512_BF16 dot products, AMX tiles.
struct CpuBf16Support {
  bool avx512_bf16 = false;
  bool amx_bf16 = false;
  bool native() const { return avx512_bf16 || amx_bf16; }
};
CpuBf16Support detectCpuBf16();

// The precision chosen and why, for the node's log.
struct PrecisionChoice {
  Precision precision = Precision::kFp32;
  std::string reason;
};
// On CPU without native bf16, bf16 is emulated by oneDNN and slower than fp32, so `auto` keeps
// fp32 there; an explicit `bf16` is honoured (and the reason says it is emulated).
PrecisionChoice choosePrecision(PrecisionRequest request, torch::Device device, const CpuBf16Support& cpu);

// Autocast to bf16 for the lifetime of the scope on the given device (no-op for fp32).
// Autocast state is thread-local: the scope covers the calling thread only.
class AutocastScope {
 public:
  AutocastScope(Precision precision, torch::Device device);
  ~AutocastScope();
  AutocastScope(const AutocastScope&) = delete;
  AutocastScope& operator=(const AutocastScope&) = delete;

 private:
  bool active_ = false;
  bool cuda_ = false;
  bool was_enabled_ = false;
  at::ScalarType previous_dtype_ = at::kBFloat16;
};

}  // namespace hideseek_hider
