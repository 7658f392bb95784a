// Conversions between the world core's types and ROS messages.
#pragma once

#include <geometry_msgs/Pose2D.h>
#include <geometry_msgs/TransformStamped.h>
#include <hideseek_msgs/ArenaMap.h>
#include <hideseek_msgs/GameState.h>
#include <hideseek_msgs/ObservationBatch.h>
#include <hideseek_msgs/SeekerObservationBatch.h>
#include <hideseek_msgs/StepBatch.h>
#include <nav_msgs/OccupancyGrid.h>
#include <sensor_msgs/CameraInfo.h>
#include <visualization_msgs/MarkerArray.h>

#include <optional>
#include <string>
#include <vector>

#include "hideseek_game/arena.h"
#include "hideseek_game/world.h"

namespace hideseek_game {

geometry_msgs::Pose2D toPose2D(const AgentState& agent);
hideseek_msgs::ArenaMap toArenaMap(const Layout& layout);
// Obstacles and walls at `resolution`, 100 occupied, 0 free; origin at the arena's lower-left corner.
nav_msgs::OccupancyGrid toOccupancyGrid(const Layout& layout, double resolution, const std::string& frame_id);
// Pinhole intrinsics of an agent camera (no distortion).
sensor_msgs::CameraInfo toCameraInfo(const CameraOptions& camera, const std::string& optical_frame);
geometry_msgs::TransformStamped agentTransform(const AgentState& agent, const std::string& parent,
                                               const std::string& child, const ros::Time& stamp);
// Obstacles, walls, both agents and their view cones (green: sees the other, grey: does not).
visualization_msgs::MarkerArray toMarkers(const Arena& arena, const std::string& frame_id, const ros::Time& stamp);

// What the hider gets after a decision: every arena's image (`images`, num_arenas x H x W x 3),
// the step's reward, done flag and outcome, the step, episode and seed ids, and the labels.
hideseek_msgs::ObservationBatch toObservationBatch(const World& world, const std::vector<uint8_t>& images,
                                                   const std::vector<float>& rewards, const std::vector<uint8_t>& done,
                                                   const std::vector<uint8_t>& outcome);

// "" for an observation batch a hider can act on: at most max_arenas arenas, every array one entry
// per arena, height x width RGB8 images; otherwise what is wrong, for the receiver's throttled warning.
std::string checkObservationBatch(const hideseek_msgs::ObservationBatch& msg, int height, int width, size_t max_arenas);

// Each arena's map as the seeker receives it, rebuilt only when the arena's layout changes.
class ArenaMapCache {
 public:
  const std::vector<hideseek_msgs::ArenaMap>& update(const World& world);

 private:
  std::vector<hideseek_msgs::ArenaMap> maps_;
  std::vector<uint64_t> versions_;
};

// What the seeker gets: only what it perceives (seekerPerception: its own pose, and the hider's
// position only while it sees the hider), with each arena's map; its rewards and the outcomes of
// the step just played, and every arena's camera image where a learning seeker plays (else empty).
hideseek_msgs::SeekerObservationBatch toSeekerObservationBatch(const World& world, const std::vector<uint8_t>& done,
                                                               const std::vector<hideseek_msgs::ArenaMap>& maps,
                                                               const std::vector<float>& rewards,
                                                               const std::vector<uint8_t>& outcome,
                                                               const std::vector<uint8_t>& images = {});

// "" for a seeker batch whose arrays all hold one entry per arena (at most max_arenas), or what is
// wrong. With a height and width (a learning seeker's), it also needs every arena's image.
std::string checkSeekerObservationBatch(const hideseek_msgs::SeekerObservationBatch& msg, size_t max_arenas,
                                        int height = 0, int width = 0);

// Arena 0's game state after a decision. When the decision ended an episode (`finished`), the
// state is that episode's end, not the next episode's start.
hideseek_msgs::GameState toGameState(const World& world, const std::optional<EpisodeSummary>& finished,
                                     Action hider_action, Action seeker_action, float reward, uint8_t outcome);

// The state half of a step record: every arena's pose, labels, seed and step before the decision,
// and its hider image (`images`, num_arenas x H x W x 3) when decision % image_every == 0.
hideseek_msgs::StepBatch beginStepBatch(const World& world, uint64_t decision, const uint8_t* images, int image_every);
// The other half: the actions both agents chose and what the step gave each arena.
void finishStepBatch(const std::vector<ArenaStep>& results, const std::vector<Action>& hider,
                     const std::vector<Action>& seeker, hideseek_msgs::StepBatch& batch);

}  // namespace hideseek_game
