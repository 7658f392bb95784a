#include "hideseek_play/scripted_game.h"

#include <algorithm>
#include <utility>

#include "hideseek_game/arena.h"
#include "hideseek_game/game_loop.h"

namespace hideseek_play {

using hideseek_game::Action;
using hideseek_game::Arena;
using hideseek_hider::ScriptedEvader;
using hideseek_seeker::seekerOptionsFor;
using hideseek_seeker::SeekerPolicy;

std::vector<ScriptedEpisode> playScriptedHider(const hideseek_game::VariantConfig& variant,
                                               std::shared_ptr<const hideseek_game::MapSpec> map, EvaderKind evader,
                                               uint32_t first_seed, int episodes, const ScriptedStepObserver& observe,
                                               const EvaderOptions& evader_options) {
  // One arena, unrendered (a scripted hider needs no image), playing seeds first_seed, first_seed + 1, ...
  hideseek_game::GameLoopOptions loop_options;
  loop_options.seed = first_seed;
  loop_options.render = false;
  hideseek_game::GameLoop game(variant.game, std::move(map), loop_options);
  const Arena& arena = game.world().arena(0);
  SeekerPolicy seeker(seekerOptionsFor(variant));
  ScriptedEvader hider(evader, variant.game, evader_options);
  const hideseek_game::ArenaSeekerDecide decide = [&](int, const hideseek_game::SeekerPerception& p) {
    return seeker.act(p);
  };
  std::vector<ScriptedEpisode> out;
  for (int e = 0; e < episodes; ++e) {
    ScriptedEpisode episode;
    episode.seed = arena.seed();
    seeker.reset(arena.layout(), episode.seed);
    hider.reset(arena.layout());
    episode.seen_at_start = arena.labels().seeker_sees_hider;
    // The world node's lockstep order: both agents answer the observation of step t (the seeker
    // again before each of its later decisions in the step), then the arena advances.
    for (;;) {
      const auto step = static_cast<uint32_t>(arena.stepCount());
      const Action hider_action = hider.act({arena.hider(), arena.seeker(), episode.seed, step});
      if (observe)
        observe({episode.seed, static_cast<int>(step), arena.hider(), arena.seeker(), arena.labels(), hider_action});
      const hideseek_game::Decision d = game.step({hider_action}, decide);
      if (const auto& finished = d.steps[0].finished) {
        episode.living_steps = finished->steps;
        episode.survived = finished->outcome == hideseek_game::Outcome::kSurvived;
        break;
      }
    }
    out.push_back(episode);
  }
  return out;
}

ScriptedSummary summarize(const std::vector<ScriptedEpisode>& episodes) {
  ScriptedSummary s;
  s.episodes = static_cast<int>(episodes.size());
  if (episodes.empty()) return s;
  std::vector<int> steps;
  for (const auto& e : episodes) {
    steps.push_back(e.living_steps);
    s.avg_living_steps += e.living_steps;
    s.success_rate += e.survived;
    s.seen_at_start_rate += e.seen_at_start;
  }
  s.avg_living_steps /= s.episodes;
  s.success_rate /= s.episodes;
  s.seen_at_start_rate /= s.episodes;
  std::sort(steps.begin(), steps.end());
  const size_t n = steps.size();
  s.median_living_steps = n % 2 ? steps[n / 2] : 0.5 * (steps[n / 2 - 1] + steps[n / 2]);
  return s;
}

}  // namespace hideseek_play
