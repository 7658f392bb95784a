#include "hideseek_hider/precision.h"

#include <ATen/autocast_mode.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#endif

// OpenBLAS's own query, found at run time when OpenBLAS is loaded (weak: absent otherwise).
extern "C" int openblas_get_parallel(void) __attribute__((weak));

namespace hideseek_hider {

std::string blasDescription() {
  if (!openblas_get_parallel) return "not OpenBLAS";
  switch (openblas_get_parallel()) {
    case 0:
      return "OpenBLAS, sequential";
    case 1:
      return "OpenBLAS with its own threads";
    default:
      return "OpenBLAS on OpenMP threads";
  }
}

PrecisionRequest parsePrecision(const std::string& text, const std::string& param) {
  if (text == "auto") return PrecisionRequest::kAuto;
  if (text == "fp32") return PrecisionRequest::kFp32;
  if (text == "bf16") return PrecisionRequest::kBf16;
  throw std::invalid_argument("parameter " + param + " must be auto, fp32 or bf16, got '" + text + "'");
}

const char* precisionName(Precision precision) { return precision == Precision::kBf16 ? "bf16" : "fp32"; }

CpuBf16Support detectCpuBf16() {
  CpuBf16Support s;
#if defined(__x86_64__) || defined(__i386__)
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  if (__get_cpuid_max(0, nullptr) < 7) return s;
  __cpuid_count(7, 0, eax, ebx, ecx, edx);
  s.amx_bf16 = (edx >> 22) & 1u;  // CPUID.(EAX=7,ECX=0):EDX[22] AMX-BF16
  const unsigned max_subleaf = eax;
  if (max_subleaf >= 1) {
    __cpuid_count(7, 1, eax, ebx, ecx, edx);
    s.avx512_bf16 = (eax >> 5) & 1u;  // CPUID.(EAX=7,ECX=1):EAX[5] AVX512_BF16
  }
  // The instructions are usable only where the OS saves the AVX-512 (and AMX tile) state.
  __cpuid(1, eax, ebx, ecx, edx);
  const bool osxsave = (ecx >> 27) & 1u;
  unsigned long long xcr0 = 0;
  if (osxsave) {
    unsigned lo = 0, hi = 0;
    __asm__("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
    xcr0 = (static_cast<unsigned long long>(hi) << 32) | lo;
  }
  const bool avx512_state = (xcr0 & 0xe6) == 0xe6;     // SSE, AVX, opmask, ZMM state
  const bool amx_state = (xcr0 & 0x60000) == 0x60000;  // XTILECFG, XTILEDATA
  s.avx512_bf16 = s.avx512_bf16 && avx512_state;
  s.amx_bf16 = s.amx_bf16 && amx_state;
#endif
  return s;
}

namespace {

constexpr double kAmxBf16FlopsPerCycle = 1024.0;

}  // namespace

double CpuPeak::gflops(Precision precision) const {
  if (precision == Precision::kBf16 && amx_bf16) return cores * ghz * kAmxBf16FlopsPerCycle;
  const double bf16 = precision == Precision::kBf16 && avx512_bf16 ? 2.0 : 1.0;
  return cores * ghz * (vector_bits / 32.0) * 2.0 * fma_units * bf16;
}

std::string CpuPeak::unit(Precision precision) const {
  if (precision == Precision::kBf16 && amx_bf16) return "AMX-BF16 tiles";
  if (precision == Precision::kBf16 && avx512_bf16) return "AVX512_BF16 FMA";
  return "FMA";
}

std::string CpuPeak::describe(Precision precision) const {
  char text[400];
  if (precision == Precision::kBf16 && amx_bf16) {
    std::snprintf(text, sizeof(text),
                  "AMX-BF16 tiles: %d cores x %.3f GHz (%s) x %.0f flops per cycle = %.1f GFLOP/s %s", cores, ghz,
                  clock_source.c_str(), kAmxBf16FlopsPerCycle, gflops(precision), precisionName(precision));
    return text;
  }
  std::snprintf(text, sizeof(text),
                "%s: %d cores x %.3f GHz (%s) x %d-bit FMA (%d fp32 lanes) x 2 flops x %d FMA units%s%s = %.1f GFLOP/s "
                "%s%s",
                unit(precision).c_str(), cores, ghz, clock_source.c_str(), vector_bits, vector_bits / 32, fma_units,
                zen4 ? " (Zen 4: a 512-bit FMA per cycle)" : "",
                precision == Precision::kBf16 && avx512_bf16 ? " x 2 (AVX512_BF16 pairs)" : "", gflops(precision),
                precisionName(precision),
                precision == Precision::kBf16 && !avx512_bf16 ? " (emulated: no native bf16 unit)" : "");
  return text;
}

CpuPeak cpuPeakFrom(const std::string& cpuinfo, double max_khz, int threads, int online_cpus, int fma_units) {
  CpuPeak p;
  p.cores = std::max(1, std::min(threads, online_cpus));
  std::istringstream in(cpuinfo);
  std::set<std::string> flags;
  double mhz = 0.0;
  std::string vendor;
  int family = -1;
  for (std::string line; std::getline(in, line);) {
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string key = line.substr(0, colon);
    key.erase(key.find_last_not_of(" \t") + 1);
    if (key == "cpu MHz") mhz = std::max(mhz, std::atof(line.c_str() + colon + 1));
    if (key == "vendor_id" && vendor.empty()) std::istringstream(line.substr(colon + 1)) >> vendor;
    if (key == "cpu family" && family < 0) family = std::atoi(line.c_str() + colon + 1);
    if (key == "flags" && flags.empty()) {
      std::istringstream words(line.substr(colon + 1));
      for (std::string w; words >> w;) flags.insert(w);
    }
  }
  if (flags.count("avx512f")) {
    p.vector_bits = 512;
  } else if (flags.count("avx2") && flags.count("fma")) {
    p.vector_bits = 256;
  }
  p.avx512_bf16 = flags.count("avx512_bf16") > 0;
  p.amx_bf16 = flags.count("amx_bf16") > 0;
  // Zen 4 (AMD family 19h with AVX-512) executes a 512-bit FMA as two 256-bit halves on its two
  // 256-bit pipes: one 512-bit FMA per cycle.
  p.zen4 = vendor == "AuthenticAMD" && family == 0x19 && p.vector_bits == 512;
  p.fma_units = fma_units > 0 ? fma_units : (p.zen4 ? 1 : 2);
  if (max_khz > 0.0) {
    p.ghz = max_khz / 1e6;
    p.clock_source = "cpufreq cpuinfo_max_freq";
  } else {
    p.ghz = mhz / 1e3;
    p.clock_source = "cpu MHz of /proc/cpuinfo";
  }
  return p;
}

CpuPeak detectCpuPeak(int threads) {
  std::ifstream info("/proc/cpuinfo");
  const std::string text((std::istreambuf_iterator<char>(info)), std::istreambuf_iterator<char>());
  double max_khz = 0.0;
  std::ifstream freq("/sys/devices/system/cpu/cpu0/cpufreq/cpuinfo_max_freq");
  if (!(freq >> max_khz)) max_khz = 0.0;
  const char* units = std::getenv("HIDESEEK_FMA_UNITS");
  const int fma_units = units && std::atoi(units) > 0 ? std::atoi(units) : 0;  // 0: from the CPU
  return cpuPeakFrom(text, max_khz, threads, static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN)), fma_units);
}

