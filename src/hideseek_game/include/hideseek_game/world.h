// Many independent arenas stepped and rendered together: what the world node drives.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "hideseek_game/arena.h"
#include "hideseek_game/renderer.h"

namespace hideseek_game {

// How an episode ended, captured before the arena starts its next one.
struct EpisodeSummary {
  uint32_t episode = 0;
  uint32_t seed = 0;
  int steps = 0;
  double episode_return = 0.0;
  Outcome outcome = Outcome::kRunning;
  AgentState hider;
  AgentState seeker;
  Labels labels;
  double seeker_return = 0.0;  // a learning seeker's return (seeker_rewards)
};

struct ArenaStep {
  StepResult result;
  std::optional<EpisodeSummary> finished;  // set when this step ended the episode
};

// Arena i plays episodes with seeds seed + i, seed + i + n, seed + i + 2n, ... (n arenas), so
// the first episodes of all arenas together cover seeds seed .. seed + k n - 1 whatever the timing.
// A seed_stride other than n replaces n in that sequence: the ranks of a data-parallel training,
// rank r with seed + r n and stride (ranks x n), together play the seeds one world of ranks x n
// arenas would.
class World {
 public:
  World(const GameOptions& options, std::shared_ptr<const MapSpec> map, int num_arenas, uint32_t seed, bool render,
        int render_threads = 2, uint32_t seed_stride = 0);  // seed_stride 0: num_arenas

  int numArenas() const { return static_cast<int>(arenas_.size()); }
  const GameOptions& options() const { return options_; }
  const Arena& arena(int i) const { return arenas_[i]; }
  uint32_t episode(int i) const { return episodes_[i]; }

  // Starts a new episode in arena i, with `seed` or the next of its sequence; the sequence
  // then continues from the seed used.
  void resetArena(int i, std::optional<uint32_t> seed);
  // Advances arena i one decision step with fixed actions; a finished episode is replaced by the
  // next one.
  ArenaStep stepArena(int i, Action hider, Action seeker);
  // Advances arena i one decision step, asking the in-process seeker at each of its decisions.
  ArenaStep stepArena(int i, Action hider, const SeekerDecide& seeker);

  // The world node's exchange, all arenas in phase: a decision step is action_repeat frames, and
  // the seeker decides before every seeker_decision_frames-th of them (SeekerObservationBatch).
  int frameInStep() const { return frame_; }
  bool seekerDecisionDue() const { return frame_ % options_.seeker_decision_frames == 0; }
  // The decision step arena i is in, counted from its episode's start: its step count, less the
  // step a capture ended early while the other arenas' frames play. At a step's start, the step
  // about to be taken.
  int stepPlaying(int i) const;
  // Arena i's seeker decision about to be taken, counted from its episode's start: the step id
  // of the seeker's exchange (the hider's step id when the seeker decides once a step).
  uint32_t seekerDecisionId(int i) const;
  // Plays one physics frame of every arena whose decision step still runs (a capture ends an
  // arena's step early; it then waits for the others). After the step's last frame returns every
  // arena's result, finished episodes replaced by their next ones; else nothing.
  std::optional<std::vector<ArenaStep>> advanceFrame(const std::vector<Action>& hider,
                                                     const std::vector<Action>& seeker);

  // Renders every arena's hider camera into out (numArenas() images, rgb8, rows top down).
  void renderHiderViews(uint8_t* out, RenderMode mode = RenderMode::kColor);
  // Renders every arena's seeker camera into out (numArenas() images): a learning seeker's input.
  void renderSeekerViews(uint8_t* out, RenderMode mode = RenderMode::kColor);
  // Renders one arena's seeker camera into out (one image).
  void renderSeekerView(int i, uint8_t* out, RenderMode mode = RenderMode::kColor);
  size_t imageBytes() const;

  // From now on, also renders each episode's terminal state before its arena starts the next
  // episode: the hider's camera, or the seeker's (`seeker`), exactly as the batch would show it
  // (arena i's tile). The game itself never shows it (an ended episode's observation is the next
  // one's first image); a learner that bootstraps on a truncation needs it (the Python module's
  // final_obs). One view per episode end; off by default.
  void keepTerminalViews(bool seeker);
  // Arena i's terminal image (at i * imageBytes()) of the last episode it ended; empty until
  // keepTerminalViews.
  const std::vector<uint8_t>& terminalImages() const { return terminal_images_; }

 private:
  void startEpisode(int i, uint32_t seed);
  ArenaStep conclude(int i, const StepResult& result);
  void syncScenes();
  // Every arena's hider camera, or (`seeker`) seeker camera.
  void renderViews(bool seeker, uint8_t* out, RenderMode mode);
  // Arena i's terminal view, while its ended episode is still in place.
  void renderTerminalView(int i);

  GameOptions options_;
  std::vector<Arena> arenas_;
  std::vector<uint32_t> episodes_;
  std::vector<uint32_t> next_seeds_;
  uint32_t seed_stride_;
  std::vector<uint64_t> uploaded_layouts_;
  int frame_ = 0;                                   // frames played of the current step
  std::vector<std::optional<StepResult>> results_;  // each arena's step result once it is over
  std::unique_ptr<Renderer> renderer_;
  std::vector<ViewRequest> views_;
  std::vector<uint8_t> terminal_images_;  // keepTerminalViews
  bool terminal_seeker_ = false;
};

}  // namespace hideseek_game
