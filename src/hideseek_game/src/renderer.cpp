#include "hideseek_game/renderer.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>

namespace hideseek_game {

namespace {

// Everything llvmpipe gets is already clipped to its view and mapped to its tile, so a whole
// frame is one buffer upload and one draw call. llvmpipe's own clipping and per-draw state
// changes cost far more than this CPU stage (measured: ~60 us per view for a viewport change
// and a draw, ~3 us per clipped triangle).
constexpr char kVertexShader[] = R"(#version 120
attribute vec4 a_position;
attribute vec3 a_color;
varying vec3 v_color;
void main() {
  v_color = a_color;
  gl_Position = a_position;
}
)";

constexpr char kFragmentShader[] = R"(#version 120
varying vec3 v_color;
void main() {
  gl_FragColor = vec4(v_color, 1.0);
}
)";

constexpr float kMaxFog = 0.7f;

struct FrameVertex {
  float x, y, z, w;
  float r, g, b;
};

// A planar quad of the scene, corners counter-clockwise seen from its front.
struct Quad {
  std::array<Eigen::Vector3f, 4> corners;
  Rgb color;
  Eigen::Vector3f normal;
  bool occluder;  // an obstacle (segmentation draws it black like everything but the agent)
};

const Eigen::Vector3f kSun = Eigen::Vector3f(0.45f, 0.3f, 0.84f).normalized();

// Lambert shading baked into colours: a fixed sun, faces of different orientation differ.
Rgb shade(Rgb c, const Eigen::Vector3f& normal) {
  const float k = 0.45f + 0.55f * std::max(0.f, normal.normalized().dot(kSun));
  return {c.r * k, c.g * k, c.b * k};
}

Quad makeQuad(const std::array<Eigen::Vector3f, 4>& p, Rgb color, bool occluder) {
  const Eigen::Vector3f n = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
  return {p, shade(color, n), n, occluder};
}

GLuint compileShader(GLenum type, const char* source) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024];
    glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
    throw std::runtime_error(std::string("renderer: shader compilation failed: ") + log);
  }
  return shader;
}

Eigen::Matrix4f perspective(double fovy, double aspect, double near_clip, double far_clip) {
  const double f = 1.0 / std::tan(0.5 * fovy);
  Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
  m(0, 0) = static_cast<float>(f / aspect);
  m(1, 1) = static_cast<float>(f);
  m(2, 2) = static_cast<float>((far_clip + near_clip) / (near_clip - far_clip));
  m(2, 3) = static_cast<float>(2.0 * far_clip * near_clip / (near_clip - far_clip));
  m(3, 2) = -1.f;
  return m;
}

// GL eye frame of an agent camera: x right, y up, looking down -z along the agent's heading.
Eigen::Matrix4f viewMatrix(const AgentState& a, double mount_height) {
  const Eigen::Vector3f eye(a.position.x, a.position.y, mount_height);
  const Eigen::Vector3f forward(std::cos(a.yaw), std::sin(a.yaw), 0.f);
  const Eigen::Vector3f up = Eigen::Vector3f::UnitZ();
  const Eigen::Vector3f right = forward.cross(up);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = right.transpose();
  m.block<1, 3>(1, 0) = up.transpose();
  m.block<1, 3>(2, 0) = -forward.transpose();
  m(0, 3) = -right.dot(eye);
  m(1, 3) = -up.dot(eye);
  m(2, 3) = forward.dot(eye);
  return m;
}

// A vertex on its way through the view: clip-space position and final colour.
struct ClipVertex {
  Eigen::Vector4f p;
  Eigen::Vector3f c;
};

using Polygon = std::vector<ClipVertex>;

// Sutherland-Hodgman against the six planes of the clip volume (-w <= x, y, z <= w).
void clipPolygon(Polygon& poly, Polygon& scratch) {
  for (int plane = 0; plane < 6 && !poly.empty(); ++plane) {
    const int axis = plane / 2;
    const float sign = plane % 2 ? -1.f : 1.f;
    auto distance = [&](const ClipVertex& v) { return v.p.w() + sign * v.p[axis]; };
    scratch.clear();
    for (size_t i = 0; i < poly.size(); ++i) {
      const ClipVertex& a = poly[i];
      const ClipVertex& b = poly[(i + 1) % poly.size()];
      const float da = distance(a), db = distance(b);
      if (da >= 0.f) scratch.push_back(a);
      if ((da >= 0.f) != (db >= 0.f)) {
        const float t = da / (da - db);
        scratch.push_back({a.p + t * (b.p - a.p), a.c + t * (b.c - a.c)});
      }
    }
    poly.swap(scratch);
  }
}

