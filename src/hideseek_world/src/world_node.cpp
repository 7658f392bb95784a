#include "hideseek_world/world_node.h"

#include <hideseek_msgs/GameState.h>
#include <hideseek_msgs/ObservationBatch.h>
#include <hideseek_msgs/SeekerObservationBatch.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/master.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/image_encodings.h>
#include <visualization_msgs/MarkerArray.h>

#include <cstdio>
#include <string>
#include <vector>

#include "hideseek_game/msg_conversion.h"
#include "hideseek_game/topic_names.h"
#include "hideseek_game/wall_throttle.h"

namespace hideseek_world {

using namespace hideseek_game;  // NOLINT(google-build-using-namespace): the node is the game's ROS face

namespace {

constexpr double kMapResolution = 0.05;  // m per cell of the published OccupancyGrid
constexpr double kOwnerTimeout = 2.0;    // s a silent publisher keeps its topic
constexpr double kSimTimeOrigin = 1.0;   // s; sim time 0 means "no time" to tf and rosbag

const char* outcomeName(Outcome o) {
  switch (o) {
    case Outcome::kCaptured:
      return "captured";
    case Outcome::kSurvived:
      return "survived";
    default:
      return "running";
  }
}

geometry_msgs::TransformStamped fixedTransform(const std::string& parent, const std::string& child, double z, double qx,
                                               double qy, double qz, double qw) {
  geometry_msgs::TransformStamped t;
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform.translation.z = z;
  t.transform.rotation.x = qx;
  t.transform.rotation.y = qy;
  t.transform.rotation.z = qz;
  t.transform.rotation.w = qw;
  return t;
}

// The nodes other than this one that the master lists as publishing `topic` (none where the master
// cannot be asked).
std::vector<std::string> otherPublishers(const std::string& topic) {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", args, result, payload, false)) return {};
  std::vector<std::string> nodes;
  if (payload.getType() != XmlRpc::XmlRpcValue::TypeArray || payload.size() < 1) return nodes;
  XmlRpc::XmlRpcValue& publications = payload[0];
  for (int i = 0; i < publications.size(); ++i) {
    if (publications[i].size() < 2 || static_cast<std::string>(publications[i][0]) != topic) continue;
    for (int j = 0; j < publications[i][1].size(); ++j) {
      const std::string node = publications[i][1][j];
      if (node != ros::this_node::getName()) nodes.push_back(node);
    }
  }
  return nodes;
}

// Another game's observation topic on this master, if any (checked before this world advertises its own).
std::string anotherGame() {
  ros::master::V_TopicInfo topics;
  if (!ros::master::getTopics(topics)) return "";
  for (const ros::master::TopicInfo& t : topics) {
    if (t.datatype == ros::message_traits::datatype<hideseek_msgs::ObservationBatch>()) return t.name;
  }
  return "";
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

WorldNode::WorldNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh),
      image_transport_(nh),
      options_(loadWorldNodeOptions(private_nh)),
      game_(options_.variant.game, std::make_shared<const MapSpec>(options_.map), options_.loop) {
  const GameOptions& game = options_.variant.game;
  const int n = options_.loop.num_arenas;
  seeker_image_.resize(game_.world().imageBytes());
  hider_.name = "hider";
  hider_.player = Player::kHider;
  seeker_.name = "seeker";
  seeker_.player = Player::kSeeker;
  camera_info_ = toCameraInfo(game.camera, options_.frame("hider/camera_optical_frame"));

  const bool lockstep = options_.loop.mode == ClockMode::kLockstep;
  // /clock and /use_sim_time belong to the whole master: a lockstep game needs a master where
  // nothing else sets the time (checked once its own /clock is advertised, below), and a game
  // beside one of the other mode leaves /use_sim_time as the last launch set it, for every tool
  // started afterwards.
  if (const std::vector<std::string> clocks = otherPublishers("/clock"); !lockstep && !clocks.empty()) {
    ROS_WARN(
        "world: /clock is published on this master, by %s (a lockstep game, or a bag played with --clock): "
        "/use_sim_time is global and the last launch set it: tools started from now on (rviz, tf_echo) read one "
        "clock for both games; give a lockstep game a master of its own",
        joined(clocks).c_str());
  } else if (const std::string other = lockstep && clocks.empty() ? anotherGame() : std::string(); !other.empty()) {
    ROS_WARN(
        "world: another game runs on this master (%s): /use_sim_time is global and this lockstep launch set it true, "
        "so tools started from now on (rviz, tf_echo) read this game's sim time for that game too; give a lockstep "
        "game a master of its own",
        other.c_str());
  }
  if (!lockstep && ros::Time::isSimTime()) {
    ROS_WARN(
        "world: /use_sim_time is true, so this realtime game stamps its messages with /clock's time, not the wall "
        "clock's (its pace stays the wall clock's): start it with a launch file, which sets /use_sim_time false");
  }
  hider_obs_pub_ = nh_.advertise<hideseek_msgs::ObservationBatch>(kHiderObservationsTopic, 2);
  seeker_obs_pub_ = nh_.advertise<hideseek_msgs::SeekerObservationBatch>(kSeekerObservationsTopic, 2);
  if (lockstep) {
    clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
    // Checked once this world is itself registered: of two lockstep worlds starting together, the
    // later to look sees the other (and if both look at once, both stop).
    if (const std::vector<std::string> clocks = otherPublishers("/clock"); !clocks.empty()) {
      throw std::runtime_error("/clock is already published on this master, by " + joined(clocks) +
                               " (another lockstep game, or a bag played with --clock): a lockstep game sets the "
                               "master's sim time, so it needs a master of its own (roslaunch -p PORT; `rosnode "
                               "cleanup` clears a node that died without unregistering)");
    }
  }
  // image_raw with its camera_info beside it, and every transport plugin installed (compressed, ...).
  hider_camera_pub_ = image_transport_.advertiseCamera(kHiderImageTopic, 2);
  seeker_camera_pub_ = image_transport_.advertiseCamera(kSeekerImageTopic, 2);
  markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>(kMarkersTopic, 2);
  map_pub_ = nh_.advertise<nav_msgs::OccupancyGrid>(kMapTopic, 1, true);
  hider_path_pub_ = nh_.advertise<nav_msgs::Path>(kHiderPathTopic, 2);
  seeker_path_pub_ = nh_.advertise<nav_msgs::Path>(kSeekerPathTopic, 2);
  // Deep queues: a recorder that falls behind by a few seconds of lockstep loses nothing. A
  // step record without images is about 1 kB per 16 arenas.
  state_pub_ = nh_.advertise<hideseek_msgs::GameState>(kGameStateTopic, 1000);
  steps_pub_ = nh_.advertise<hideseek_msgs::StepBatch>(kStepsTopic, 1000);
  // Small and rare: a deep queue loses no episode even behind a slow listener.
  episodes_pub_ = nh_.advertise<hideseek_msgs::EpisodeResult>(kEpisodesTopic, 10000);
  diagnostics_pub_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 5);

