// Measures the lockstep throughput of a running game graph from game_state (one message per
// decision step of arena 0, stamped with sim time). Prints `<name> N`: arena-steps per wall second.
#include <hideseek_msgs/GameState.h>
#include <ros/ros.h>

#include <cstdio>

int main(int argc, char** argv) {
  ros::init(argc, argv, "throughput_probe", ros::init_options::AnonymousName);
  ros::NodeHandle nh, pnh("~");
  const std::string name = pnh.param<std::string>("name", "world_ros_steps_per_s");
  const int arenas = pnh.param("num_arenas", 16);
  const double warmup = pnh.param("warmup", 3.0), duration = pnh.param("duration", 10.0);
  long messages = 0;
  ros::WallTime start;
  bool measuring = false;
  ros::WallTime first_message;
  auto sub = nh.subscribe<hideseek_msgs::GameState>("game_state", 1000, [&](const hideseek_msgs::GameState::ConstPtr&) {
    const ros::WallTime now = ros::WallTime::now();
    if (first_message.isZero()) first_message = now;
    if (!measuring && (now - first_message).toSec() >= warmup) {
      measuring = true;
      start = now;
      messages = 0;
    }
    ++messages;
  });
  while (ros::ok()) {
    ros::spinOnce();
    if (measuring && (ros::WallTime::now() - start).toSec() >= duration) break;
    if (first_message.isZero() && ros::WallTime::now().toSec() > 0 && messages == 0) ros::WallDuration(0.001).sleep();
    ros::WallDuration(0.0005).sleep();
  }
  const double elapsed = (ros::WallTime::now() - start).toSec();
  std::printf("%s %.0f\n", name.c_str(), messages * arenas / elapsed);
  std::fflush(stdout);
  ros::shutdown();
  return 0;
}
