// The replay side of a fuzz target (issue #49). A fuzz target is one file defining
// LLVMFuzzerTestOneInput; built with clang's -fsanitize=fuzzer it is a libFuzzer binary (make fuzz),
// linked with this file (hideseek_fuzz_target in hideseek_fuzz.cmake), a gtest that feeds it every
// file of its committed corpus (HIDESEEK_FUZZ_CORPUS) once, in name order: make test's deterministic
// replay. A finding aborts the target, which fails the test. A source of the tests, not a header:
// nothing of it is installed with the package's headers.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

TEST(FuzzCorpus, EveryCommittedInputRunsWithoutAFinding) {
  std::vector<std::filesystem::path> inputs;
  for (const auto& entry : std::filesystem::directory_iterator(HIDESEEK_FUZZ_CORPUS)) {
    if (entry.is_regular_file()) inputs.push_back(entry.path());
  }
  std::sort(inputs.begin(), inputs.end());
  ASSERT_GE(inputs.size(), 3u) << "the corpus " << HIDESEEK_FUZZ_CORPUS << " holds fewer than 3 inputs";
  for (const auto& path : inputs) {
    std::ifstream in(path, std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    SCOPED_TRACE(path.string());
    EXPECT_EQ(LLVMFuzzerTestOneInput(bytes.data(), bytes.size()), 0);
  }
}
