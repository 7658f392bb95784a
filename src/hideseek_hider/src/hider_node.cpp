#include "hideseek_hider/hider_node.h"

#include <hideseek_msgs/ActionBatch.h>

#include <stdexcept>

#include "hideseek_world/topic_names.h"
#include "hideseek_world/world_node_options.h"

namespace hideseek_hider {

namespace {

torch::Device deviceFrom(const std::string& name, const std::string& param) {
  if (name == "cpu") return torch::kCPU;
  if (name == "cuda") {
    if (!torch::cuda::is_available()) {
      throw std::runtime_error("parameter " + param + " is 'cuda' but the linked libtorch has no usable CUDA device");
    }
    return torch::kCUDA;
  }
  throw std::runtime_error("parameter " + param + " must be 'cpu' or 'cuda', got '" + name + "'");
}

}  // namespace

HiderNode::HiderNode(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh) {
  const hideseek_world::VariantConfig v = hideseek_world::loadVariantParams(pnh);
  image_height_ = v.game.camera.height;
  image_width_ = v.game.camera.width;
  const std::string policy = pnh.param<std::string>("policy", "random");
  const int threads = pnh.param("threads", 1);
  if (threads < 1 || threads > 64) throw std::runtime_error("parameter " + pnh.resolveName("threads") + " must be in [1, 64]");
  torch::set_num_threads(threads);
  if (policy == "random") {
    policy_ = std::make_unique<RandomHiderPolicy>();
    ROS_INFO("hider: uniformly random policy");
  } else {
    const torch::Device device = deviceFrom(pnh.param<std::string>("device", "cpu"), pnh.resolveName("device"));
    CheckpointInfo info;
    HiderNet net = loadCheckpoint(policy, image_height_, image_width_, &info);
    policy_ = std::make_unique<NetworkHiderPolicy>(net, device, pnh.param("greedy", false));
    ROS_INFO("hider: policy %s (variant '%s', %ld training steps) on %s", policy.c_str(), info.variant.c_str(),
             static_cast<long>(info.steps), device.str().c_str());
  }
  actions_pub_ = nh_.advertise<hideseek_msgs::ActionBatch>(hideseek_world::kHiderActionsTopic, 2);
  observations_sub_ = nh_.subscribe(hideseek_world::kHiderObservationsTopic, 2, &HiderNode::onObservations, this,
                                    ros::TransportHints().tcpNoDelay());
}

void HiderNode::onObservations(const hideseek_msgs::ObservationBatch::ConstPtr& msg) {
  const size_t n = msg->num_arenas;
  const size_t bytes = static_cast<size_t>(image_height_) * image_width_ * 3;
  if (msg->height != static_cast<uint32_t>(image_height_) || msg->width != static_cast<uint32_t>(image_width_) ||
      msg->images.size() != n * bytes || msg->step.size() != n || msg->seed.size() != n) {
    ++malformed_;
    ROS_WARN_THROTTLE(2.0, "hider: ignored an observation batch that does not hold %zu %dx%d images with step ids (%lu so far)",
                      n, image_height_, image_width_, static_cast<unsigned long>(malformed_));
    return;
  }
  std::vector<ArenaObservation> batch(n);
  for (size_t i = 0; i < n; ++i) {
    batch[i] = {msg->images.data() + i * bytes, msg->seed[i], msg->step[i], static_cast<uint32_t>(i)};
  }
  hideseek_msgs::ActionBatch out;
  out.header.stamp = msg->header.stamp;
  out.step = msg->step;
  out.actions = policy_->act(batch);
  actions_pub_.publish(out);
}

}  // namespace hideseek_hider
