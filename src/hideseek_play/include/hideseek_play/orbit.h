// The orbit study (issue #65): a hider circling in the open on a fixed pattern of its five
// actions, against the scripted seeker started at chosen angles round the circle. Game v2's
// seeker turns or moves, never both, so while it chases a circling hider it moves in only part of
// its frames; learned hiders found that it then trails them round for good. This measures which
// orbits a game's seeker catches, without training.
#pragma once

#include <vector>

#include "hideseek_game/game_options.h"

namespace hideseek_play {

// Forward for `forward_steps` decision steps, then one turn step (left), over and over: a polygon
// close to a circle whose radius grows with forward_steps (orbitRadius).
struct OrbitShape {
  int forward_steps = 1;
};

// The circle's radius (m) and the hider's mean speed round it (m/s) under a game's hider motion
// (constant-speed hiders; the accelerating hider's orbit depends on its history).
double orbitRadius(const hideseek_game::GameOptions& game, OrbitShape shape);
double orbitSpeed(const hideseek_game::GameOptions& game, OrbitShape shape);

struct OrbitEpisode {
  double start_angle_deg = 0.0;  // where the seeker starts, round the circle's centre
  int living_steps = 0;
  bool survived = false;
  double seen_share = 0.0;     // decision steps after which the seeker sees the hider
  double mutual_share = 0.0;   // decision steps after which each agent sees the other
  double mean_distance = 0.0;  // m between the agents, over the decision steps
};

// One episode in an open arena of `half_extent` m: the hider starts on the circle round the
// arena's centre, heading along it; the seeker starts `gap` m outside the circle at
// `start_angle_deg`, facing the hider's start. The seeker is the variant's (its steering, speeds,
// decision rate and spawn knowledge); the episode lasts up to the game's max_steps. Throws
// std::invalid_argument when the circle and the gap do not fit inside the arena.
OrbitEpisode playOrbit(const hideseek_game::VariantConfig& variant, OrbitShape shape, double start_angle_deg,
                       double gap = 3.0, double half_extent = 7.0);

// The same shape from `angles` start angles evenly round the circle.
std::vector<OrbitEpisode> playOrbitAngles(const hideseek_game::VariantConfig& variant, OrbitShape shape, int angles,
                                          double gap = 3.0, double half_extent = 7.0);

}  // namespace hideseek_play