// Keeps the part of a world-space quad inside the arena square (boxes may cross the walls).
std::vector<Eigen::Vector3f> clipToArena(const std::array<Eigen::Vector3f, 4>& quad, float half_extent) {
  std::vector<Eigen::Vector3f> poly(quad.begin(), quad.end()), next;
  for (int plane = 0; plane < 4 && !poly.empty(); ++plane) {
    const int axis = plane / 2;
    const float sign = plane % 2 ? -1.f : 1.f;
    auto distance = [&](const Eigen::Vector3f& v) { return half_extent - sign * v[axis]; };
    next.clear();
    for (size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector3f& a = poly[i];
      const Eigen::Vector3f& b = poly[(i + 1) % poly.size()];
      const float da = distance(a), db = distance(b);
      if (da >= 0.f) next.push_back(a);
      if ((da >= 0.f) != (db >= 0.f)) next.push_back(a + (da / (da - db)) * (b - a));
    }
    poly.swap(next);
  }
  return poly;
}

}  // namespace

struct Renderer::Impl {
  OSMesaContext context = nullptr;
  int tiles_x = 1;
  int tiles_y = 1;
  int fb_width = 0;
  int fb_height = 0;
  std::vector<uint8_t> framebuffer;  // RGBA, written by OSMesa
  GLuint program = 0;
  GLint a_position = -1;
  GLint a_color = -1;
  GLuint buffer = 0;
  size_t buffer_capacity = 0;  // vertices; the buffer only grows, so frames reuse its memory
  Eigen::Matrix4f projection;
  std::map<int, std::vector<Quad>> scenes;
  std::vector<Quad> cylinder;        // around the origin, front (+x) stripe on the first quad
  std::vector<Quad> plain_cylinder;  // the same without the stripe, for agents with a front colour
  std::vector<bool> front_segment;   // which of its quads face within kFrontHalfAngle of +x
  std::vector<FrameVertex> frame;
  Polygon poly;
  Polygon scratch;

  // The three steps of Renderer::render: each view's triangles into the frame, in its tile's clip
  // space; the frame drawn by OSMesa; each tile copied out as a top-row-first RGB8 image.
  void appendView(const RendererOptions& options, size_t k, const ViewRequest& view, bool segmentation,
                  const Eigen::Vector3f& fog_color);
  void draw(const Rgb& sky);
  void copyTiles(const RendererOptions& options, size_t first_tile, size_t views, size_t image_bytes,
                 uint8_t* out) const;
};

RendererOptions rendererOptionsFor(const GameOptions& game, const MapColors& colors, int max_views) {
  RendererOptions r;
  r.camera = game.camera;
  r.max_views = max_views;
  r.agent_radius = game.agent_radius;
  r.agent_height = game.agent_height;
  r.colors = colors;
  return r;
}

