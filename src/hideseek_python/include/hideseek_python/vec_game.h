// The game as a batched environment for Python (the hideseek module): the world's arenas and each
// arena's scripted seeker, stepped in process by GameLoop, the one game loop the world node also
// serves. The same seeds and hider actions give the same images, rewards, labels and episodes as
// the ROS graph in lockstep and as play_episodes. Free of ROS and of Python: the pybind11 layer
// (module.cpp) only converts arrays.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "hideseek_game/game_loop.h"
#include "hideseek_game/game_options.h"
#include "hideseek_hider/scripted_evader.h"
#include "hideseek_seeker/seeker_policy.h"

namespace hideseek_python {

// A game and variant under a config folder (the hideseek_game package's config/), resolved as
// every node resolves them (hideseek_game::selectGame). Throws hideseek_game::ConfigError naming
// the unknown game or variant (with those there), or the bad file and field.
// variant_file: a variant file of one's own, whose variant field must be `variant` (empty: the
// config folder's variants/VARIANT.yaml).
hideseek_game::VariantConfig loadVariant(const std::string& config_dir, const std::string& game,
                                         const std::string& variant, const std::string& variant_file = "");

// One arena's state after a step or reset, as the world node's ObservationBatch carries it: after
// an episode ended, everything but the reward and outcome already describes the next episode.
struct ArenaInfo {
  bool hider_sees_seeker = false;    // S
  bool seeker_sees_hider = false;    // H
  bool obstacle_in_view = false;     // O
  double hider_pose[3] = {0, 0, 0};  // x, y (m), yaw (rad) in the map frame
  double seeker_pose[3] = {0, 0, 0};
  uint32_t seed = 0;     // the episode's seed
  uint32_t step = 0;     // decision steps taken in the episode
  uint32_t episode = 0;  // the arena's episode counter
};

class VecGame {
 public:
  // num_envs arenas; arena i's first episode has seed seed + i, its later ones seed + i + k num_envs.
  // seeker_outside: the seeker's actions come from outside (step's second argument: a learner, a
  // policy or the random seeker), decided once a step on its own camera (seekerObservations), as
  // the seeker node's policy and train modes play; else each arena's scripted seeker plays.
  VecGame(const hideseek_game::VariantConfig& variant, int num_envs, uint32_t seed, int render_threads = 2,
          bool seeker_outside = false);

  int numEnvs() const { return game_.numArenas(); }
  int height() const { return variant_.game.camera.height; }
  int width() const { return variant_.game.camera.width; }
  int maxSteps() const { return variant_.game.max_steps; }
  const hideseek_game::VariantConfig& variant() const { return variant_; }

  // Starts a new episode in every arena: with seeds (one per arena), with seed + i in arena i
  // (one seed), or with the next seed of each arena's sequence (none). Where every arena's episode
  // has just started (construction or reset, no step since) with the seeds asked, or with none
  // asked, nothing changes but the evaders' state, so no seed of the sequence is skipped.
  // Throws
  // std::invalid_argument for a wrong count or a seed outside [0, 2^32).
  void reset(const std::vector<int64_t>& seeds);
  // Starts a new episode in one arena (seed -1: the next of its sequence).
  void resetEnv(int env, int64_t seed);
  // One decision step of every arena with the hider's actions (0..4, ActionBatch's values); each
  // seeker decides on its perception as the seeker node does. An arena whose episode ends starts
  // its next one within the step: observations() is then its first image, and the terminal
  // state's image is terminalObservations()'s. Throws
  // std::invalid_argument, changing nothing, for a wrong count or an action out of range.
  void step(const std::vector<uint8_t>& actions);
  // The same with the seeker's actions too (seeker_outside only; 0..seekerActions()-1).
  void step(const std::vector<uint8_t>& actions, const std::vector<uint8_t>& seeker_actions);
  bool seekerOutside() const { return seeker_outside_; }
  int seekerActions() const { return hideseek_game::actionCount(variant_.game, true); }
  // What the seeker observes (seeker_outside only): every arena's camera image and its rewards.
  const std::vector<uint8_t>& seekerObservations() const { return game_.seekerImages(); }
  const std::vector<float>& seekerRewards() const { return game_.seekerRewards(); }
  // The uniformly random seeker's actions for the current state (the seeker node's random mode).
  std::vector<uint8_t> randomSeekerActions() const;

  // After the last step or reset, per arena.
  const std::vector<uint8_t>& observations() const { return game_.hiderImages(); }  // rgb8, rows top down
  const std::vector<float>& rewards() const { return game_.rewards(); }
  // 1 where the step ended the episode; outcome 1 captured (termination), 2 survived max_steps (truncation).
  const std::vector<uint8_t>& done() const { return game_.done(); }
  const std::vector<uint8_t>& outcomes() const { return game_.outcomes(); }
  ArenaInfo info(int env) const;
  // The episode the last step ended in arena env (length, return, terminal state), if it did.
  const std::optional<hideseek_game::EpisodeSummary>& finished(int env) const { return finished_[env]; }
  // From now on, renders the terminal state of every episode that ends as the camera of one side
  // shows it (the seeker's: seeker_outside only); the game itself never shows it. For a learner
  // that bootstraps on a truncation (Gymnasium's final_obs); one view an episode.
  void keepTerminalViews(bool seeker);
  // That episode's terminal image (arena env's at env * height() * width() * 3, where
  // finished(env)); empty before keepTerminalViews.
  const std::vector<uint8_t>& terminalObservations() const { return game_.world().terminalImages(); }
  // Decision steps taken since construction.
  uint64_t decisions() const { return game_.decisions(); }
  // VecGame is not thread-safe: the Python layer holds this around every call, so that two threads
  // sharing one environment take turns instead of racing.
  std::mutex& mutex() const { return mutex_; }

  // A scripted hider's actions for the current state of every arena (random: the paper's random
  // hider, drawn from seed and step; backpedal, flee, hide, lap: evaders that read the true state),
  // as policy:=scripted/NAME plays them in process. The evaders keep state within an episode
  // (their goal and path): ask once per step, as the graph does.
  std::vector<uint8_t> scriptedActions(hideseek_hider::EvaderKind kind);

 private:
  void episodeStarted(int env);

  hideseek_game::VariantConfig variant_;
  bool seeker_outside_;
  hideseek_game::GameLoop game_;
  std::vector<hideseek_seeker::SeekerPolicy> seekers_;
  std::vector<std::optional<hideseek_game::EpisodeSummary>> finished_;
  mutable std::mutex mutex_;
  bool untouched_ = true;         // no step or single-arena reset since construction or reset()
  std::vector<uint64_t> starts_;  // episodes started per arena, so that evaders reset once per episode
  struct Evaders {
    std::vector<hideseek_hider::ScriptedEvader> arenas;
    std::vector<uint64_t> reset_at;  // starts_ when each was last reset
  };
  std::vector<std::unique_ptr<Evaders>> evaders_;  // per EvaderKind, made when first asked
};

}  // namespace hideseek_python
