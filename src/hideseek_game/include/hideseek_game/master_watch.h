// Watches the ROS master from a thread of its own, every period_s of wall time (issue #49).
//
// A ROS 1 node talks to its peers directly once connected, so a game or a training run goes on
// when the master dies, and still goes on when a new master starts on the same port. But the new
// master knows none of the running nodes (roscpp does not register again), so a subscriber that
// starts later (rviz, rostopic, a recorder) finds nothing. The watch says so, once per event, on
// the node's log: the master gone, back and still knowing the node, or restarted without it,
// with what to do. (When roslaunch started the master itself, the master is a required process:
// its death stops the launch, and the same command resumes a training run from its checkpoint.)
#pragma once

#include <condition_variable>
#include <mutex>
#include <thread>

namespace hideseek_game {

class MasterWatch {
 public:
  explicit MasterWatch(double period_s = 2.0);
  ~MasterWatch();
  MasterWatch(const MasterWatch&) = delete;
  MasterWatch& operator=(const MasterWatch&) = delete;

 private:
  void run(double period_s);

  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace hideseek_game