Renderer::Renderer(const RendererOptions& options) : options_(options), impl_(std::make_unique<Impl>()) {
  Impl& r = *impl_;
  const int w = options.camera.width, h = options.camera.height;
  if (options.max_views < 1) throw std::invalid_argument("renderer: max_views must be at least 1");
  r.tiles_x = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(options.max_views))));
  r.tiles_y = (options.max_views + r.tiles_x - 1) / r.tiles_x;
  r.fb_width = r.tiles_x * w;
  r.fb_height = r.tiles_y * h;
  r.framebuffer.assign(static_cast<size_t>(r.fb_width) * r.fb_height * 4, 0);
  // llvmpipe reads its thread count when the first context is made; an explicit environment wins.
  setenv("LP_NUM_THREADS", std::to_string(options.render_threads).c_str(), 0);
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            24,
                            OSMESA_STENCIL_BITS,
                            0,
                            OSMESA_ACCUM_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_COMPAT_PROFILE,
                            0};
  r.context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!r.context) throw std::runtime_error("renderer: OSMesa could not create a context");
  if (!OSMesaMakeCurrent(r.context, r.framebuffer.data(), GL_UNSIGNED_BYTE, r.fb_width, r.fb_height)) {
    throw std::runtime_error("renderer: OSMesa could not bind the framebuffer");
  }
  r.program = glCreateProgram();
  glAttachShader(r.program, compileShader(GL_VERTEX_SHADER, kVertexShader));
  glAttachShader(r.program, compileShader(GL_FRAGMENT_SHADER, kFragmentShader));
  glLinkProgram(r.program);
  GLint linked = 0;
  glGetProgramiv(r.program, GL_LINK_STATUS, &linked);
  if (!linked) throw std::runtime_error("renderer: shader program did not link");
  glUseProgram(r.program);
  r.a_position = glGetAttribLocation(r.program, "a_position");
  r.a_color = glGetAttribLocation(r.program, "a_color");
  glGenBuffers(1, &r.buffer);
  glBindBuffer(GL_ARRAY_BUFFER, r.buffer);
  glEnableVertexAttribArray(r.a_position);
  glEnableVertexAttribArray(r.a_color);
  glEnable(GL_DEPTH_TEST);
  glViewport(0, 0, r.fb_width, r.fb_height);
  r.projection = perspective(options.camera.verticalFov(), static_cast<double>(w) / h, options.camera.near_clip,
                             options.camera.far_clip);

  // The other agent: an upright cylinder, darker on its front so its heading shows. Its top is
  // left out when cameras sit below the agents' height, as they do by default.
  constexpr int kSegments = 12;
  const float radius = static_cast<float>(options.agent_radius), height = static_cast<float>(options.agent_height);
  for (int i = 0; i < kSegments; ++i) {
    const float a0 = 2.f * static_cast<float>(kPi) * (i - 0.5f) / kSegments;
    const float a1 = 2.f * static_cast<float>(kPi) * (i + 0.5f) / kSegments;
    const Eigen::Vector3f p0(radius * std::cos(a0), radius * std::sin(a0), 0.f);
    const Eigen::Vector3f p1(radius * std::cos(a1), radius * std::sin(a1), 0.f);
    const Eigen::Vector3f up(0.f, 0.f, height);
    r.cylinder.push_back(
        makeQuad({p0, p1, p1 + up, p0 + up}, i == 0 ? Rgb{0.45f, 0.45f, 0.45f} : Rgb{1.f, 1.f, 1.f}, false));
    r.plain_cylinder.push_back(makeQuad({p0, p1, p1 + up, p0 + up}, Rgb{1.f, 1.f, 1.f}, false));
    // Segment i faces 30 i degrees; the front colour covers the five facing within 60 degrees.
    const int facing = i <= kSegments / 2 ? i : kSegments - i;
    r.front_segment.push_back(facing <= 2);
  }
}

Renderer::~Renderer() {
  if (impl_->context) OSMesaDestroyContext(impl_->context);
}

void Renderer::setScene(int scene, const Layout& layout) {
  std::vector<Quad>& quads = impl_->scenes[scene];
  quads.clear();
  const MapColors& colors = options_.colors;
  const float e = static_cast<float>(layout.half_extent), wh = static_cast<float>(layout.wall_height);
  // One floor quad: llvmpipe's cost grows with triangles, and fog already tells distance.
  quads.push_back({{Eigen::Vector3f(-e, -e, 0.f), Eigen::Vector3f(e, -e, 0.f), Eigen::Vector3f(e, e, 0.f),
                    Eigen::Vector3f(-e, e, 0.f)},
                   colors.floor,
                   Eigen::Vector3f::UnitZ(),
                   false});
  // Inner faces of the walls.
  const std::array<Eigen::Vector2f, 4> inner = {Eigen::Vector2f(e, e), Eigen::Vector2f(-e, e), Eigen::Vector2f(-e, -e),
                                                Eigen::Vector2f(e, -e)};
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2f a = inner[(i + 1) % 4], b = inner[i];
    quads.push_back(makeQuad({Eigen::Vector3f(a.x(), a.y(), 0.f), Eigen::Vector3f(b.x(), b.y(), 0.f),
                              Eigen::Vector3f(b.x(), b.y(), wh), Eigen::Vector3f(a.x(), a.y(), wh)},
                             colors.wall, false));
  }
  for (const Box& box : layout.obstacles) {
    const float hx = 0.5f * box.size.x, hy = 0.5f * box.size.y, h = box.height;
    const float c = box.cos_yaw, s = box.sin_yaw;
    auto at = [&](float lx, float ly, float z) {
      return Eigen::Vector3f(box.center.x + c * lx - s * ly, box.center.y + s * lx + c * ly, z);
    };
    const std::array<std::array<float, 2>, 4> corner = {{{hx, hy}, {-hx, hy}, {-hx, -hy}, {hx, -hy}}};
    for (int i = 0; i < 4; ++i) {
      const auto& a = corner[i];
      const auto& b = corner[(i + 1) % 4];
      quads.push_back(makeQuad({at(a[0], a[1], 0.f), at(b[0], b[1], 0.f), at(b[0], b[1], h), at(a[0], a[1], h)},
                               box.wall ? colors.wall : colors.obstacle, true));
    }
    quads.push_back(makeQuad({at(hx, hy, h), at(-hx, hy, h), at(-hx, -hy, h), at(hx, -hy, h)},
                             box.wall ? colors.wall : colors.obstacle, true));
  }
  for (Quad& q : quads) {
    if (!q.occluder) continue;
    for (const Eigen::Vector3f& p : q.corners) {
      // Only boxes that cross a wall need the arena clip; mark them by a zero-length check later.
      if (std::abs(p.x()) > e || std::abs(p.y()) > e) {
        const auto clipped = clipToArena(q.corners, e);
        if (clipped.size() < 3) {
          q.corners = {Eigen::Vector3f::Zero(), Eigen::Vector3f::Zero(), Eigen::Vector3f::Zero(),
                       Eigen::Vector3f::Zero()};
        } else if (clipped.size() <= 4) {
          for (size_t i = 0; i < 4; ++i) q.corners[i] = clipped[std::min(i, clipped.size() - 1)];
        } else {
          // A quad cut by two walls near a corner: split it so each part stays a quad.
          Quad rest = q;
          for (size_t i = 0; i < 4; ++i) q.corners[i] = clipped[i];
          rest.corners = {clipped[0], clipped[3], clipped[std::min<size_t>(4, clipped.size() - 1)],
                          clipped[std::min<size_t>(5, clipped.size() - 1)]};
          quads.push_back(rest);
        }
        break;
      }
    }
  }
}

