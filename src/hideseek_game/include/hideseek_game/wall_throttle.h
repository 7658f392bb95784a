// Rate limit for repeated warnings, on the wall clock. roscpp's *_THROTTLE macros follow
// ros::Time, which in lockstep is sim time: a flood of bad input printed hundreds of lines in a
// few wall seconds, and a stalled game (sim time frozen) printed nothing at all.
#pragma once

#include <chrono>
#include <cstdint>
#include <limits>

namespace hideseek_game {

class WallThrottle {
 public:
  explicit WallThrottle(double period_s) : period_(period_s) {}

  // True when a message may go out now (at most one per period); otherwise counts it as suppressed.
  bool ready() {
    return ready(std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count());
  }
  bool ready(double now_s) {
    if (now_s - last_ < period_) {
      ++suppressed_;
      return false;
    }
    last_ = now_s;
    reported_suppressed_ = suppressed_;
    suppressed_ = 0;
    return true;
  }
  // How many messages were suppressed before the one ready() just let out.
  uint64_t suppressed() const { return reported_suppressed_; }

 private:
  double period_;
  double last_ = -std::numeric_limits<double>::infinity();
  uint64_t suppressed_ = 0;
  uint64_t reported_suppressed_ = 0;
};

}  // namespace hideseek_game
