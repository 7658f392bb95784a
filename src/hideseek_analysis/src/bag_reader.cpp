#include "hideseek_analysis/bag_reader.h"

#include <ros/message_traits.h>
#include <rosbag/bag.h>
#include <rosbag/query.h>
#include <rosbag/view.h>

#include "hideseek_analysis/bag_check.h"

namespace hideseek_analysis {

DecisionRecord toDecisionRecord(const hideseek_msgs::StepBatch& m) {
  const size_t n = m.num_arenas;
  auto check = [&](const char* field, size_t size) {
    if (size != n) {
      throw std::invalid_argument("StepBatch of decision " + std::to_string(m.decision) + ": " + field + " has " +
                                  std::to_string(size) + " entries for " + std::to_string(n) + " arenas");
    }
  };
  check("episode", m.episode.size());
  check("seed", m.seed.size());
  check("step", m.step.size());
  check("hider_pose", m.hider_pose.size());
  check("seeker_pose", m.seeker_pose.size());
  check("distance", m.distance.size());
  check("hider_sees_seeker", m.hider_sees_seeker.size());
  check("seeker_sees_hider", m.seeker_sees_hider.size());
  check("obstacle_in_view", m.obstacle_in_view.size());
  check("hider_action", m.hider_action.size());
  check("seeker_action", m.seeker_action.size());
  check("reward", m.reward.size());
  check("outcome", m.outcome.size());
  DecisionRecord d;
  d.decision = m.decision;
  d.height = static_cast<int>(m.height);
  d.width = static_cast<int>(m.width);
  d.images = m.images;
  d.arenas.resize(n);
  for (size_t i = 0; i < n; ++i) {
    ArenaStepRecord& r = d.arenas[i];
    r.episode = m.episode[i];
    r.seed = m.seed[i];
    r.step = m.step[i];
    r.hider_x = m.hider_pose[i].x;
    r.hider_y = m.hider_pose[i].y;
    r.hider_yaw = m.hider_pose[i].theta;
    r.seeker_x = m.seeker_pose[i].x;
    r.seeker_y = m.seeker_pose[i].y;
    r.seeker_yaw = m.seeker_pose[i].theta;
    r.distance = m.distance[i];
    r.hider_sees_seeker = m.hider_sees_seeker[i];
    r.seeker_sees_hider = m.seeker_sees_hider[i];
    r.obstacle_in_view = m.obstacle_in_view[i];
    r.hider_action = m.hider_action[i];
    r.seeker_action = m.seeker_action[i];
    r.reward = m.reward[i];
    r.outcome = m.outcome[i];
  }
  return d;
}

StepLog readStepBag(const std::string& path) {
  // rosbag trusts the lengths and offsets the file declares: check them all first.
  const std::string problem = checkBagFile(path);
  if (!problem.empty()) throw std::runtime_error("cannot read bag " + path + ": " + problem + "; nothing was analysed");
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error("cannot read bag " + path + ": " + e.what());
  }
  rosbag::View view(bag, rosbag::TypeQuery(ros::message_traits::DataType<hideseek_msgs::StepBatch>::value()));
  if (view.size() == 0) throw std::runtime_error("bag " + path + " holds no hideseek_msgs/StepBatch (world/steps)");
  // The world stamps each decision later than the one before (sim time in lockstep, wall time
  // in realtime), so the bag's time order is the decision order.
  StepLog log;
  try {
    for (const rosbag::MessageInstance& m : view) {
      if (auto b = m.instantiate<hideseek_msgs::StepBatch>()) log.append(toDecisionRecord(*b));
    }
  } catch (const MissingStepsError& e) {
    throw MissingStepsError("bag " + path + ": " + e.what() + "; nothing was analysed");
  }
  return log;
}

}  // namespace hideseek_analysis