void Renderer::Impl::appendView(const RendererOptions& options, size_t k, const ViewRequest& view, bool segmentation,
                                const Eigen::Vector3f& fog_color) {
  Impl& r = *this;
  const int w = options.camera.width, h = options.camera.height;
  const auto scene = r.scenes.find(view.scene);
  if (scene == r.scenes.end())
    throw std::invalid_argument("renderer: scene " + std::to_string(view.scene) + " not set");
  const AgentState& v = view.viewer;
  const Eigen::Vector3f eye(v.position.x, v.position.y, options.camera.mount_height);
  const Eigen::Matrix4f vp = r.projection * viewMatrix(v, options.camera.mount_height);
  // Maps the view's clip space onto its tile of the framebuffer: x' = sx x + ox w.
  const float sx = static_cast<float>(w) / r.fb_width, sy = static_cast<float>(h) / r.fb_height;
  const float ox = (2.f * (k % r.tiles_x) * w + w) / r.fb_width - 1.f;
  const float oy = (2.f * (k / r.tiles_x) * h + h) / r.fb_height - 1.f;

  auto emit = [&](const Quad& q, const Eigen::Vector3f& offset, float cos_yaw, float sin_yaw, const Rgb& tint,
                  bool is_agent) {
    // Back faces never show: a camera sees a face only from its front.
    Eigen::Vector3f corners[4];
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3f& c = q.corners[i];
      corners[i] = Eigen::Vector3f(offset.x() + cos_yaw * c.x() - sin_yaw * c.y(),
                                   offset.y() + sin_yaw * c.x() + cos_yaw * c.y(), c.z());
    }
    const Eigen::Vector3f normal(cos_yaw * q.normal.x() - sin_yaw * q.normal.y(),
                                 sin_yaw * q.normal.x() + cos_yaw * q.normal.y(), q.normal.z());
    if (normal.dot(eye - corners[0]) <= 0.f) return;
    Eigen::Vector3f color = segmentation ? (is_agent ? Eigen::Vector3f(1.f, 1.f, 1.f) : Eigen::Vector3f::Zero())
                                         : Eigen::Vector3f(q.color.r * tint.r, q.color.g * tint.g, q.color.b * tint.b);
    r.poly.clear();
    bool all_inside = true;
    for (const Eigen::Vector3f& c : corners) {
      const Eigen::Vector4f p = vp * Eigen::Vector4f(c.x(), c.y(), c.z(), 1.f);
      const float fog = segmentation ? 0.f : std::min(options.fog_density * (c - eye).norm(), kMaxFog);
      r.poly.push_back({p, color + fog * (fog_color - color)});
      all_inside = all_inside && std::abs(p.x()) <= p.w() && std::abs(p.y()) <= p.w() && std::abs(p.z()) <= p.w();
    }
    if (!all_inside) clipPolygon(r.poly, r.scratch);
    for (size_t i = 1; i + 1 < r.poly.size(); ++i) {
      for (size_t j : {size_t{0}, i, i + 1}) {
        const ClipVertex& cv = r.poly[j];
        r.frame.push_back({sx * cv.p.x() + ox * cv.p.w(), sy * cv.p.y() + oy * cv.p.w(), cv.p.z(), cv.p.w(), cv.c.x(),
                           cv.c.y(), cv.c.z()});
      }
    }
  };

  const Rgb white{1.f, 1.f, 1.f};
  for (const Quad& q : scene->second) emit(q, Eigen::Vector3f::Zero(), 1.f, 0.f, white, false);
  const AgentState& o = view.other;
  const Rgb tint = view.other_is_hider ? options.colors.hider : options.colors.seeker;
  const std::optional<Rgb>& front = view.other_is_hider ? options.colors.hider_front : options.colors.seeker_front;
  const Eigen::Vector3f at(o.position.x, o.position.y, 0.f);
  const float c = std::cos(o.yaw), s = std::sin(o.yaw);
  if (front) {
    for (size_t q = 0; q < r.plain_cylinder.size(); ++q) {
      emit(r.plain_cylinder[q], at, c, s, r.front_segment[q] ? *front : tint, true);
    }
  } else {
    for (const Quad& q : r.cylinder) emit(q, at, c, s, tint, true);
  }
}

