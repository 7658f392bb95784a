// Who sees whom: the geometric test every label, reward and seeker perception uses.
#pragma once

#include "hideseek_game/agent.h"

namespace hideseek_game {

// A viewer sees a target when a sampled point of the target's silhouette is inside the viewer's
// camera frustum and the sight line to it crosses no obstacle. Walls never occlude one agent from
// another: the segment between two points inside the convex arena stays inside it.
bool agentSeesAgent(const AgentState& viewer, const AgentState& target, const Layout& layout,
                    const GameOptions& options);

// True when at least one obstacle (not wall, not floor) is in the viewer's camera image.
bool obstacleInView(const AgentState& viewer, const Layout& layout, const GameOptions& options);

// How far a horizontal sight line at `height` from `origin` along `yaw` runs before it meets an
// obstacle or a wall (at most max_range): where a view cone drawn on the floor should stop.
double sightRange(Vec2 origin, double yaw, double height, const Layout& layout, double max_range);

}  // namespace hideseek_game