  // The callback must take the MessageEvent itself: a lambda would be wrapped as a ConstPtr
  // callback (MessageEvent converts from a pointer) and lose the publisher's caller id.
  // Actions are read through hideseek_game::CheckedActionBatch: ActionBatch on the wire, its
  // lengths checked before anything is allocated.
  using ActionEvent = const ros::MessageEvent<const hideseek_game::CheckedActionBatch>&;
  const auto hints = ros::TransportHints().tcpNoDelay();
  const boost::function<void(ActionEvent)> on_hider = [this](ActionEvent e) { onActions(e, hider_); };
  const boost::function<void(ActionEvent)> on_seeker = [this](ActionEvent e) { onActions(e, seeker_); };
  hider_sub_ = nh_.subscribe<hideseek_game::CheckedActionBatch, ActionEvent>(kHiderActionsTopic, 2 * n, on_hider,
                                                                             ros::VoidConstPtr(), hints);
  seeker_sub_ = nh_.subscribe<hideseek_game::CheckedActionBatch, ActionEvent>(kSeekerActionsTopic, 2 * n, on_seeker,
                                                                              ros::VoidConstPtr(), hints);
  reset_srv_ = nh_.advertiseService(kResetService, &WorldNode::onReset, this);

  // REP 103/105 camera frames: camera_link looks along the agent's x; the optical frame has
  // z forward, x right, y down.
  std::vector<geometry_msgs::TransformStamped> fixed;
  for (const std::string agent : {"hider", "seeker"}) {
    const std::string base = options_.frame(agent + "/base_link"), camera = options_.frame(agent + "/camera_link");
    fixed.push_back(fixedTransform(base, camera, game.camera.mount_height, 0, 0, 0, 1));
    fixed.push_back(fixedTransform(camera, options_.frame(agent + "/camera_optical_frame"), 0, -0.5, 0.5, -0.5, 0.5));
  }
  for (auto& t : fixed) t.header.stamp = simNow();
  static_tf_.sendTransform(fixed);