void Renderer::Impl::draw(const Rgb& sky) {
  Impl& r = *this;
  // Several renderers may share a thread (tests do); each draws into its own context.
  OSMesaMakeCurrent(r.context, r.framebuffer.data(), GL_UNSIGNED_BYTE, r.fb_width, r.fb_height);
  glClearColor(sky.r, sky.g, sky.b, 1.f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (r.frame.size() > r.buffer_capacity) {
    r.buffer_capacity = 2 * r.frame.size();
    glBufferData(GL_ARRAY_BUFFER, r.buffer_capacity * sizeof(FrameVertex), nullptr, GL_DYNAMIC_DRAW);
  }
  glBufferSubData(GL_ARRAY_BUFFER, 0, r.frame.size() * sizeof(FrameVertex), r.frame.data());
  glVertexAttribPointer(r.a_position, 4, GL_FLOAT, GL_FALSE, sizeof(FrameVertex), reinterpret_cast<void*>(0));
  glVertexAttribPointer(r.a_color, 3, GL_FLOAT, GL_FALSE, sizeof(FrameVertex),
                        reinterpret_cast<void*>(4 * sizeof(float)));
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(r.frame.size()));
  glFinish();
}

void Renderer::Impl::copyTiles(const RendererOptions& options, size_t first_tile, size_t views, size_t image_bytes,
                               uint8_t* out) const {
  const Impl& r = *this;
  const int w = options.camera.width, h = options.camera.height;
  // OSMesa's buffer has GL's bottom row first; images want the top row first.
  const size_t row_bytes = static_cast<size_t>(w) * 3;
  for (size_t k = 0; k < views; ++k) {
    const size_t tile = first_tile + k;
    const int x0 = static_cast<int>(tile % r.tiles_x) * w, y0 = static_cast<int>(tile / r.tiles_x) * h;
    uint8_t* image = out + k * image_bytes;
    for (int row = 0; row < h; ++row) {
      const uint8_t* src = r.framebuffer.data() + (static_cast<size_t>(y0 + h - 1 - row) * r.fb_width + x0) * 4;
      uint8_t* dst = image + row * row_bytes;
      for (int x = 0; x < w; ++x, src += 4, dst += 3) {
        dst[0] = src[0];
        dst[1] = src[1];
        dst[2] = src[2];
      }
    }
  }
}

void Renderer::render(const std::vector<ViewRequest>& views, RenderMode mode, uint8_t* out, int first_tile) {
  if (first_tile < 0 || first_tile + static_cast<int>(views.size()) > options_.max_views) {
    throw std::invalid_argument("renderer: " + std::to_string(views.size()) + " views requested from tile " +
                                std::to_string(first_tile) + ", built for " + std::to_string(options_.max_views));
  }
  const bool segmentation = mode == RenderMode::kSegmentation;
  const Rgb sky = segmentation ? Rgb{} : options_.colors.sky;
  impl_->frame.clear();
  for (size_t k = 0; k < views.size(); ++k) {
    impl_->appendView(options_, first_tile + k, views[k], segmentation, Eigen::Vector3f(sky.r, sky.g, sky.b));
  }
  impl_->draw(sky);
  impl_->copyTiles(options_, static_cast<size_t>(first_tile), views.size(), imageBytes(), out);
}

}  // namespace hideseek_game
