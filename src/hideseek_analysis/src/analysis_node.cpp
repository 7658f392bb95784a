// Records an analysis rollout (world/steps) into a bag with the C++ rosbag API, and once it holds
// the requested decisions, closes it and analyses it (runAnalysis). Its exit ends the launch
// (required). A missing decision stops the recording at once: nothing past a hole is analysed.
#include <hideseek_msgs/StepBatch.h>
#include <ros/ros.h>
#include <rosbag/bag.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "hideseek_analysis/analysis_job.h"
#include "hideseek_game/package_paths.h"
#include "hideseek_game/params.h"
#include "hideseek_game/run_registry.h"
#include "hideseek_game/topic_names.h"
#include "hideseek_hider/checkpoint.h"
#include "hideseek_hider/hider_net.h"

namespace {

class Recorder {
 public:
  Recorder(ros::NodeHandle& nh, const std::string& path, int decisions) : wanted_(decisions) {
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    bag_.open(path, rosbag::bagmode::Write);
    bag_.setCompression(rosbag::compression::LZ4);
    // A deep queue: the bag is written in the callback, and lockstep may run ahead for a while.
    sub_ = nh.subscribe(hideseek_game::kStepsTopic, 100000, &Recorder::onSteps, this);
  }

  bool complete() const { return recorded_ == wanted_; }
  int recorded() const { return recorded_; }
  const std::string& failure() const { return failure_; }
  void close() {
    sub_.shutdown();
    if (bag_.isOpen()) bag_.close();
  }

 private:
  void onSteps(const ros::MessageEvent<const hideseek_msgs::StepBatch>& event) {
    if (complete() || !failure_.empty()) return;
    const auto& msg = *event.getConstMessage();
    if (next_ && msg.decision != *next_) {
      failure_ = "decision " + std::to_string(msg.decision) + " arrived after decision " + std::to_string(*next_ - 1) +
                 ": the recording lost steps";
      close();
      ros::shutdown();
      return;
    }
    if (msg.image_every == 0) {
      failure_ =
          "world/steps carries no hider images (the world's step_image_every is 0, or record_images is "
          "false): the probes need them";
      close();
      ros::shutdown();
      return;
    }
    next_ = msg.decision + 1;
    bag_.write(sub_.getTopic(), msg.header.stamp.isZero() ? ros::TIME_MIN : msg.header.stamp, msg);
    ++recorded_;
    if (recorded_ % 500 == 0 || complete()) ROS_INFO("analysis: recorded %d of %d decisions", recorded_, wanted_);
    if (complete()) {
      close();
      ros::shutdown();
    }
  }

  rosbag::Bag bag_;
  ros::Subscriber sub_;
  const int wanted_;
  int recorded_ = 0;
  std::optional<uint64_t> next_;
  std::string failure_;
};

constexpr int kMaxDecisions = 1 << 24;  // ~decisions: a bag of this many steps is already tens of GB

// What the node does, read from its private parameters; throws naming the parameter at fault.
struct AnalysisNodeOptions {
  hideseek_analysis::AnalysisJob job;
  int decisions = 0;  // decision steps of world/steps to record
};

AnalysisNodeOptions loadAnalysisNodeOptions(const ros::NodeHandle& pnh) {
  AnalysisNodeOptions o;
  o.job.variant = hideseek_game::loadVariantParams(pnh);
  o.job.policy = hideseek_game::requireString(pnh, "policy", "a checkpoint file, or 'shipped'");
  if (o.job.policy == hideseek_game::kShippedPolicy) {
    const std::string registry = hideseek_game::requireString(pnh, "policy_registry", "the run registry file");
    const std::string network = hideseek_game::readString(pnh, "network", "auto") == "gru" ? "gru" : "ff";
    o.job.policy = hideseek_game::shippedPolicyFile(registry, o.job.variant.name, network, o.job.variant.game.name);
    if (o.job.policy.empty()) {
      throw std::runtime_error("parameter " + pnh.resolveName("policy") + " is 'shipped', but " + registry +
                               " ships no " + network + " policy for variant " + o.job.variant.name + " on game " +
                               o.job.variant.game.name + ": give a checkpoint file");
    }
  }
  o.job.inputs_dir = hideseek_game::requireString(pnh, "output_dir", "a folder");
  o.job.report_dir = hideseek_game::readString(pnh, "report_dir", o.job.inputs_dir + "/report");
  // The report script hideseek_analysis installs, unless a parameter names another.
  o.job.report_script = hideseek_game::readString(pnh, "report_script", "");
  if (o.job.report_script.empty())
    o.job.report_script = hideseek_game::packageExecutable("hideseek_analysis", "report.py");
  o.job.bag = hideseek_game::readString(pnh, "bag", o.job.inputs_dir + "/rollout.bag");
  o.job.inputs.random_init_seed =
      static_cast<uint32_t>(hideseek_game::readInt(pnh, "random_init_seed", 0, 0, hideseek_game::kMaxSeed));
  o.job.tsne_samples = hideseek_game::readInt(pnh, "tsne_samples", 3000, 100, 100000);
  o.job.probe_splits = hideseek_game::readInt(pnh, "probe_splits", 5, 1, 100);
  o.job.inputs.pixel_tolerance = hideseek_game::readInt(pnh, "pixel_tolerance", 0, 0, 255);
  const std::string precision = hideseek_game::readString(pnh, "precision", "fp32");
  if (!pnh.hasParam("decisions")) {
    throw std::runtime_error("parameter " + pnh.resolveName("decisions") + " is required (decision steps to record)");
  }
  o.decisions = hideseek_game::readInt(pnh, "decisions", 0, 1, kMaxDecisions);
  if (!std::filesystem::is_regular_file(o.job.policy)) {
    throw std::runtime_error("parameter " + pnh.resolveName("policy") + ": no checkpoint at " + o.job.policy);
  }
  // Read before recording, not after: a file that is no checkpoint stops the launch at once.
  if (hideseek_hider::readCheckpointInfo(o.job.policy).network == hideseek_hider::NetworkKind::kGru &&
      precision != "fp32") {
    throw std::runtime_error("parameter " + pnh.resolveName("precision") + " is '" + precision +
                             "': a GRU policy is analysed in fp32 only, because its state is replayed in fp32 "
                             "and would drift from the state a " +
                             precision + " hider acted on; set precision:=fp32");
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "analysis");
  hideseek_analysis::AnalysisJob job;
  std::unique_ptr<Recorder> recorder;
  {
    ros::NodeHandle nh, pnh("~");
    try {
      const AnalysisNodeOptions options = loadAnalysisNodeOptions(pnh);
      job = options.job;
      recorder = std::make_unique<Recorder>(nh, job.bag, options.decisions);
      ROS_INFO("analysis: recording %d decisions of world/steps into %s", options.decisions, job.bag.c_str());
    } catch (const std::exception& e) {
      // Logged while roscpp still runs, so that roslaunch shows it.
      ROS_FATAL("analysis: %s", e.what());
      return 1;
    }
    ros::spin();
  }
  recorder->close();
  if (!recorder->failure().empty()) {
    std::fprintf(stderr, "analysis: %s; the bag %s is closed and nothing was analysed\n", recorder->failure().c_str(),
                 job.bag.c_str());
    return 1;
  }
  if (!recorder->complete()) {
    std::fprintf(stderr, "analysis: interrupted after %d decisions; the bag %s is closed, nothing was analysed\n",
                 recorder->recorded(), job.bag.c_str());
    return 1;
  }
  try {
    hideseek_analysis::runAnalysis(job);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "analysis: %s\n", e.what());
    return 1;
  }
  return 0;
}
