// The archive check before libtorch reads a checkpoint: real checkpoints pass; a file cut short,
// another zip, compressed or unknown entries, a lying directory and oversized entries are refused
// naming the file and the rule, before libtorch sees them.
#include "hideseek_hider/checkpoint_archive.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "hideseek_hider/checkpoint.h"
#include "hideseek_hider/hider_net.h"

using hideseek_hider::checkCheckpointBytes;

namespace {

std::vector<uint8_t> readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string refusal(const std::vector<uint8_t>& bytes, const hideseek_hider::CheckpointLimits& limits = {}) {
  try {
    checkCheckpointBytes(bytes.data(), bytes.size(), "test.pt", limits);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

// Offset of the end-of-directory record, and of the first directory entry.
size_t endOfDirectory(const std::vector<uint8_t>& b) {
  for (size_t at = b.size() - 22;; --at) {
    if (b[at] == 0x50 && b[at + 1] == 0x4b && b[at + 2] == 5 && b[at + 3] == 6) return at;
  }
}
uint32_t u32(const std::vector<uint8_t>& b, size_t at) {
  uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

std::vector<uint8_t> checkpoint() {
  const std::string path = ::testing::TempDir() + "/archive_test.pt";
  hideseek_hider::HiderNet net(84, 84);
  hideseek_hider::CheckpointInfo info;
  info.architecture = hideseek_hider::kArchitecture;
  info.image_height = info.image_width = 84;
  info.variant = "basic";
  hideseek_hider::saveCheckpoint(path, net, info);
  return readFile(path);
}

}  // namespace

TEST(CheckpointArchive, RealCheckpointsPass) {
  EXPECT_EQ(refusal(checkpoint()), "");
  EXPECT_EQ(refusal(readFile(HIDESEEK_POLICY_DIR "/basic.pt")), "");
}

TEST(CheckpointArchive, CutOrForeignFilesAreRefusedNamingTheFile) {
  const std::vector<uint8_t> good = checkpoint();
  for (const size_t keep : {size_t{0}, size_t{21}, size_t{1000}, good.size() / 2, good.size() - 1}) {
    const std::string why = refusal({good.begin(), good.begin() + keep});
    EXPECT_NE(why.find("checkpoint test.pt: "), std::string::npos) << keep << ": " << why;
  }
  std::vector<uint8_t> text(100, 'x');
  EXPECT_NE(refusal(text).find("not a zip archive"), std::string::npos);
}

TEST(CheckpointArchive, ALyingDirectoryIsRefused) {
  const std::vector<uint8_t> good = checkpoint();
  const size_t eocd = endOfDirectory(good);
  const size_t first = u32(good, eocd + 16);
  {  // an entry claiming 4 GB
    std::vector<uint8_t> b = good;
    const uint32_t huge = 0xF0000000u;
    std::memcpy(b.data() + first + 20, &huge, 4);
    std::memcpy(b.data() + first + 24, &huge, 4);
    EXPECT_NE(refusal(b).find("holds 4026531840 bytes"), std::string::npos) << refusal(b);
  }
  {  // compressed
    std::vector<uint8_t> b = good;
    b[first + 10] = 8;
    EXPECT_NE(refusal(b).find("is compressed (checkpoints store their records)"), std::string::npos) << refusal(b);
  }
  {  // a local header elsewhere than the directory says
    std::vector<uint8_t> b = good;
    const uint32_t shifted = u32(b, first + 42) + 7;
    std::memcpy(b.data() + first + 42, &shifted, 4);
    EXPECT_NE(refusal(b).find("no local header where the directory says"), std::string::npos) << refusal(b);
  }
  {  // a name no checkpoint holds (the first entry's name renamed in place)
    std::vector<uint8_t> b = good;
    const uint16_t name_len = static_cast<uint16_t>(b[first + 28] | b[first + 29] << 8);
    b[first + 46 + name_len - 1] = 'Z';
    EXPECT_NE(refusal(b), "");
  }
  {  // a ZIP64 marker
    std::vector<uint8_t> b = good;
    b[eocd + 10] = b[eocd + 11] = b[eocd + 8] = b[eocd + 9] = 0xFF;
    EXPECT_NE(refusal(b).find("ZIP64"), std::string::npos) << refusal(b);
  }
  hideseek_hider::CheckpointLimits small;
  small.max_file_bytes = 1000;
  EXPECT_NE(refusal(good, small).find("larger than 1000 bytes"), std::string::npos);
}

TEST(CheckpointArchive, LoadCheckpointChecksBeforeLibtorch) {
  std::vector<uint8_t> b = checkpoint();
  const size_t first = u32(b, endOfDirectory(b) + 16);
  b[first + 10] = 8;  // libtorch would try to read a compressed record
  const std::string path = ::testing::TempDir() + "/archive_test_bad.pt";
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), b.size());
  try {
    hideseek_hider::loadCheckpoint(path, 84, 84);
    FAIL() << "a compressed entry was loaded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": entry"), std::string::npos) << e.what();
  }
}

// checkpoint_fuzz's finding: libtorch 1.13 reads a tensor record shorter than its pickle declares
// past its end and crashes. The check compares every record with its tensor first.
TEST(CheckpointArchive, ARecordShorterThanItsTensorIsRefused) {
  const std::string why = refusal(readFile(HIDESEEK_CHECKPOINT_CORPUS "/policy_records_cut"));
  EXPECT_NE(why.find("tensor record data/2 holds 8 bytes, its tensor 24576"), std::string::npos) << why;
  EXPECT_NE(refusal(readFile(HIDESEEK_CHECKPOINT_CORPUS "/policy_no_records")).find("data/0 is missing"),
            std::string::npos);
}

// checkpoint_fuzz's second finding: libtorch 1.13's TorchScript parser (ScriptTypeParser) crashes
// on crafted source in an archive's code/ entries, which it compiles on load. Our checkpoints hold
// only class declarations there, so every line must be one of their forms.
TEST(CheckpointArchive, TorchScriptOtherThanDeclarationsIsRefused) {
  const std::string why = refusal(readFile(HIDESEEK_CHECKPOINT_CORPUS "/finding_torchscript_parser_crash"));
  EXPECT_NE(why.find("holds TorchScript that is no checkpoint's declaration"), std::string::npos) << why;
}
