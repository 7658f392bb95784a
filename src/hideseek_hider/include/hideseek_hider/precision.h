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

// The CPU's peak arithmetic rate, from what the machine says of itself: the widest FMA vectors in
// /proc/cpuinfo's flags (avx512f: 512 bits; avx2 and fma: 256; otherwise 128), the clock
// (cpufreq's cpuinfo_max_freq where the kernel has it, else the highest "cpu MHz", which a
// virtual machine reports as its nominal clock and a boosting host can exceed), the cores the work
// runs on (its threads, at most the CPUs online; a virtual CPU may be a hyperthread), and FMA
// units per core, which no flag tells: 2 (every x86 server core since Haswell and Zen 2 has two
// FMA pipes), except on Zen 4 (AMD family 19h with AVX-512), which executes a 512-bit FMA as two
// 256-bit halves: one 512-bit FMA per cycle. HIDESEEK_FMA_UNITS overrides either. bf16 doubles the
// rate where AVX512_BF16 dot products exist (AMX tiles are not counted).
struct CpuPeak {
  int cores = 1;
  double ghz = 0.0;
  std::string clock_source;
  int vector_bits = 128;
  int fma_units = 2;
  bool zen4 = false;  // AMD family 19h with AVX-512: fma_units 1 unless overridden
  bool avx512_bf16 = false;
  // cores x GHz x (vector_bits / 32 lanes) x 2 (multiply and add) x fma_units [x 2 in bf16].
  double gflops(Precision precision) const;
  std::string describe(Precision precision) const;  // the formula with its numbers
};
// From /proc/cpuinfo's text, cpufreq's maximum in kHz (0: none), the work's threads and the
// online CPUs, and the FMA units per core (0: from the CPU, as above).
CpuPeak cpuPeakFrom(const std::string& cpuinfo, double max_khz, int threads, int online_cpus, int fma_units);
CpuPeak detectCpuPeak(int threads);

// Which BLAS libtorch's fully connected layers run on, for logs: "OpenBLAS on OpenMP threads"
// (the build the training programs link, see the hider's CMakeLists.txt), "OpenBLAS with its own
// threads", "OpenBLAS, sequential", or "not OpenBLAS".
std::string blasDescription();

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
