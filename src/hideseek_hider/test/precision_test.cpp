#include "hideseek_hider/precision.h"

#include <ATen/autocast_mode.h>
#include <gtest/gtest.h>

#include "hideseek_hider/checkpoint.h"
#include "hideseek_hider/hider_net.h"

namespace hideseek_hider {

TEST(Precision, ParsesTheThreeChoicesAndNamesTheParameterOtherwise) {
  EXPECT_EQ(parsePrecision("auto", "~precision"), PrecisionRequest::kAuto);
  EXPECT_EQ(parsePrecision("fp32", "~precision"), PrecisionRequest::kFp32);
  EXPECT_EQ(parsePrecision("bf16", "~precision"), PrecisionRequest::kBf16);
  try {
    parsePrecision("fp16", "/hider/precision");
    FAIL() << "fp16 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("/hider/precision"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("auto, fp32 or bf16"), std::string::npos) << e.what();
  }
}

TEST(Precision, AutoPicksBf16OnlyWhereTheCpuHasItNatively) {
  const CpuBf16Support none{}, avx512{true, false}, amx{false, true};
  EXPECT_EQ(choosePrecision(PrecisionRequest::kAuto, torch::kCPU, none).precision, Precision::kFp32);
  EXPECT_EQ(choosePrecision(PrecisionRequest::kAuto, torch::kCPU, avx512).precision, Precision::kBf16);
  EXPECT_EQ(choosePrecision(PrecisionRequest::kAuto, torch::kCPU, amx).precision, Precision::kBf16);
  // The reason is what the node logs: it says which feature decided.
  EXPECT_NE(choosePrecision(PrecisionRequest::kAuto, torch::kCPU, amx).reason.find("AMX-BF16"), std::string::npos);
  EXPECT_NE(choosePrecision(PrecisionRequest::kAuto, torch::kCPU, none).reason.find("neither"), std::string::npos);
  // An explicit choice is honoured either way; on an emulating CPU the reason warns.
  EXPECT_EQ(choosePrecision(PrecisionRequest::kFp32, torch::kCPU, avx512).precision, Precision::kFp32);
  const PrecisionChoice forced = choosePrecision(PrecisionRequest::kBf16, torch::kCPU, none);
  EXPECT_EQ(forced.precision, Precision::kBf16);
  EXPECT_NE(forced.reason.find("emulated"), std::string::npos);
}

TEST(CpuPeak, ReadsVectorWidthClockAndCoresFromTheMachinesOwnDescription) {
  const std::string zen3 =
      "processor\t: 0\ncpu MHz\t\t: 2445.404\nflags\t\t: fpu sse sse2 avx fma avx2\n\n"
      "processor\t: 1\ncpu MHz\t\t: 2445.404\nflags\t\t: fpu sse sse2 avx fma avx2\n";
  const CpuPeak p = cpuPeakFrom(zen3, 0.0, 2, 2, 2);
  EXPECT_EQ(p.vector_bits, 256);
  EXPECT_EQ(p.cores, 2);
  EXPECT_NEAR(p.ghz, 2.445404, 1e-9);
  // 2 cores x 2.445 GHz x 8 lanes x 2 flops x 2 FMA units; bf16 is no faster without AVX512_BF16.
  EXPECT_NEAR(p.gflops(Precision::kFp32), 2 * 2.445404 * 8 * 2 * 2, 1e-9);
  EXPECT_DOUBLE_EQ(p.gflops(Precision::kBf16), p.gflops(Precision::kFp32));
  EXPECT_NE(p.describe(Precision::kFp32).find("cpu MHz"), std::string::npos) << p.describe(Precision::kFp32);
  // More threads than CPUs count the CPUs; cpufreq's maximum wins over cpu MHz.
  const std::string zen4 = "cpu MHz : 2000.0\nflags : avx2 fma avx512f avx512_bf16\n";
  const CpuPeak q = cpuPeakFrom(zen4, 3.7e6, 8, 4, 1);
  EXPECT_EQ(q.vector_bits, 512);
  EXPECT_EQ(q.cores, 4);
  EXPECT_DOUBLE_EQ(q.ghz, 3.7);
  EXPECT_DOUBLE_EQ(q.gflops(Precision::kFp32), 4 * 3.7 * 16 * 2 * 1);
  EXPECT_DOUBLE_EQ(q.gflops(Precision::kBf16), 2 * q.gflops(Precision::kFp32));
  EXPECT_NE(q.describe(Precision::kBf16).find("cpuinfo_max_freq"), std::string::npos);
  // Zen 4 (AMD family 19h with AVX-512) counts one 512-bit FMA per cycle unless told otherwise;
  // Zen 3 (family 19h without AVX-512) and Intel keep two.
  const std::string epyc9004 =
      "vendor_id\t: AuthenticAMD\ncpu family\t: 25\ncpu MHz\t\t: 2596.0\nflags\t\t: avx2 fma avx512f avx512_bf16\n";
  const CpuPeak z = cpuPeakFrom(epyc9004, 0.0, 2, 2, 0);
  EXPECT_TRUE(z.zen4);
  EXPECT_EQ(z.fma_units, 1);
  EXPECT_NEAR(z.gflops(Precision::kBf16), 2 * 2.596 * 16 * 2 * 1 * 2, 1e-9);  // 332.3
  EXPECT_NE(z.describe(Precision::kBf16).find("Zen 4"), std::string::npos);
  EXPECT_EQ(cpuPeakFrom(epyc9004, 0.0, 2, 2, 2).fma_units, 2);  // HIDESEEK_FMA_UNITS wins
  const std::string milan = "vendor_id : AuthenticAMD\ncpu family : 25\nflags : avx2 fma\n";
  EXPECT_EQ(cpuPeakFrom(milan, 0.0, 2, 2, 0).fma_units, 2);
  const std::string intel = "vendor_id : GenuineIntel\ncpu family : 6\nflags : avx2 fma avx512f\n";
  EXPECT_EQ(cpuPeakFrom(intel, 0.0, 2, 2, 0).fma_units, 2);
  // Without AVX2 and FMA, 128-bit vectors.
  EXPECT_EQ(cpuPeakFrom("flags : sse sse2 avx\n", 0.0, 1, 1, 2).vector_bits, 128);
}

// Where oneDNN runs bf16 on AMX tiles, the peak is the tiles', an order of magnitude above the
// FMA units': a fraction of the FMA peak would read as 3x the machine's limit there.
TEST(CpuPeak, Bf16OnAnAmxCpuCountsTheTilesAndSaysSo) {
  const std::string spr =
      "vendor_id : GenuineIntel\ncpu family : 6\ncpu MHz : 2000.0\n"
      "flags : avx2 fma avx512f avx512_bf16 amx_bf16 amx_tile amx_int8\n";
  const CpuPeak p = cpuPeakFrom(spr, 0.0, 2, 2, 0);
  EXPECT_TRUE(p.amx_bf16);
  EXPECT_DOUBLE_EQ(p.gflops(Precision::kBf16), 2 * 2.0 * 1024);  // 4,096 GFLOP/s
  EXPECT_DOUBLE_EQ(p.gflops(Precision::kFp32), 2 * 2.0 * 16 * 2 * 2);
  EXPECT_GT(p.gflops(Precision::kBf16), 10 * p.gflops(Precision::kFp32));
  EXPECT_EQ(p.unit(Precision::kBf16), "AMX-BF16 tiles");
  EXPECT_EQ(p.unit(Precision::kFp32), "FMA");
  EXPECT_NE(p.describe(Precision::kBf16).find("AMX-BF16 tiles"), std::string::npos) << p.describe(Precision::kBf16);
  // Without AMX the bf16 unit is the AVX512_BF16 pairs, and without those bf16 is emulated.
  const CpuPeak q = cpuPeakFrom("flags : avx2 fma avx512f avx512_bf16\n", 0.0, 2, 2, 2);
  EXPECT_EQ(q.unit(Precision::kBf16), "AVX512_BF16 FMA");
  const CpuPeak r = cpuPeakFrom("flags : avx2 fma avx512f\n", 0.0, 2, 2, 2);
  EXPECT_NE(r.describe(Precision::kBf16).find("emulated"), std::string::npos) << r.describe(Precision::kBf16);
}

TEST(MemoryFormat, ParsesTheThreeChoicesAndNamesTheParameterOtherwise) {
  EXPECT_EQ(parseMemoryFormat("auto", "~memory_format"), MemoryFormatRequest::kAuto);
  EXPECT_EQ(parseMemoryFormat("channels_last", "~memory_format"), MemoryFormatRequest::kChannelsLast);
  EXPECT_EQ(parseMemoryFormat("nchw", "~memory_format"), MemoryFormatRequest::kNchw);
  try {
    parseMemoryFormat("nhwc", "/hider/memory_format");
    FAIL() << "nhwc accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("/hider/memory_format"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("auto, channels_last or nchw"), std::string::npos) << e.what();
  }
}

// The rule: channels-last on every CPU kind and in every precision measured; an explicit choice wins.
TEST(MemoryFormat, AutoIsChannelsLastEverywhereMeasuredAndAChoiceIsHonoured) {
  const CpuBf16Support none{}, avx512{true, false}, amx{false, true};
  for (const CpuBf16Support& cpu : {none, avx512, amx}) {
    for (const Precision p : {Precision::kFp32, Precision::kBf16}) {
      EXPECT_EQ(chooseMemoryFormat(MemoryFormatRequest::kAuto, p, cpu).format, MemoryFormat::kChannelsLast);
      EXPECT_EQ(chooseMemoryFormat(MemoryFormatRequest::kNchw, p, cpu).format, MemoryFormat::kNchw);
    }
  }
  EXPECT_NE(chooseMemoryFormat(MemoryFormatRequest::kAuto, Precision::kBf16, amx).reason.find("AMX-BF16"),
            std::string::npos);
}

// The layout changes where the numbers sit, not what the network computes: channels-last is what a
// network always ran (evaluations stay byte-identical), and NCHW agrees with it to rounding.
TEST(MemoryFormat, ChannelsLastIsTheDefaultAndNchwAgreesWithItToRounding) {
  torch::manual_seed(11);
  HiderNet net(84, 84);
  EXPECT_EQ(net->memoryFormat(), MemoryFormat::kChannelsLast);
  const torch::Tensor images = torch::randint(0, 256, {8, 84, 84, 3}, torch::kUInt8);
  const HiderOutput channels_last = net->forward(images);
  net->setMemoryFormat(MemoryFormat::kNchw);
  const HiderOutput nchw = net->forward(images);
  EXPECT_TRUE(torch::allclose(channels_last.logits, nchw.logits, 1e-5, 1e-6));
  EXPECT_TRUE(torch::allclose(channels_last.value, nchw.value, 1e-5, 1e-6));
  EXPECT_TRUE(torch::allclose(channels_last.features, nchw.features, 1e-5, 1e-6));
}

TEST(Precision, AutocastScopeRestoresTheThreadsStateWhenItEnds) {
  ASSERT_FALSE(at::autocast::is_cpu_enabled());
  {
    const AutocastScope scope(Precision::kBf16, torch::kCPU);
    EXPECT_TRUE(at::autocast::is_cpu_enabled());
    EXPECT_EQ(at::autocast::get_autocast_cpu_dtype(), at::kBFloat16);
    const torch::Tensor y = torch::matmul(torch::ones({2, 3}), torch::ones({3, 2}));
    EXPECT_EQ(y.scalar_type(), at::kBFloat16);
  }
  EXPECT_FALSE(at::autocast::is_cpu_enabled());
  {
    const AutocastScope scope(Precision::kFp32, torch::kCPU);
    EXPECT_FALSE(at::autocast::is_cpu_enabled());
  }
}

// bf16 changes the arithmetic, never what is stored: outputs are fp32, the weights stay fp32
// through a backward pass and an Adam step, and the checkpoint loads into an fp32 network.
TEST(Precision, Bf16NetworkKeepsFp32WeightsGradientsAndCheckpoints) {
  torch::manual_seed(5);
  HiderNet net(36, 36);
  net->setPrecision(Precision::kBf16);
  const torch::Tensor images = torch::randint(0, 256, {4, 36, 36, 3}, torch::kUInt8);
  const HiderOutput out = net->forward(images);
  EXPECT_EQ(out.logits.scalar_type(), torch::kFloat32);
  EXPECT_EQ(out.value.scalar_type(), torch::kFloat32);
  EXPECT_EQ(out.features.scalar_type(), torch::kFloat32);
  torch::optim::Adam adam(net->parameters(), torch::optim::AdamOptions(1e-3));
  (out.logits.pow(2).mean() + out.value.pow(2).mean()).backward();
  adam.step();
  for (const auto& p : net->named_parameters()) {
    EXPECT_EQ(p.value().scalar_type(), torch::kFloat32) << p.key();
    ASSERT_TRUE(p.value().grad().defined()) << p.key();
    EXPECT_EQ(p.value().grad().scalar_type(), torch::kFloat32) << p.key();
  }
  const std::string path = testing::TempDir() + "bf16_trained.pt";
  saveCheckpoint(path, net, {kArchitecture, 36, 36, "basic", 4}, &adam);
  HiderNet fp32 = loadCheckpoint(path, 36, 36);
  EXPECT_EQ(fp32->precision(), Precision::kFp32);
  for (const auto& p : fp32->named_parameters()) {
    EXPECT_TRUE(torch::equal(p.value(), net->named_parameters()[p.key()])) << p.key();
  }
  // The two precisions compute nearly the same function.
  const torch::Tensor a = torch::softmax(net->forward(images).logits, 1);
  const torch::Tensor b = torch::softmax(fp32->forward(images).logits, 1);
  EXPECT_LT((a - b).abs().max().item<double>(), 0.02);
}

}  // namespace hideseek_hider
