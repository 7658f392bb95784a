// A scripted hider (the random hider or an evader) against the scripted seeker, played in process
// with the same cores, draws and frame order as the ROS graph in lockstep (no rendering: a
// scripted hider needs no image). This is what calibrates the game against the paper's random
// hider and shows which strategies the game rewards.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "hideseek_game/arena.h"
#include "hideseek_game/game_options.h"
#include "hideseek_game/map.h"
#include "hideseek_hider/scripted_evader.h"
#include "hideseek_seeker/seeker_policy.h"

namespace hideseek_play {

using hideseek_hider::EvaderKind;
using hideseek_hider::EvaderOptions;

struct ScriptedEpisode {
  uint32_t seed = 0;
  int living_steps = 0;  // decision steps until capture, or max_steps
  bool survived = false;
  bool seen_at_start = false;  // the seeker saw the hider at step 0
};

// One decision of an episode: the state both agents chose in, and the hider's action.
struct ScriptedStep {
  uint32_t seed = 0;
  int step = 0;
  hideseek_game::AgentState hider, seeker;
  hideseek_game::Labels labels;
  hideseek_game::Action hider_action = hideseek_game::Action::kStay;
};
using ScriptedStepObserver = std::function<void(const ScriptedStep&)>;

// Plays the episodes with seeds first_seed .. first_seed + episodes - 1, in seed order; `observe`,
// when given, sees every decision (the state statistics of the scripted hiders).
std::vector<ScriptedEpisode> playScriptedHider(const hideseek_game::VariantConfig& variant,
                                               std::shared_ptr<const hideseek_game::MapSpec> map, EvaderKind evader,
                                               uint32_t first_seed, int episodes,
                                               const ScriptedStepObserver& observe = {},
                                               const EvaderOptions& evader_options = {});

// Summary of a set of episodes.
struct ScriptedSummary {
  int episodes = 0;
  double avg_living_steps = 0.0;
  double median_living_steps = 0.0;
  double success_rate = 0.0;        // fraction that survived max_steps
  double seen_at_start_rate = 0.0;  // fraction in which the seeker saw the hider at step 0
};
ScriptedSummary summarize(const std::vector<ScriptedEpisode>& episodes);

}  // namespace hideseek_play
