#include "hideseek_hider/teleop.h"

#include <gtest/gtest.h>

namespace hideseek_hider {
namespace {

TEST(TeleopKeys, LettersAndArrowKeysBecomeActions) {
  TeleopKeys k;
  EXPECT_EQ(k.feed("w").action, 1);
  EXPECT_EQ(k.feed("s").action, 2);
  EXPECT_EQ(k.feed("a").action, 3);
  EXPECT_EQ(k.feed("D").action, 4);
  EXPECT_EQ(k.feed(" ").action, 0);
  EXPECT_EQ(k.feed("\x1b[A").action, 1);  // up
  EXPECT_EQ(k.feed("\x1b[B").action, 2);  // down
  EXPECT_EQ(k.feed("\x1b[D").action, 3);  // left
  EXPECT_EQ(k.feed("\x1b[C").action, 4);  // right
  EXPECT_FALSE(k.feed("z").action);
  EXPECT_EQ(k.feed("wwd").action, 4);  // the last key of a burst counts
}

TEST(TeleopKeys, AnArrowSplitAcrossReadsStillCounts) {
  TeleopKeys k;
  EXPECT_FALSE(k.feed("\x1b").action);
  EXPECT_FALSE(k.feed("[").action);
  EXPECT_EQ(k.feed("C").action, 4);
  EXPECT_EQ(k.feed("w").action, 1);  // nothing left pending
}

TEST(TeleopKeys, ModifiedArrowsAndALoneEscapeDoNotMisfire) {
  TeleopKeys k;
  EXPECT_EQ(k.feed("\x1b[1;5D").action, 3);  // Ctrl+left is left, not a stray 'D' (turn right)
  EXPECT_EQ(k.feed("\x1bOA").action, 1);     // application-mode up
  EXPECT_TRUE(k.feed("\x1bq").quit);         // Esc then q: the q still quits
  EXPECT_EQ(k.feed("\x1bw").action, 1);
}

TEST(TeleopKeys, QAndCtrlCQuit) {
  TeleopKeys k;
  EXPECT_TRUE(k.feed("q").quit);
  EXPECT_TRUE(k.feed("\x03").quit);
  EXPECT_FALSE(k.feed("w").quit);
}

TEST(TeleopAction, AHeldKeyLastsUntilItsRepeatsStop) {
  TeleopAction a(0.7);
  EXPECT_EQ(a.current(0.0), 0);
  a.press(1, 10.0);
  EXPECT_EQ(a.current(10.5), 1);
  a.press(1, 10.6);  // auto-repeat
  EXPECT_EQ(a.current(11.2), 1);
  EXPECT_EQ(a.current(11.4), 0);  // released
  TeleopAction sticky(0.0);
  sticky.press(3, 1.0);
  EXPECT_EQ(sticky.current(100.0), 3);
}

TEST(RenderHalfBlocks, DrawsTwoPixelsPerCellInTheirColours) {
  // 2 x 1 image: red above blue, one cell.
  const uint8_t rgb[] = {255, 0, 0, 0, 0, 255};
  const std::string s = renderHalfBlocks(rgb, 2, 1);
  EXPECT_EQ(s.rfind("\x1b[H", 0), 0u);  // from the top-left corner
  EXPECT_NE(s.find("\x1b[38;2;255;0;0m\x1b[48;2;0;0;255m\u2580"), std::string::npos) << s;
  // An 84 x 84 image is 42 rows of 84 cells.
  std::vector<uint8_t> image(84 * 84 * 3, 7);
  const std::string big = renderHalfBlocks(image.data(), 84, 84);
  size_t rows = 0, cells = 0;
  for (size_t p = 0; (p = big.find("\r\n", p)) != std::string::npos; p += 2) ++rows;
  for (size_t p = 0; (p = big.find("\u2580", p)) != std::string::npos; p += 3) ++cells;
  EXPECT_EQ(rows, 42u);
  EXPECT_EQ(cells, 84u * 42u);
}

}  // namespace
}  // namespace hideseek_hider
