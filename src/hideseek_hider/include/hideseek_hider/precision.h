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
  bool amx_bf16 = false;  // the "amx_bf16" flag: oneDNN runs bf16 convolutions and products on AMX tiles
  // The unit the kernels use: fp32, and bf16 without native support, run on the FMA units:
  // cores x GHz x (vector_bits / 32 lanes) x 2 (multiply and add) x fma_units [x 2 in bf16 with
  // AVX512_BF16 pairs]. bf16 with AMX-BF16 runs on the tiles: cores x GHz x 1024 flops per cycle
  // (one TDPBF16PS, 16 x 16 x 32 multiply-adds, every 16 cycles: Intel's 1024 bf16 ops per cycle
  // and core), which oneDNN's brgemm kernels use (ONEDNN_VERBOSE names avx512_core_amx_bf16).
  double gflops(Precision precision) const;
  std::string unit(Precision precision) const;      // "AMX-BF16 tiles", "AVX512_BF16 FMA", "FMA"
  std::string describe(Precision precision) const;  // the unit and the formula with its numbers
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

// The memory layout of the encoder's images and activations. The world sends HWC bytes: viewed as
// [B, 3, H, W] they are channels-last (NHWC) without a copy, and oneDNN follows its input's layout,
// so every convolution, forward and backward, runs NHWC. `nchw` copies the images into NCHW order
// first, the layout a network built from NCHW tensors would run in; it is there to measure the
// difference (make bench prints both). The convolution weights keep their default layout in both:
// storing them channels-last too gave bitwise the same logits and gradients and no speed
// (docs/performance.md, "Memory format").
enum class MemoryFormat { kChannelsLast, kNchw };
enum class MemoryFormatRequest { kAuto, kChannelsLast, kNchw };
// Parses "auto", "channels_last" or "nchw"; throws std::invalid_argument naming `param` and the choices.
MemoryFormatRequest parseMemoryFormat(const std::string& text, const std::string& param);
struct MemoryFormatChoice {
  MemoryFormat format = MemoryFormat::kChannelsLast;
  std::string reason;
};
// The one rule for the layout, with the measurements behind it (docs/performance.md, "Memory
// format"): `auto` is channels-last in every precision and on every CPU. Through the project's
// trainer on a 2-core Intel Xeon without native bf16, NCHW made the fp32 floor 1.09x slower
// (whole-process wall time, train_floor_bench, median of 5 pairs). On an Intel Xeon with AMX-BF16
// (oneDNN's AMX kernels; this network in Python, PyTorch 2.11, 2 threads, median of 6 pairs), the
// images' HWC view ran 1.42x the samples/s of NCHW images in bf16 and 1.10x in fp32, and storing
// the weights channels-last too gave 0.97x and 1.01x. fp32 must stay in the layout it always ran in
// anyway: it is the evaluation's precision, NCHW changes its sums (logits by about 1e-8), and a
// shipped policy re-evaluates byte-identically only in its own layout.
MemoryFormatChoice chooseMemoryFormat(MemoryFormatRequest request, Precision precision, const CpuBf16Support& cpu);

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
