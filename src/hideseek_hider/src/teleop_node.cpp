// The keyboard hider: a person plays arena 0 from a terminal that shows the hider's camera.
// w/s/a/d or the arrow keys move and turn, space stops, q or Ctrl-D quits, as does closing the
// terminal. The node answers every observation batch like the hider node does, so the world, the
// recorder and the evaluator treat a human like any policy.
#include <fcntl.h>
#include <hideseek_msgs/ActionBatch.h>
#include <hideseek_msgs/ObservationBatch.h>
#include <ros/ros.h>
#include <unistd.h>

#include <cstdio>
#include <exception>
#include <string>

#include "hideseek_game/params.h"
#include "hideseek_game/topic_names.h"
#include "hideseek_hider/teleop.h"

namespace {

double wallNow() { return ros::WallTime::now().toSec(); }

// The node's private parameters.
struct TeleopNodeOptions {
  double key_timeout = 0.7;  // s a held key keeps acting after its last repeat
};

// Throws naming the parameter at fault.
TeleopNodeOptions loadTeleopNodeOptions(const ros::NodeHandle& pnh) {
  TeleopNodeOptions o;
  o.key_timeout = hideseek_game::readDouble(pnh, "key_timeout", 0.7, 0.0, 60.0);
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "teleop");
  ros::NodeHandle nh, pnh("~");
  TeleopNodeOptions options;
  try {
    options = loadTeleopNodeOptions(pnh);
  } catch (const std::exception& e) {
    ROS_FATAL("teleop: %s", e.what());
    return 1;
  }
  const double key_timeout = options.key_timeout;
  ROS_INFO("teleop: you play the hider of arena 0 (key_timeout %.2f s)", key_timeout);
  // Clears the screen: the game's picture replaces the log from here on.
  const bool on_stdin = isatty(STDIN_FILENO);
  hideseek_hider::RawTerminal terminal(on_stdin ? STDIN_FILENO : open("/dev/tty", O_RDWR | O_NONBLOCK), !on_stdin);
  if (!terminal.ok()) {
    ROS_FATAL(
        "teleop: no terminal to read keys from. Run it in one: rosrun hideseek_hider teleop_node "
        "(play.launch opens an xterm for it when a display is available)");
    return 1;
  }
  hideseek_hider::TeleopKeys keys;
  hideseek_hider::TeleopAction action(key_timeout);
  std::string last_outcome = "no episode finished yet";
  uint32_t previous_step = 0;
  auto pub = nh.advertise<hideseek_msgs::ActionBatch>(hideseek_game::kHiderActionsTopic, 2);
  auto sub = nh.subscribe<hideseek_msgs::ObservationBatch>(
      hideseek_game::kHiderObservationsTopic, 1, [&](const hideseek_msgs::ObservationBatch::ConstPtr& m) {
        const size_t n = m->num_arenas, bytes = static_cast<size_t>(m->height) * m->width * 3;
        if (n == 0 || m->step.size() != n || m->images.size() != n * bytes || m->done.size() != n ||
            m->outcome.size() != n || m->episode.size() != n) {
          return;  // the world checks its own batches; nothing sensible to answer
        }
        hideseek_msgs::ActionBatch out;
        out.header.stamp = m->header.stamp;
        out.step = m->step;
        out.actions.assign(n, hideseek_msgs::ActionBatch::STAY);  // a person plays arena 0 only
        out.actions[0] = action.current(wallNow());
        pub.publish(out);
        if (m->done[0]) {
          last_outcome = std::string(m->outcome[0] == 2 ? "survived" : "caught") + " after " +
                         std::to_string(previous_step + 1) + " steps";
        }
        previous_step = m->step[0];
        char status[200];
        std::snprintf(status, sizeof status,
                      "\x1b[0mepisode %u, step %u    last episode: %s\x1b[K\r\n"
                      "w/up forward  s/down back  a/left d/right turn  space stop  q/Ctrl-D quit\x1b[K\r\n",
                      m->episode[0], m->step[0], last_outcome.c_str());
        terminal.write(hideseek_hider::renderHalfBlocks(m->images.data(), static_cast<int>(m->height),
                                                        static_cast<int>(m->width)) +
                       status);
      });
  // Keys are polled between batches on the wall clock (the game may run on sim time).
  ros::WallTimer poll = nh.createWallTimer(ros::WallDuration(0.01), [&](const ros::WallTimerEvent&) {
    const hideseek_hider::TeleopCommand c = keys.feed(terminal.read());
    if (c.action) action.press(*c.action, wallNow());
    if (c.quit) ros::shutdown();
    if (terminal.closed()) {
      ROS_INFO("teleop: the terminal closed; quitting");
      ros::shutdown();
    }
  });
  ros::spin();
  return 0;
}
