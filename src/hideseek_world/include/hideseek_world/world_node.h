// Wires the game core to ROS: observation and action batches, standard outputs for arena 0.
#pragma once

#include <diagnostic_msgs/DiagnosticArray.h>
#include <hideseek_msgs/ActionBatch.h>
#include <hideseek_msgs/ArenaMap.h>
#include <hideseek_msgs/EpisodeResult.h>
#include <hideseek_msgs/Reset.h>
#include <hideseek_msgs/StepBatch.h>
#include <image_transport/image_transport.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hideseek_game/checked_action_batch.h"
#include "hideseek_game/decision_scheduler.h"
#include "hideseek_game/game_loop.h"
#include "hideseek_game/msg_conversion.h"
#include "hideseek_game/wall_throttle.h"
#include "hideseek_game/world.h"
#include "hideseek_world/world_node_options.h"

namespace hideseek_world {

// The game's types, which the node serves over ROS.
using hideseek_game::Action;
using hideseek_game::ArenaMapCache;
using hideseek_game::ArenaStep;
using hideseek_game::Decision;
using hideseek_game::EpisodeSummary;
using hideseek_game::GameLoop;
using hideseek_game::Player;
using hideseek_game::WallThrottle;
using hideseek_game::World;

// Counts of rejected input, published on /diagnostics.
struct RejectionCounts {
  uint64_t malformed = 0;  // bytes that are no ActionBatch (hideseek_game::parseActionBatch)
  uint64_t wrong_arena_count = 0;
  uint64_t invalid_action = 0;
  uint64_t wrong_step = 0;
  uint64_t second_publisher = 0;
  uint64_t late = 0;  // realtime: arrived after its step had started without it
  // An answer to the step an arena was at when world/reset restarted it: expected, so counted
  // apart and not warned about (an agent answering while the reset happens sends one).
  uint64_t superseded_by_reset = 0;
};

// One agent's side of the exchange: who may send its actions.
struct AgentChannel {
  std::string name;  // "hider" or "seeker"
  Player player = Player::kHider;
  std::string owner;  // caller id of the accepted publisher
  ros::WallTime owner_last_seen;
};

// The warnings the node repeats at most once per period each, with how many it held back.
struct WarningThrottles {
  WallThrottle malformed{2.0}, second_publisher{2.0}, wrong_arena_count{2.0}, invalid_action{2.0}, late{2.0},
      wrong_step{2.0}, stale{2.0}, resend{10.0}, waiting{10.0};
};

// The game loop (hideseek_game::GameLoop) served over ROS: the node turns action messages into
// offers, decisions into observation batches, episode results, step records and arena 0's
// visuals, and keeps the wall-clock side (who publishes, re-sends, realtime ticks, diagnostics).
// All callbacks run on the one spinner thread that created the node, which also owns the
// OSMesa context of the renderer.
class WorldNode {
 public:
  WorldNode(ros::NodeHandle nh, ros::NodeHandle private_nh);

 private:
  void onActions(const ros::MessageEvent<const hideseek_game::CheckedActionBatch>& event, AgentChannel& channel);
  bool acceptPublisher(const std::string& caller, AgentChannel& channel);
  void tryAdvanceLockstep();
  void onRealtimeTick(const ros::WallTimerEvent&);
  void onWatchdog(const ros::WallTimerEvent&);
  bool onReset(hideseek_msgs::Reset::Request& req, hideseek_msgs::Reset::Response& res);
  // Publishes a finished decision step: its episode results and its step record.
  void publishDecision(const Decision& decision);
  // The state half of world/steps' record of the decision about to be taken, when someone listens.
  void beginStepRecord();
  void publishAgentTransforms(const ros::Time& stamp);
  // Both agents' observation batches of the decision due; a lockstep re-send goes only to the
  // agent that has not answered.
  void publishObservations(bool to_hider = true, bool to_seeker = true);
  // The seeker's observation alone: its later decisions inside a step.
  void publishSeekerObservations();
  void publishSeekerObservations(const std_msgs::Header& header, const std::vector<uint8_t>& done,
                                 const std::vector<float>& rewards, const std::vector<uint8_t>& outcome,
                                 const std::vector<uint8_t>& images);
  // Counts and warns about a decision an agent missed (realtime).
  void warnStale();
  void publishArenaZero(bool force_visuals);
  void startEpisodeVisuals();
  void publishDiagnostics(const ros::WallTimerEvent&);
  // One console line on arena 0: its episode and step, the distance, who sees whom.
  void printStatus(const ros::WallTimerEvent&);
  // Sim time after `decisions` decision steps (lockstep), or wall time (realtime).
  ros::Time simTime(uint64_t decisions) const;
  ros::Time simNow() const { return simTime(game_.decisions()); }
  // Before the start: may the game start (every agent and required listener there)? While it may
  // not, says every 10 s, after the first 10, whom it waits for.
  bool readyToStart();
  bool reachedMaxDecisions() const;

  ros::NodeHandle nh_;
  image_transport::ImageTransport image_transport_;  // cameras go out through image_transport's plugins
  WorldNodeOptions options_;
  GameLoop game_;  // the arenas, the decision rules, what the hider observes
  std::vector<uint8_t> seeker_image_;
  AgentChannel hider_;
  AgentChannel seeker_;
  RejectionCounts rejected_;
  WarningThrottles throttles_;
  uint64_t batches_published_ = 0;
  ros::WallTime last_visuals_;
  bool started_ = false;
  std::optional<ros::WallTime> waiting_since_;           // when the world first found someone missing
  std::optional<EpisodeSummary> last_finished_;          // arena 0's episode that ended in the last step
  std::optional<hideseek_msgs::StepBatch> step_record_;  // world/steps: the decision being taken

  image_transport::CameraPublisher hider_camera_pub_, seeker_camera_pub_;
  ros::Publisher hider_obs_pub_, seeker_obs_pub_, clock_pub_, markers_pub_, map_pub_, hider_path_pub_, seeker_path_pub_,
      state_pub_, episodes_pub_, steps_pub_, diagnostics_pub_;
  ros::Subscriber hider_sub_, seeker_sub_;
  ros::ServiceServer reset_srv_;
  ros::WallTimer tick_timer_, watchdog_timer_, diagnostics_timer_, status_timer_;
  tf2_ros::TransformBroadcaster tf_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  nav_msgs::Path hider_path_, seeker_path_;
  sensor_msgs::CameraInfo camera_info_;
  // Each arena's map as the seeker receives it, rebuilt only when the arena's layout changes.
  ArenaMapCache arena_maps_;
  uint64_t stale_decisions_ = 0;  // decisions an agent missed (it stood still)
  // Diagnostics: the counts at the previous report, so that a status returns to OK once a
  // problem is over.
  uint64_t reported_rejections_ = 0, reported_stale_ = 0, reported_steps_ = 0;
  ros::WallTime reported_at_;
};

}  // namespace hideseek_world
