// Headless OSMesa renderer of egocentric agent cameras, many views per frame.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "hideseek_game/agent.h"
#include "hideseek_game/map.h"

namespace hideseek_game {

enum class RenderMode {
  kColor,         // shaded colours with distance fog, what agents see
  kSegmentation,  // the other agent white, everything else black (for tests and labels)
};

struct RendererOptions {
  CameraOptions camera;
  int max_views = 1;      // views per frame; each gets one tile of the framebuffer
  double agent_radius{};  // m, the game's (rendererOptionsFor)
  double agent_height{};
  MapColors colors;
  float fog_density = 0.035f;  // 1/m: enough haze that distance reads at 84 x 84
  // llvmpipe rasteriser threads (LP_NUM_THREADS, which wins when set). On the 2-core reference
  // machine 2 threads gave 9,200 arena-steps/s in the core and 5,900 through ROS, 1 thread 4,300.
  int render_threads = 2;
};

// A renderer of the game's cameras and agents in a map's colours, max_views views per frame: every
// value the game decides comes from it; fog and threads keep the renderer's own defaults.
RendererOptions rendererOptionsFor(const GameOptions& game, const MapColors& colors, int max_views);

// One camera image to render: the viewer's pose, the scene it stands in and the other agent.
struct ViewRequest {
  int scene = 0;
  AgentState viewer;
  AgentState other;
  bool other_is_hider = false;
};

// Renders all requested views as tiles of one framebuffer in one pass: no context switch per
// view. Not thread safe: create and use it from one thread (OSMesa contexts are per thread).
class Renderer {
 public:
  explicit Renderer(const RendererOptions& options);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Uploads the static geometry (floor, walls, obstacles) of one scene, usually one arena.
  void setScene(int scene, const Layout& layout);

  // Renders views into `out`: views.size() images of height x width x 3 bytes, rows top down.
  // View k takes tile first_tile + k of the framebuffer. A view's pixels depend on its tile (by a
  // level, here and there), so a view rendered alone matches the batch where it takes the tile the
  // batch gave it.
  void render(const std::vector<ViewRequest>& views, RenderMode mode, uint8_t* out, int first_tile = 0);

  int width() const { return options_.camera.width; }
  int height() const { return options_.camera.height; }
  size_t imageBytes() const { return static_cast<size_t>(width()) * height() * 3; }

 private:
  struct Impl;
  RendererOptions options_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hideseek_game
