// A minimal agent for tests and benchmarks: answers every observation batch at once with
// uniformly random actions. Each action is a hash of (episode seed, step), so an
// answer re-sent for the same step is the same answer and runs are reproducible.
#include <hideseek_msgs/ActionBatch.h>
#include <hideseek_msgs/ObservationBatch.h>
#include <hideseek_msgs/SeekerObservationBatch.h>
#include <ros/ros.h>

#include <cstdint>

#include "hideseek_game/agent.h"
#include "hideseek_game/hash_uniform.h"
#include "hideseek_game/topic_names.h"

namespace {

template <typename Batch>
hideseek_msgs::ActionBatch answer(const Batch& obs, uint32_t salt) {
  hideseek_msgs::ActionBatch out;
  out.header.stamp = obs.header.stamp;
  out.step = obs.step;
  for (uint32_t i = 0; i < obs.num_arenas; ++i)
    out.actions.push_back(hideseek_game::hashAction(obs.seed[i], obs.step[i], salt));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "minimal_agent");
  ros::NodeHandle nh, pnh("~");
  const std::string role = pnh.param<std::string>("role", "hider");
  if (role != "hider" && role != "seeker") {
    ROS_FATAL("minimal_agent: parameter %s must be 'hider' or 'seeker', got '%s'", pnh.resolveName("role").c_str(),
              role.c_str());
    return 1;
  }
  const auto hints = ros::TransportHints().tcpNoDelay();
  ros::Publisher pub;
  ros::Subscriber sub;
  if (role == "hider") {
    pub = nh.advertise<hideseek_msgs::ActionBatch>(hideseek_game::kHiderActionsTopic, 2);
    sub = nh.subscribe<hideseek_msgs::ObservationBatch>(
        hideseek_game::kHiderObservationsTopic, 2,
        [&](const hideseek_msgs::ObservationBatch::ConstPtr& m) { pub.publish(answer(*m, 0x51)); }, ros::VoidConstPtr(),
        hints);
  } else {
    pub = nh.advertise<hideseek_msgs::ActionBatch>(hideseek_game::kSeekerActionsTopic, 2);
    sub = nh.subscribe<hideseek_msgs::SeekerObservationBatch>(
        hideseek_game::kSeekerObservationsTopic, 2,
        [&](const hideseek_msgs::SeekerObservationBatch::ConstPtr& m) { pub.publish(answer(*m, 0x5e)); },
        ros::VoidConstPtr(), hints);
  }
  ros::spin();
  return 0;
}
