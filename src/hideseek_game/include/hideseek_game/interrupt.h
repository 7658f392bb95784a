// Ctrl-C for a node with work to finish as it stops (a training run's last checkpoint).
//
// roscpp's own SIGINT handler shuts ROS down at once, after which the node's log lines no longer
// appear. Such a node takes SIGINT itself instead: ros::init(..., ros::init_options::NoSigintHandler),
// then catchInterrupt(), its setup, spinUntilInterrupted(), the work, and ros::shutdown(). roslaunch
// stops its nodes with SIGINT and, 15 s later, SIGTERM.
#pragma once

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <csignal>

namespace hideseek_game {

inline volatile std::sig_atomic_t g_interrupted = 0;

// From now on SIGINT asks spinUntilInterrupted() to return; a second SIGINT stops the process at
// once, as roscpp's own handler would (a node stuck in a wait).
inline void catchInterrupt() {
  std::signal(SIGINT, [](int) {
    g_interrupted = 1;
    std::signal(SIGINT, SIG_DFL);
  });
}

// Runs the callbacks, one thread, until SIGINT came or ROS shut down (ros::shutdown(), a node
// that stopped itself): a wait of at most 0.1 s notices it, no busy loop.
inline void spinUntilInterrupted() {
  while (ros::ok() && !g_interrupted) ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.1));
}

}  // namespace hideseek_game
