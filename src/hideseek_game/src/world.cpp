#include "hideseek_game/world.h"

#include <algorithm>
#include <stdexcept>

namespace hideseek_game {

World::World(const GameOptions& options, std::shared_ptr<const MapSpec> map, int num_arenas, uint32_t seed, bool render,
             int render_threads, uint32_t seed_stride)
    : options_(options),
      episodes_(num_arenas, 0),
      next_seeds_(num_arenas),
      seed_stride_(seed_stride == 0 ? static_cast<uint32_t>(std::max(num_arenas, 1)) : seed_stride),
      uploaded_layouts_(num_arenas, ~uint64_t{0}),
      results_(num_arenas) {
  if (num_arenas < 1) throw std::invalid_argument("World: num_arenas must be at least 1");
  arenas_.reserve(num_arenas);
  for (int i = 0; i < num_arenas; ++i) arenas_.emplace_back(options, map);
  if (render) {
    RendererOptions r = rendererOptionsFor(options, map->colors, num_arenas);
    r.render_threads = render_threads;
    renderer_ = std::make_unique<Renderer>(r);
  }
  for (int i = 0; i < num_arenas; ++i) startEpisode(i, seed + static_cast<uint32_t>(i));
}

void World::startEpisode(int i, uint32_t seed) {
  arenas_[i].reset(seed);
  next_seeds_[i] = seed + seed_stride_;
}

void World::resetArena(int i, std::optional<uint32_t> seed) {
  if (frame_ != 0) throw std::logic_error("World: reset in the middle of a decision step");
  startEpisode(i, seed ? *seed : next_seeds_[i]);
  ++episodes_[i];
}

ArenaStep World::stepArena(int i, Action hider, Action seeker) { return conclude(i, arenas_[i].step(hider, seeker)); }

ArenaStep World::stepArena(int i, Action hider, const SeekerDecide& seeker) {
  return conclude(i, playDecisionStep(arenas_[i], hider, seeker));
}

int World::stepPlaying(int i) const {
  // An arena whose step ended early (a capture) has counted that step already.
  return arenas_[i].stepCount() - (results_[i] ? 1 : 0);
}

uint32_t World::seekerDecisionId(int i) const {
  return static_cast<uint32_t>(stepPlaying(i) * options_.seekerDecisionsPerStep() +
                               frame_ / options_.seeker_decision_frames);
}

std::optional<std::vector<ArenaStep>> World::advanceFrame(const std::vector<Action>& hider,
                                                          const std::vector<Action>& seeker) {
  const int n = numArenas();
  for (int i = 0; i < n; ++i) {
    if (!results_[i]) results_[i] = arenas_[i].advanceFrame(hider[i], seeker[i]);
  }
  if (++frame_ < options_.action_repeat) return std::nullopt;
  frame_ = 0;
  std::vector<ArenaStep> out;
  out.reserve(n);
  for (int i = 0; i < n; ++i) {
    out.push_back(conclude(i, *results_[i]));
    results_[i].reset();
  }
  return out;
}

ArenaStep World::conclude(int i, const StepResult& result) {
  const Arena& a = arenas_[i];
  ArenaStep out;
  out.result = result;
  if (result.done()) {
    if (!terminal_images_.empty()) renderTerminalView(i);
    out.finished = EpisodeSummary{episodes_[i],   a.seed(),  a.stepCount(), a.episodeReturn(),
                                  result.outcome, a.hider(), a.seeker(),    a.labels()};
    out.finished->seeker_return = a.seekerEpisodeReturn();
    resetArena(i, std::nullopt);
  }
  return out;
}

size_t World::imageBytes() const { return static_cast<size_t>(options_.camera.width) * options_.camera.height * 3; }

void World::syncScenes() {
  for (int i = 0; i < numArenas(); ++i) {
    if (uploaded_layouts_[i] != arenas_[i].layoutVersion()) {
      renderer_->setScene(i, arenas_[i].layout());
      uploaded_layouts_[i] = arenas_[i].layoutVersion();
    }
  }
}

void World::renderHiderViews(uint8_t* out, RenderMode mode) { renderViews(false, out, mode); }

void World::renderSeekerViews(uint8_t* out, RenderMode mode) { renderViews(true, out, mode); }

void World::renderViews(bool seeker, uint8_t* out, RenderMode mode) {
  if (!renderer_) throw std::logic_error("World: built without a renderer");
  syncScenes();
  views_.resize(arenas_.size());
  for (int i = 0; i < numArenas(); ++i) {
    const Arena& a = arenas_[i];
    views_[i] = {i, seeker ? a.seeker() : a.hider(), seeker ? a.hider() : a.seeker(), seeker};
  }
  renderer_->render(views_, mode, out);
}

void World::keepTerminalViews(bool seeker) {
  if (!renderer_) throw std::logic_error("World: built without a renderer, so it keeps no terminal view");
  terminal_images_.assign(imageBytes() * arenas_.size(), 0);
  terminal_seeker_ = seeker;
}

void World::renderTerminalView(int i) {
  syncScenes();  // arena i's layout is still its ended episode's
  const Arena& a = arenas_[i];
  const ViewRequest view =
      terminal_seeker_ ? ViewRequest{i, a.seeker(), a.hider(), true} : ViewRequest{i, a.hider(), a.seeker(), false};
  // Arena i's tile, as renderViews gives it: the same pixels as the batch.
  renderer_->render({view}, RenderMode::kColor, terminal_images_.data() + imageBytes() * static_cast<size_t>(i), i);
}

void World::renderSeekerView(int i, uint8_t* out, RenderMode mode) {
  if (!renderer_) throw std::logic_error("World: built without a renderer");
  syncScenes();
  renderer_->render({{i, arenas_[i].seeker(), arenas_[i].hider(), true}}, mode, out);
}

}  // namespace hideseek_game
