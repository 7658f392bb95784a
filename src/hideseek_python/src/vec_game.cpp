#include "hideseek_python/vec_game.h"

#include <stdexcept>
#include <utility>

#include "hideseek_game/game_selection.h"
#include "hideseek_game/hash_uniform.h"
#include "hideseek_game/map.h"

namespace hideseek_python {

namespace hg = hideseek_game;

hg::VariantConfig loadVariant(const std::string& config_dir, const std::string& game, const std::string& variant,
                              const std::string& variant_file) {
  return hg::selectGame(config_dir, game, variant, variant_file).config;
}

namespace {

hg::GameLoopOptions loopOptions(int num_envs, uint32_t seed, int render_threads, bool seeker_outside) {
  if (num_envs < 1 || num_envs > 64)
    throw std::invalid_argument("num_envs must be in [1, 64], got " + std::to_string(num_envs));
  if (render_threads < 1) throw std::invalid_argument("render_threads must be >= 1");
  hg::GameLoopOptions o;
  o.num_arenas = num_envs;
  o.seed = seed;
  o.render = true;
  o.render_threads = render_threads;
  o.render_seeker = seeker_outside;
  return o;
}

// The game as played: a seeker from outside decides once a step, as a learning seeker does.
hg::VariantConfig played(hg::VariantConfig v, bool seeker_outside) {
  if (seeker_outside) v.game = hg::withLearnedSeeker(v.game);
  return v;
}

}  // namespace

VecGame::VecGame(const hg::VariantConfig& variant, int num_envs, uint32_t seed, int render_threads, bool seeker_outside)
    : variant_(played(variant, seeker_outside)),
      seeker_outside_(seeker_outside),
      game_(variant_.game, std::make_shared<const hg::MapSpec>(hg::loadMapFile(variant_.map_file)),
            loopOptions(num_envs, seed, render_threads, seeker_outside)),
      finished_(num_envs),
      starts_(num_envs, 0),
      evaders_(std::size(hideseek_hider::kAllEvaders)) {
  seekers_.reserve(num_envs);
  for (int i = 0; i < num_envs; ++i) {
    seekers_.emplace_back(hideseek_seeker::seekerOptionsFor(variant_));
    episodeStarted(i);
  }
}

void VecGame::episodeStarted(int env) {
  const hg::Arena& arena = game_.world().arena(env);
  seekers_[env].reset(arena.layout(), arena.seed());
  ++starts_[env];
}

void VecGame::reset(const std::vector<int64_t>& seeds) {
  const int n = numEnvs();
  if (seeds.size() > 1 && seeds.size() != static_cast<size_t>(n)) {
    throw std::invalid_argument(std::to_string(seeds.size()) + " seeds for " + std::to_string(n) +
                                " environments: give one seed, one per environment, or none");
  }
  for (const int64_t s : seeds) {
    if (s < 0 || s > static_cast<int64_t>(UINT32_MAX)) throw std::invalid_argument("a seed must be in [0, 2^32)");
  }
  if (seeds.size() == 1 && seeds[0] + n - 1 > static_cast<int64_t>(UINT32_MAX))
    throw std::invalid_argument("seed + num_envs - 1 must be below 2^32");
  // Episodes just started with these seeds, not yet stepped, are already what a reset would start:
  // kept, so that the episode counters stay the world node's (reset(seed) after construction with
  // that seed starts nothing new, as the node starts nothing before its first decision).
  bool same = untouched_;
  for (int i = 0; same && !seeds.empty() && i < n; ++i)
    same = game_.world().arena(i).seed() == static_cast<uint32_t>(seeds.size() == 1 ? seeds[0] + i : seeds[i]);
  if (same) {
    for (int i = 0; i < n; ++i) ++starts_[i];  // the evaders start the episode afresh
    return;
  }
  untouched_ = true;
  if (seeds.size() <= 1) {
    game_.reset(-1, seeds.empty() ? -1 : seeds[0]);
  } else {
    for (int i = 0; i < n; ++i) game_.reset(i, seeds[i]);
  }
  for (int i = 0; i < n; ++i) {
    finished_[i].reset();
    episodeStarted(i);
  }
}

void VecGame::resetEnv(int env, int64_t seed) {
  if (env < 0 || env >= numEnvs())
    throw std::invalid_argument("environment " + std::to_string(env) + " does not exist");
  game_.reset(env, seed);
  untouched_ = false;
  finished_[env].reset();
  episodeStarted(env);
}

void VecGame::step(const std::vector<uint8_t>& actions) {
  if (seeker_outside_) {
    throw std::invalid_argument("this game's seeker plays from outside: step(hider actions, seeker actions)");
  }
  step(actions, {});
}

void VecGame::step(const std::vector<uint8_t>& actions, const std::vector<uint8_t>& seeker_actions) {
  const int n = numEnvs();
  if (seeker_outside_ && seeker_actions.size() != static_cast<size_t>(n)) {
    throw std::invalid_argument(std::to_string(seeker_actions.size()) + " seeker actions for " + std::to_string(n) +
                                " environments");
  }
  if (!seeker_outside_ && !seeker_actions.empty()) {
    throw std::invalid_argument("this game's seeker is the variant's scripted one: give the hider's actions alone");
  }
  for (int i = 0; seeker_outside_ && i < n; ++i) {
    if (seeker_actions[i] >= seekerActions()) {
      throw std::invalid_argument("seeker action " + std::to_string(seeker_actions[i]) + " of environment " +
                                  std::to_string(i) + " is not in [0, " + std::to_string(seekerActions()) + ")");
    }
  }
  if (actions.size() != static_cast<size_t>(n)) {
    throw std::invalid_argument(std::to_string(actions.size()) + " actions for " + std::to_string(n) + " environments");
  }
  std::vector<hg::Action> hider(n);
  for (int i = 0; i < n; ++i) {
    if (actions[i] >= hg::kNumActions) {
      throw std::invalid_argument("action " + std::to_string(actions[i]) + " of environment " + std::to_string(i) +
                                  " is not in [0, 5)");
    }
    hider[i] = static_cast<hg::Action>(actions[i]);
  }
  untouched_ = false;
  const hg::Decision d = game_.step(hider, [&](int i, const hg::SeekerPerception& p) {
    return seeker_outside_ ? static_cast<hg::Action>(seeker_actions[i]) : seekers_[i].act(p);
  });
  for (int i = 0; i < n; ++i) {
    finished_[i] = d.steps[i].finished;
    if (finished_[i]) episodeStarted(i);
  }
}

void VecGame::keepTerminalViews(bool seeker) {
  if (seeker && !seeker_outside_)
    throw std::invalid_argument("the scripted seeker's side is not played: no seeker view");
  game_.world().keepTerminalViews(seeker);
}

std::vector<uint8_t> VecGame::randomSeekerActions() const {
  std::vector<uint8_t> a(numEnvs());
  for (int i = 0; i < numEnvs(); ++i) {
    const hg::Arena& arena = game_.world().arena(i);
    a[i] =
        hg::hashAction(arena.seed(), static_cast<uint32_t>(arena.stepCount()), hg::kSaltRandomSeeker, seekerActions());
  }
  return a;
}

ArenaInfo VecGame::info(int env) const {
  const hg::Arena& a = game_.world().arena(env);
  ArenaInfo info;
  info.hider_sees_seeker = a.labels().hider_sees_seeker;
  info.seeker_sees_hider = a.labels().seeker_sees_hider;
  info.obstacle_in_view = a.labels().obstacle_in_view;
  const hg::AgentState &h = a.hider(), &s = a.seeker();
  info.hider_pose[0] = h.position.x;
  info.hider_pose[1] = h.position.y;
  info.hider_pose[2] = h.yaw;
  info.seeker_pose[0] = s.position.x;
  info.seeker_pose[1] = s.position.y;
  info.seeker_pose[2] = s.yaw;
  info.seed = a.seed();
  info.step = static_cast<uint32_t>(a.stepCount());
  info.episode = game_.world().episode(env);
  return info;
}

std::vector<uint8_t> VecGame::scriptedActions(hideseek_hider::EvaderKind kind) {
  const int n = numEnvs();
  std::unique_ptr<Evaders>& e = evaders_[static_cast<size_t>(kind)];
  if (!e) {
    e = std::make_unique<Evaders>();
    for (int i = 0; i < n; ++i) e->arenas.emplace_back(kind, variant_.game);
    e->reset_at.assign(n, 0);
  }
  std::vector<uint8_t> actions(n);
  for (int i = 0; i < n; ++i) {
    const hg::Arena& a = game_.world().arena(i);
    if (e->reset_at[i] != starts_[i]) {
      e->arenas[i].reset(a.layout());
      e->reset_at[i] = starts_[i];
    }
    actions[i] =
        static_cast<uint8_t>(e->arenas[i].act({a.hider(), a.seeker(), a.seed(), static_cast<uint32_t>(a.stepCount())}));
  }
  return actions;
}

}  // namespace hideseek_python