  startEpisodeVisuals();
  if (lockstep) {
    watchdog_timer_ = nh_.createWallTimer(ros::WallDuration(0.05), &WorldNode::onWatchdog, this);
  } else {
    tick_timer_ = nh_.createWallTimer(ros::WallDuration(game.physics_dt), &WorldNode::onRealtimeTick, this);
    // The agents' first observation goes out once, when both are connected (onRealtimeTick). Sent
    // here too, it reached agents that were already listening, and their second answers to the
    // same step could arrive after the step had started with the first: counted as late.
    publishArenaZero(true);
  }
  diagnostics_timer_ = nh_.createWallTimer(ros::WallDuration(1.0), &WorldNode::publishDiagnostics, this);
  if (options_.status_period > 0.0) {
    status_timer_ = nh_.createWallTimer(ros::WallDuration(options_.status_period), &WorldNode::printStatus, this);
  }
  ROS_INFO("world: game '%s', variant '%s', map '%s', %d arena(s), %s mode, seed %u, images %dx%d", game.name.c_str(),
           options_.variant.name.c_str(), options_.map.name.c_str(), n, lockstep ? "lockstep" : "realtime",
           options_.loop.seed, game.camera.width, game.camera.height);
}

bool WorldNode::readyToStart() {
  // Both agents listen and both can answer, so neither the first observation nor the first answer
  // is lost (an agent connects its two topics one after the other), and every listener that must
  // see the first episodes listens.
  std::vector<std::string> missing;
  auto need = [&](bool present, const std::string& what) {
    if (!present) missing.push_back(what);
  };
  need(hider_obs_pub_.getNumSubscribers() > 0, "the hider to listen on " + hider_obs_pub_.getTopic());
  need(hider_sub_.getNumPublishers() > 0, "the hider to publish on " + hider_sub_.getTopic());
  need(seeker_obs_pub_.getNumSubscribers() > 0, "the seeker to listen on " + seeker_obs_pub_.getTopic());
  need(seeker_sub_.getNumPublishers() > 0, "the seeker to publish on " + seeker_sub_.getTopic());
  auto listeners = [&](const ros::Publisher& pub, int wanted, const char* param) {
    need(pub.getNumSubscribers() >= static_cast<uint32_t>(wanted),
         std::to_string(wanted) + " listener(s) of " + pub.getTopic() + " (" + param + ", " +
             std::to_string(pub.getNumSubscribers()) +
             " so far: an evaluator, an analysis or record:=true's recorder)");
  };
  listeners(episodes_pub_, options_.episode_listeners, "episode_listeners");
  listeners(steps_pub_, options_.step_listeners, "step_listeners");
  if (missing.empty()) return true;
  // After 10 s of waiting, say every 10 s whom for: agents and recorders connect within seconds.
  constexpr double kWaitingReportAfter = 10.0;
  const ros::WallTime now = ros::WallTime::now();
  if (!waiting_since_) waiting_since_ = now;
  const double waited = (now - *waiting_since_).toSec();
  if (waited >= kWaitingReportAfter && throttles_.waiting.ready()) {
    ROS_WARN("world: waiting %.0f s to start, for %s", waited, joined(missing).c_str());
  }
  return false;
}

bool WorldNode::reachedMaxDecisions() const {
  return options_.max_decisions > 0 && game_.decisions() >= static_cast<uint64_t>(options_.max_decisions);
}

ros::Time WorldNode::simTime(uint64_t decisions) const {
  if (options_.loop.mode == ClockMode::kRealtime) return ros::Time::now();
  return ros::Time(kSimTimeOrigin + static_cast<double>(decisions) * options_.variant.game.stepDuration());
}

bool WorldNode::acceptPublisher(const std::string& caller, AgentChannel& channel) {
  const ros::WallTime now = ros::WallTime::now();
  if (channel.owner.empty() || channel.owner == caller || (now - channel.owner_last_seen).toSec() > kOwnerTimeout) {
    if (channel.owner != caller) {
      if (!channel.owner.empty()) ROS_INFO("world: %s actions now come from %s", channel.name.c_str(), caller.c_str());
      channel.owner = caller;
    }
    channel.owner_last_seen = now;
    return true;
  }
  return false;
}

void WorldNode::onActions(const ros::MessageEvent<const hideseek_game::CheckedActionBatch>& event,
                          AgentChannel& channel) {
  const std::string caller = event.getPublisherName();
  const hideseek_game::CheckedActionBatch& checked = *event.getConstMessage();
  if (!checked.problem.empty()) {
    ++rejected_.malformed;
    WallThrottle& throttle = throttles_.malformed;
    if (throttle.ready()) {
      ROS_WARN("world: rejected a malformed %s action message from %s: %s (%lu more like it since the last)",
               channel.name.c_str(), caller.c_str(), checked.problem.c_str(),
               static_cast<unsigned long>(throttle.suppressed()));
    }
    return;
  }
  if (!acceptPublisher(caller, channel)) {
    ++rejected_.second_publisher;
    WallThrottle& throttle = throttles_.second_publisher;
    if (throttle.ready()) {
      ROS_WARN("world: rejected %s actions from %s: %s already publishes them (%lu more like it since the last)",
               channel.name.c_str(), caller.c_str(), channel.owner.c_str(),
               static_cast<unsigned long>(throttle.suppressed()));
    }
    return;
  }
  const hideseek_msgs::ActionBatch& msg = checked.msg;
  const size_t n = static_cast<size_t>(options_.loop.num_arenas);
  if (const std::string wrong = hideseek_game::checkActionBatchSize(msg, n); !wrong.empty()) {
    ++rejected_.wrong_arena_count;
    WallThrottle& throttle = throttles_.wrong_arena_count;
    if (throttle.ready()) {
      ROS_WARN("world: rejected %s action batch: %s (%lu more like it since the last)", channel.name.c_str(),
               wrong.c_str(), static_cast<unsigned long>(throttle.suppressed()));
    }
    return;
  }
  const bool lockstep = options_.loop.mode == ClockMode::kLockstep;
  for (size_t i = 0; i < n; ++i) {
    const int arena = static_cast<int>(i);
    const uint32_t current = game_.expectedStepId(channel.player, arena);
    switch (game_.offer(channel.player, arena, msg.actions[i], msg.step[i])) {
      case Verdict::kAccepted:
        break;
      case Verdict::kSupersededByReset:
        ++rejected_.superseded_by_reset;
        ROS_DEBUG("world: %s answered arena %zu's step %u after world/reset restarted it (dropped)",
                  channel.name.c_str(), i, msg.step[i]);
        break;
      case Verdict::kInvalidAction: {
        ++rejected_.invalid_action;
        WallThrottle& throttle = throttles_.invalid_action;
        if (throttle.ready()) {
          ROS_WARN("world: rejected %s action %u for arena %zu: actions are 0..%d (%lu more like it since the last)",
                   channel.name.c_str(), msg.actions[i], i, game_.actions(channel.player) - 1,
                   static_cast<unsigned long>(throttle.suppressed()));
        }
        break;
      }
      case Verdict::kLate: {
        ++rejected_.late;
        WallThrottle& throttle = throttles_.late;
        if (throttle.ready()) {
          ROS_WARN(
              "world: rejected %s action for arena %zu: step %u had started without it "
              "(the agent answered after stale_action_timeout) (%lu more like it since the last)",
              channel.name.c_str(), i, msg.step[i], static_cast<unsigned long>(throttle.suppressed()));
        }
        break;
      }
      case Verdict::kWrongStep: {
        ++rejected_.wrong_step;
        WallThrottle& throttle = throttles_.wrong_step;
        if (throttle.ready()) {
          const std::string awaited = current == hideseek_game::kNoStep
                                          ? std::string("none is awaited while a decision step plays")
                                          : "the current step is " + std::to_string(current);
          ROS_WARN("world: rejected %s action for arena %zu: step id %u, %s (%lu more like it since the last)",
                   channel.name.c_str(), i, msg.step[i], awaited.c_str(),
                   static_cast<unsigned long>(throttle.suppressed()));
        }
        break;
      }
    }
  }
  if (lockstep) tryAdvanceLockstep();
}

void WorldNode::tryAdvanceLockstep() {
  if (!started_) return;
  if (reachedMaxDecisions()) {
    ROS_INFO_ONCE("world: max_decisions (%ld) reached; the world no longer advances", options_.max_decisions);
    return;
  }
  if (!game_.decisionReady()) return;
  if (game_.atStepStart()) beginStepRecord();
  game_.takeDecision();
  // Play frames up to the seeker's next decision, or to the end of the step.
  if (const std::optional<Decision> decision = game_.playToNextDecision()) {
    publishDecision(*decision);
    publishObservations();
    publishArenaZero(false);
    return;
  }
  publishSeekerObservations();
}

void WorldNode::onRealtimeTick(const ros::WallTimerEvent&) {
  if (!started_) {
    // The first episode starts when both players are there (a person's keyboard hider may take
    // seconds to open), and when every listener that must see it listens.
    if (!readyToStart()) {
      publishAgentTransforms(ros::Time::now());
      return;
    }
    started_ = true;
    ROS_INFO("world: both agents connected, starting realtime");
    publishObservations();
    return;
  }
  if (game_.decisionDue()) {
    // A decision step starts once both agents answered its observation, so each decision drives
    // its own step. A slow agent slows the game (diagnostics show the real-time factor) rather
    // than changing it; an agent silent for stale_action_timeout, or absent, stands still for
    // the step, like turtlesim's stale commands. The seeker's later decisions inside the step
    // follow the same rules.
    const bool hider_connected = hider_sub_.getNumPublishers() > 0;
    const bool seeker_connected = seeker_sub_.getNumPublishers() > 0;
    const RealtimeStart start = game_.realtimeStart(ros::WallTime::now().toSec(), hider_connected, seeker_connected);
    if (start == RealtimeStart::kWait) {
      publishAgentTransforms(ros::Time::now());
      return;
    }
    const bool connected = seeker_connected && (hider_connected || !game_.atStepStart());
    if (start == RealtimeStart::kStale && connected) warnStale();
    // The step record's state half is taken before the frames change it.
    if (game_.atStepStart()) beginStepRecord();
    game_.takeDecision();
  }
  // One physics frame per tick. An arena whose step ended early (capture) waits for the others,
  // so every arena's decisions stay on the same 0.12 s clock.
  if (const std::optional<Decision> decision = game_.playFrame()) {
    publishDecision(*decision);
    publishObservations();
    publishArenaZero(true);
    return;
  }
  if (game_.decisionDue()) publishSeekerObservations();
  publishAgentTransforms(ros::Time::now());
}

void WorldNode::warnStale() {
  ++stale_decisions_;
  WallThrottle& throttle = throttles_.stale;
  if (throttle.ready()) {
    ROS_WARN(
        "world: no action for step %d (frame %d) within %.2f s (hider %s, seeker %s): the silent "
        "agent stands still this decision (%lu more like it since the last)",
        game_.world().arena(0).stepCount(), game_.world().frameInStep(), options_.loop.stale_action_timeout,
        game_.answered(Player::kHider, 0) ? "answered" : "silent",
        game_.answered(Player::kSeeker, 0) ? "answered" : "silent", static_cast<unsigned long>(throttle.suppressed()));
  }
}

void WorldNode::onWatchdog(const ros::WallTimerEvent&) {
  const ros::WallTime now = ros::WallTime::now();
  if (!started_) {
    if (!readyToStart()) return;
    started_ = true;
    ROS_INFO("world: both agents connected, starting lockstep");
    publishObservations();
    publishArenaZero(true);
    return;
  }
  if (!reachedMaxDecisions() && game_.resendDue(now.toSec())) {
    if (!game_.atStepStart()) {
      // Inside a step only the seeker has an unanswered observation.
      publishSeekerObservations();
      return;
    }
    // Re-sent only to the agent that has not answered every arena: the other's answer is in, and a
    // second one could arrive after the step moved on (a wrong step, no fault of that agent).
    auto unanswered = [&](const AgentChannel& c) {
      int left = 0;
      for (int i = 0; i < options_.loop.num_arenas; ++i) left += !game_.answered(c.player, i);
      return left;
    };
    const int hider_left = unanswered(hider_), seeker_left = unanswered(seeker_);
    auto status = [&](const AgentChannel& c, int left) {
      return c.name + (c.owner.empty() ? " (no publisher)" : " (" + c.owner + ")") +
             (left ? ": " + std::to_string(left) + " of " + std::to_string(options_.loop.num_arenas) +
                         " arenas unanswered"
                   : ": answered");
    };
    WallThrottle& throttle = throttles_.resend;
    if (throttle.ready()) {
      ROS_WARN(
          "world: waiting %.1f s for step answers, %s; %s; re-sending the step to %s (%lu more like it since the last)",
          game_.sinceSent(now.toSec()), status(hider_, hider_left).c_str(), status(seeker_, seeker_left).c_str(),
          hider_left && seeker_left ? "both" : (hider_left ? hider_ : seeker_).name.c_str(),
          static_cast<unsigned long>(throttle.suppressed()));
    }
    publishObservations(hider_left > 0, seeker_left > 0);
  }
}

void WorldNode::publishDecision(const Decision& decision) {
  last_finished_.reset();
  // Stamped with the time the step started, like its step record.
  const ros::Time stamp = simTime(decision.index);
  for (int i = 0; i < options_.loop.num_arenas; ++i) {
    if (const auto& finished = decision.steps[i].finished) {
      const EpisodeSummary& e = *finished;
      if (i == 0) last_finished_ = e;
      hideseek_msgs::EpisodeResult result;
      result.header.stamp = stamp;
      result.header.frame_id = options_.frame_id;
      result.arena = static_cast<uint32_t>(i);
      result.episode = e.episode;
      result.seed = e.seed;
      result.steps = static_cast<uint32_t>(e.steps);
      result.outcome = static_cast<uint8_t>(e.outcome);
      result.episode_return = static_cast<float>(e.episode_return);
      episodes_pub_.publish(result);
      const auto level = i == 0 ? ros::console::levels::Info : ros::console::levels::Debug;
      ROS_LOG(level, ROSCONSOLE_DEFAULT_NAME, "arena %d episode %u (seed %u): %s after %d steps, return %.3f", i,
              e.episode, e.seed, outcomeName(e.outcome), e.steps, e.episode_return);
    }
  }
  if (step_record_) {
    finishStepBatch(decision.steps, decision.hider, decision.seeker, *step_record_);
    steps_pub_.publish(*step_record_);
    step_record_.reset();
  }
}

void WorldNode::beginStepRecord() {
  if (steps_pub_.getNumSubscribers() == 0) return;
  step_record_ =
      beginStepBatch(game_.world(), game_.decisions(), game_.hiderImages().data(), options_.step_image_every);
  step_record_->header.stamp = simNow();
  step_record_->header.frame_id = options_.frame_id;
}

void WorldNode::publishAgentTransforms(const ros::Time& stamp) {
  const Arena& a = game_.world().arena(0);
  tf_.sendTransform({agentTransform(a.hider(), options_.frame_id, options_.frame("hider/base_link"), stamp),
                     agentTransform(a.seeker(), options_.frame_id, options_.frame("seeker/base_link"), stamp)});
}

void WorldNode::publishObservations(bool to_hider, bool to_seeker) {
  const ros::Time stamp = simNow();
  if (options_.loop.mode == ClockMode::kLockstep) {
    rosgraph_msgs::Clock clock;
    clock.clock = stamp;
    clock_pub_.publish(clock);
  }
  std_msgs::Header header;
  header.stamp = stamp;
  header.frame_id = options_.frame_id;
  if (to_hider) {  // the batch, every arena's image in it, is built only to be sent
    hideseek_msgs::ObservationBatch obs =
        toObservationBatch(game_.world(), game_.hiderImages(), game_.rewards(), game_.done(), game_.outcomes());
    obs.header = header;
    hider_obs_pub_.publish(obs);
  }
  if (to_seeker) {
    publishSeekerObservations(header, game_.done(), game_.seekerRewards(), game_.outcomes(), game_.seekerImages());
  } else {
    game_.observationSent(ros::WallTime::now().toSec());
    ++batches_published_;
  }
}

void WorldNode::publishSeekerObservations() {
  std_msgs::Header header;
  header.stamp = simNow();
  header.frame_id = options_.frame_id;
  // Inside a decision step: the scripted seeker's decision between two of the hider's, no reward.
  const size_t n = static_cast<size_t>(options_.loop.num_arenas);
  publishSeekerObservations(header, std::vector<uint8_t>(n, 0), std::vector<float>(n, 0.f), std::vector<uint8_t>(n, 0),
                            {});
}

void WorldNode::publishSeekerObservations(const std_msgs::Header& header, const std::vector<uint8_t>& done,
                                          const std::vector<float>& rewards, const std::vector<uint8_t>& outcome,
                                          const std::vector<uint8_t>& images) {
  hideseek_msgs::SeekerObservationBatch seen =
      toSeekerObservationBatch(game_.world(), done, arena_maps_.update(game_.world()), rewards, outcome, images);
  seen.header = header;
  seeker_obs_pub_.publish(seen);
  game_.observationSent(ros::WallTime::now().toSec());
  ++batches_published_;
}

void WorldNode::startEpisodeVisuals() {
  const ros::Time stamp = simNow();
  nav_msgs::OccupancyGrid grid = toOccupancyGrid(game_.world().arena(0).layout(), kMapResolution, options_.frame_id);
  grid.header.stamp = stamp;
  grid.info.map_load_time = stamp;
  map_pub_.publish(grid);
  hider_path_.poses.clear();
  seeker_path_.poses.clear();
  hider_path_.header.frame_id = seeker_path_.header.frame_id = options_.frame_id;
}

void WorldNode::publishArenaZero(bool force_visuals) {
  const Arena& a = game_.world().arena(0);
  const ros::Time stamp = simNow();
  const GameOptions& game = options_.variant.game;

  hideseek_msgs::GameState state = toGameState(game_.world(), last_finished_, game_.lastHiderActions()[0],
                                               game_.lastSeekerActions()[0], game_.rewards()[0], game_.outcomes()[0]);
  state.header.stamp = stamp;
  state.header.frame_id = options_.frame_id;
  state_pub_.publish(state);

  publishAgentTransforms(stamp);

  if (last_finished_) startEpisodeVisuals();
  geometry_msgs::PoseStamped hp, sp;
  hp.header.stamp = sp.header.stamp = stamp;
  hp.header.frame_id = sp.header.frame_id = options_.frame_id;
  hp.pose.position.x = a.hider().position.x;
  hp.pose.position.y = a.hider().position.y;
  hp.pose.orientation = agentTransform(a.hider(), "", "", stamp).transform.rotation;
  sp.pose.position.x = a.seeker().position.x;
  sp.pose.position.y = a.seeker().position.y;
  sp.pose.orientation = agentTransform(a.seeker(), "", "", stamp).transform.rotation;
  hider_path_.poses.push_back(hp);
  seeker_path_.poses.push_back(sp);

  // Visual outputs cost time: only for listeners, and in lockstep at most publish_rate per wall second.
  const ros::WallTime now = ros::WallTime::now();
  if (!force_visuals && (now - last_visuals_).toSec() < 1.0 / options_.publish_rate) return;
  last_visuals_ = now;
  if (markers_pub_.getNumSubscribers() > 0) markers_pub_.publish(toMarkers(a, options_.frame_id, stamp));
  hider_path_.header.stamp = seeker_path_.header.stamp = stamp;
  if (hider_path_pub_.getNumSubscribers() > 0) hider_path_pub_.publish(hider_path_);
  if (seeker_path_pub_.getNumSubscribers() > 0) seeker_path_pub_.publish(seeker_path_);
  auto image = [&](const uint8_t* data, const std::string& frame) {
    sensor_msgs::Image img;
    img.header.stamp = stamp;
    img.header.frame_id = frame;
    img.height = game.camera.height;
    img.width = game.camera.width;
    img.encoding = sensor_msgs::image_encodings::RGB8;
    img.step = img.width * 3;
    img.data.assign(data, data + game_.world().imageBytes());
    return img;
  };
  if (hider_camera_pub_.getNumSubscribers() > 0) {
    sensor_msgs::CameraInfo info = camera_info_;
    info.header.stamp = stamp;
    hider_camera_pub_.publish(image(game_.hiderImages().data(), info.header.frame_id), info);
  }
  if (seeker_camera_pub_.getNumSubscribers() > 0) {
    // A learning seeker's images are rendered already: arena 0's is the first.
    const uint8_t* view = game_.seekerImages().data();
    if (game_.seekerImages().empty()) {
      game_.world().renderSeekerView(0, seeker_image_.data());
      view = seeker_image_.data();
    }
    sensor_msgs::CameraInfo info = camera_info_;
    info.header.stamp = stamp;
    info.header.frame_id = options_.frame("seeker/camera_optical_frame");
    seeker_camera_pub_.publish(image(view, info.header.frame_id), info);
  }
}

bool WorldNode::onReset(hideseek_msgs::Reset::Request& req, hideseek_msgs::Reset::Response& res) {
  // A decision step in progress is played to its end first, with the hider's action and the
  // seeker's latest: every arena's step stays whole, and an episode it ends is reported like any
  // other.
  const bool mid_step = !game_.atStepStart();
  std::vector<int> steps_before;
  for (int i = 0; i < options_.loop.num_arenas; ++i) steps_before.push_back(game_.world().arena(i).stepCount());
  std::optional<Decision> finished_step;
  try {
    finished_step = game_.reset(req.arena, req.seed);
    if (finished_step) publishDecision(*finished_step);
  } catch (const std::invalid_argument& e) {
    res.success = false;
    res.message = e.what();
    return true;
  }
  // The episodes the reset cut short end unreported (world/episodes holds finished episodes only):
  // say so, so that a log whose episode numbers skip one reads as it happened. An episode that the
  // step in progress ended was reported; one that had not played a step is not mentioned.
  for (int i = 0; i < options_.loop.num_arenas; ++i) {
    if (req.arena != -1 && req.arena != i) continue;
    if ((finished_step && finished_step->steps[i].finished) || (steps_before[i] == 0 && !mid_step)) continue;
    const auto level = i == 0 || req.arena == i ? ros::console::levels::Info : ros::console::levels::Debug;
    ROS_LOG(level, ROSCONSOLE_DEFAULT_NAME,
            "arena %d episode %u: cut short by world/reset (not on world/episodes); episode %u starts, seed %u", i,
            game_.world().episode(i) - 1, game_.world().episode(i), game_.world().arena(i).seed());
  }
  last_finished_.reset();
  if (req.arena <= 0) startEpisodeVisuals();
  res.success = true;
  res.message = "reset " + (req.arena == -1 ? std::string("all arenas") : "arena " + std::to_string(req.arena));
  if (started_ || options_.loop.mode == ClockMode::kRealtime) {
    publishObservations();
    publishArenaZero(true);
  }
  return true;
}

void WorldNode::printStatus(const ros::WallTimerEvent&) {
  if (!started_) return;
  const Arena& a = game_.world().arena(0);
  const Labels& l = a.labels();
  ROS_INFO("arena 0: episode seed %u, step %d, distance %.1f m; hider %s the seeker, seeker %s the hider", a.seed(),
           a.stepCount(), distance(a.hider().position, a.seeker().position),
           l.hider_sees_seeker ? "sees" : "does not see", l.seeker_sees_hider ? "sees" : "does not see");
}

void WorldNode::publishDiagnostics(const ros::WallTimerEvent&) {
  const ros::WallTime now = ros::WallTime::now();
  const double period = reported_at_.isZero() ? 0.0 : (now - reported_at_).toSec();
  const uint64_t rejections = rejected_.malformed + rejected_.wrong_arena_count + rejected_.invalid_action +
                              rejected_.wrong_step + rejected_.second_publisher + rejected_.late;
  const uint64_t decisions = game_.decisions();
  const double steps_per_s = period > 0.0 ? static_cast<double>(decisions - reported_steps_) / period : 0.0;
  diagnostic_msgs::DiagnosticArray array;
  array.header.stamp = ros::Time::now();
  diagnostic_msgs::DiagnosticStatus status;
  status.name = worldDiagnosticName(ros::this_node::getNamespace());
  status.hardware_id = ros::this_node::getName();
  // The level reflects the last period only: it returns to OK once a problem is over, while the
  // counts below keep the totals.
  const bool rejecting = rejections > reported_rejections_;
  const bool stale = stale_decisions_ > reported_stale_;
  status.level = rejecting || stale ? diagnostic_msgs::DiagnosticStatus::WARN : diagnostic_msgs::DiagnosticStatus::OK;
  status.message = rejecting && stale ? "rejected action messages; an agent missed decisions"
                   : rejecting        ? "rejected malformed or unexpected action messages"
                   : stale            ? "an agent missed decisions (it stood still)"
                                      : "all input accepted";
  auto add = [&](const std::string& key, const std::string& v) {
    diagnostic_msgs::KeyValue kv;
    kv.key = key;
    kv.value = v;
    status.values.push_back(kv);
  };
  auto fixed = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return std::string(buf);
  };
  add("decision_steps_per_s", fixed(steps_per_s));
  // Game seconds per wall second: 1 when realtime keeps up; in lockstep, how much faster than real time.
  add("real_time_factor", fixed(steps_per_s * options_.variant.game.stepDuration()));
  add("rejected_malformed", std::to_string(rejected_.malformed));
  add("rejected_wrong_arena_count", std::to_string(rejected_.wrong_arena_count));
  add("rejected_invalid_action", std::to_string(rejected_.invalid_action));
  add("rejected_wrong_step", std::to_string(rejected_.wrong_step));
  add("rejected_second_publisher", std::to_string(rejected_.second_publisher));
  add("rejected_late", std::to_string(rejected_.late));
  add("dropped_superseded_by_reset", std::to_string(rejected_.superseded_by_reset));
  add("stale_decisions", std::to_string(stale_decisions_));
  add("decision_steps", std::to_string(decisions));
  add("observation_batches", std::to_string(batches_published_));
  array.status.push_back(status);
  diagnostics_pub_.publish(array);
  reported_rejections_ = rejections;
  reported_stale_ = stale_decisions_;
  reported_steps_ = decisions;
  reported_at_ = now;
}

}  // namespace hideseek_world
