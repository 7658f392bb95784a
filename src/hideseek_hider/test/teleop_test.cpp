#include "hideseek_hider/teleop.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

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

TEST(TeleopKeys, QCtrlCAndCtrlDQuit) {
  TeleopKeys k;
  EXPECT_TRUE(k.feed("q").quit);
  EXPECT_TRUE(k.feed("\x03").quit);
  EXPECT_TRUE(k.feed("\x04").quit);  // raw mode: Ctrl-D is a byte, not an end of file
  EXPECT_FALSE(k.feed("w").quit);
}

// A pseudo-terminal stands in for the player's: its master end is the xterm.
TEST(RawTerminal, ReadsKeysUnbufferedRestoresTheTerminalAndSeesAHangUp) {
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(grantpt(master), 0);
  ASSERT_EQ(unlockpt(master), 0);
  const int slave = open(ptsname(master), O_RDWR | O_NOCTTY);
  ASSERT_GE(slave, 0);
  termios before{};
  ASSERT_EQ(tcgetattr(slave, &before), 0);
  ASSERT_TRUE(before.c_lflag & ICANON);
  {
    RawTerminal terminal(slave, false);
    ASSERT_TRUE(terminal.ok());
    EXPECT_EQ(terminal.read(), "") << "nothing typed: the read returns at once";
    ASSERT_EQ(write(master, "w", 1), 1);  // no Enter: raw mode delivers the key alone
    std::string got;
    for (int i = 0; i < 200 && got.empty(); ++i) {
      got = terminal.read();
      if (got.empty()) usleep(5000);
    }
    EXPECT_EQ(got, "w");
    EXPECT_FALSE(terminal.closed());
  }
  termios after{};
  ASSERT_EQ(tcgetattr(slave, &after), 0);
  EXPECT_TRUE(after.c_lflag & ICANON) << "the terminal left in raw mode";
  EXPECT_TRUE(after.c_lflag & ECHO);
  RawTerminal terminal(slave, true);
  ASSERT_TRUE(terminal.ok());
  close(master);  // the window closes
  EXPECT_TRUE(terminal.closed());
  EXPECT_FALSE(RawTerminal(-1, false).ok());
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
