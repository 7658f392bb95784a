// Conversions between the world core's types and ROS messages.
#pragma once

#include <geometry_msgs/Pose2D.h>
#include <geometry_msgs/TransformStamped.h>
#include <hideseek_msgs/ArenaMap.h>
#include <hideseek_msgs/GameState.h>
#include <hideseek_msgs/StepBatch.h>
#include <nav_msgs/OccupancyGrid.h>
#include <sensor_msgs/CameraInfo.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <vector>

#include "hideseek_world/arena.h"
#include "hideseek_world/world.h"

namespace hideseek_world {

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

// The state half of a step record: every arena's pose, labels, seed and step before the decision,
// and its hider image (`images`, num_arenas x H x W x 3) when decision % image_every == 0.
hideseek_msgs::StepBatch beginStepBatch(const World& world, uint64_t decision, const uint8_t* images, int image_every);
// The other half: the actions both agents chose and what the step gave each arena.
void finishStepBatch(const std::vector<ArenaStep>& results, const std::vector<Action>& hider,
                     const std::vector<Action>& seeker, hideseek_msgs::StepBatch& batch);

}  // namespace hideseek_world
