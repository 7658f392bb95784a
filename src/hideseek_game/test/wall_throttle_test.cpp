#include "hideseek_game/wall_throttle.h"

#include <gtest/gtest.h>

namespace hideseek_game {
namespace {

TEST(WallThrottle, LetsOneMessageOutPerPeriodAndCountsTheRest) {
  WallThrottle t(2.0);
  EXPECT_TRUE(t.ready(100.0));
  EXPECT_EQ(t.suppressed(), 0u);
  int out = 0;
  uint64_t suppressed_before_second = 0;
  for (int k = 0; k < 400; ++k) {  // a 4 s flood, 100 a second, from 100.005 s to 103.995 s
    if (t.ready(100.005 + 0.01 * k)) {
      ++out;
      suppressed_before_second = t.suppressed();
    }
  }
  EXPECT_EQ(out, 1);                          // at 102.005 s
  EXPECT_EQ(suppressed_before_second, 200u);  // those from 100.005 s to 101.995 s
  EXPECT_TRUE(t.ready(200.0));                // after a quiet spell, at once
  EXPECT_EQ(t.suppressed(), 199u);            // the flood's tail
}

TEST(WallThrottle, SpeaksOnTheWallClockWhateverSimTimeDoes) {
  // The default clock is steady wall time: two calls far apart in sim time but not in wall time
  // give one message, and a period of zero lets every message out.
  WallThrottle t(3600.0);
  EXPECT_TRUE(t.ready());
  EXPECT_FALSE(t.ready());
  WallThrottle every(0.0);
  EXPECT_TRUE(every.ready());
  EXPECT_TRUE(every.ready());
}

}  // namespace
}  // namespace hideseek_game