PrecisionChoice choosePrecision(PrecisionRequest request, torch::Device device, const CpuBf16Support& cpu) {
  const std::string where = device.is_cuda() ? "CUDA" : "CPU";
  const std::string native = cpu.amx_bf16 ? "AMX-BF16" : "AVX512_BF16";
  switch (request) {
    case PrecisionRequest::kFp32:
      return {Precision::kFp32, "fp32 as asked"};
    case PrecisionRequest::kBf16:
      if (device.is_cuda() || cpu.native()) return {Precision::kBf16, "bf16 as asked"};
      return {Precision::kBf16,
              "bf16 as asked, although this CPU has no native bf16 (emulated: expect it slower than fp32)"};
    case PrecisionRequest::kAuto:
      break;
  }
  if (device.is_cuda()) return {Precision::kFp32, "auto: fp32 on CUDA (bf16 is chosen automatically on CPU only)"};
  if (cpu.native()) return {Precision::kBf16, "auto: bf16, this CPU executes it natively (" + native + ")"};
  return {Precision::kFp32,
          "auto: fp32, this CPU has neither AVX512_BF16 nor AMX-BF16 (bf16 would be emulated and slower)"};
}

MemoryFormatRequest parseMemoryFormat(const std::string& text, const std::string& param) {
  if (text == "auto") return MemoryFormatRequest::kAuto;
  if (text == "channels_last") return MemoryFormatRequest::kChannelsLast;
  if (text == "nchw") return MemoryFormatRequest::kNchw;
  throw std::invalid_argument("parameter " + param + " must be auto, channels_last or nchw, got '" + text + "'");
}

MemoryFormatChoice chooseMemoryFormat(MemoryFormatRequest request, Precision precision, const CpuBf16Support& cpu) {
  switch (request) {
    case MemoryFormatRequest::kChannelsLast:
      return {MemoryFormat::kChannelsLast, "channels_last as asked"};
    case MemoryFormatRequest::kNchw:
      return {MemoryFormat::kNchw, "nchw as asked (the images copied into NCHW order before the encoder)"};
    case MemoryFormatRequest::kAuto:
      break;
  }
  // Channels-last everywhere (the measurements and the reasons are in the header's comment): faster
  // than NCHW through the trainer without native bf16, and in the standalone network on AMX-BF16. A
  // kind where NCHW measures faster in bf16 through make bench gets its branch here, with its figure.
  const std::string kind = cpu.amx_bf16 ? "AMX-BF16" : cpu.avx512_bf16 ? "AVX512_BF16" : "no native bf16";
  return {MemoryFormat::kChannelsLast, std::string("auto: channels_last (") + precisionName(precision) + ", CPU with " +
                                           kind + "; the images' own HWC layout, no copy)"};
}

AutocastScope::AutocastScope(Precision precision, torch::Device device) {
  if (precision != Precision::kBf16) return;
  active_ = true;
  cuda_ = device.is_cuda();
  if (cuda_) {
    was_enabled_ = at::autocast::is_enabled();
    previous_dtype_ = at::autocast::get_autocast_gpu_dtype();
    at::autocast::set_autocast_gpu_dtype(at::kBFloat16);
    at::autocast::set_enabled(true);
  } else {
    was_enabled_ = at::autocast::is_cpu_enabled();
    previous_dtype_ = at::autocast::get_autocast_cpu_dtype();
    at::autocast::set_autocast_cpu_dtype(at::kBFloat16);
    at::autocast::set_cpu_enabled(true);
  }
  at::autocast::increment_nesting();
}

AutocastScope::~AutocastScope() {
  if (!active_) return;
  // The cache of bf16 weight copies lives as long as the outermost autocast region.
  if (at::autocast::decrement_nesting() == 0) at::autocast::clear_cache();
  if (cuda_) {
    at::autocast::set_enabled(was_enabled_);
    at::autocast::set_autocast_gpu_dtype(previous_dtype_);
  } else {
    at::autocast::set_cpu_enabled(was_enabled_);
    at::autocast::set_autocast_cpu_dtype(previous_dtype_);
  }
}

}  // namespace hideseek_hider
