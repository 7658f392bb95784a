#include "hideseek_analysis/analysis_inputs.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>

#include "hideseek_game/arena.h"
#include "hideseek_game/renderer.h"
#include "hideseek_play/scripted_game.h"

namespace hideseek_analysis {

namespace hw = hideseek_game;

namespace {

std::ofstream openOrThrow(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out.precision(7);
  return out;
}

constexpr char kStepsHeader[] =
    "arena,episode,step,S,H,O,distance,hider_x,hider_y,hider_yaw,seeker_x,seeker_y,seeker_yaw,hider_action,reward,"
    "outcome\n";

void writeStepRow(std::ofstream& out, const ArenaStepRecord& r) {
  out << r.arena << ',' << r.seed << ',' << r.step << ',' << r.hider_sees_seeker << ',' << r.seeker_sees_hider << ','
      << r.obstacle_in_view << ',' << r.distance << ',' << r.hider_x << ',' << r.hider_y << ',' << r.hider_yaw << ','
      << r.seeker_x << ',' << r.seeker_y << ',' << r.seeker_yaw << ',' << r.hider_action << ',' << r.reward << ','
      << r.outcome << '\n';
}

// Rows grouped by episode (seed) and in step order, as the transition counts need them.
std::vector<const ArenaStepRecord*> byEpisode(const std::vector<ArenaStepRecord>& records) {
  std::vector<const ArenaStepRecord*> rows;
  rows.reserve(records.size());
  for (const auto& r : records) rows.push_back(&r);
  std::stable_sort(rows.begin(), rows.end(), [](const ArenaStepRecord* a, const ArenaStepRecord* b) {
    return a->seed != b->seed ? a->seed < b->seed : a->step < b->step;
  });
  return rows;
}

}  // namespace

torch::Tensor extractFeatures(hideseek_hider::HiderNet& net, const uint8_t* images, int64_t count, int height,
                              int width, int batch) {
  torch::NoGradGuard no_grad;
  net->eval();
  const int64_t bytes = static_cast<int64_t>(height) * width * 3;
  std::vector<torch::Tensor> parts;
  for (int64_t first = 0; first < count; first += batch) {
    const int64_t b = std::min<int64_t>(batch, count - first);
    const torch::Tensor x =
        torch::from_blob(const_cast<uint8_t*>(images + first * bytes), {b, height, width, 3}, torch::kUInt8);
    const torch::Tensor f =
        net->recurrent() ? net->forwardSequence(x.unsqueeze(0), net->initialHidden(b), torch::zeros({1, b})).features[0]
                         : net->forward(x).features;
    parts.push_back(f.to(torch::kFloat32).contiguous());
  }
  if (parts.empty()) return torch::zeros({0, hideseek_hider::kFeatures});
  return torch::cat(parts).contiguous();
}

void writeNpy(const std::string& path, const float* data, int64_t rows, int64_t cols) {
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(rows) + ", " +
                       std::to_string(cols) + "), }";
  // The magic, version and header length take 10 bytes; the header ends in a newline and pads
  // the whole preamble to a multiple of 64 bytes.
  const size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header.push_back('\n');
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write " + path);
  const uint16_t length = static_cast<uint16_t>(header.size());
  out.write("\x93NUMPY\x01\x00", 8);
  out.put(static_cast<char>(length & 0xff));
  out.put(static_cast<char>(length >> 8));
  out << header;
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(rows * cols * sizeof(float)));
  if (!out) throw std::runtime_error("cannot write " + path);
}

MemoryReplay replayMemory(const StepLog& log, const std::vector<hideseek_hider::HiderNet*>& nets,
                          const hw::VariantConfig& variant, std::shared_ptr<const hw::MapSpec> map, int tolerance,
                          int render_threads) {
  for (auto* net : nets) {
    if (!(*net)->recurrent()) throw std::invalid_argument("replayMemory: a feed-forward network has no memory");
  }
  const int n = log.numArenas();
  const int h = variant.game.camera.height, w = variant.game.camera.width;
  if (log.numImages() > 0 && (log.imageHeight() != h || log.imageWidth() != w)) {
    throw std::runtime_error("the recorded images are " + std::to_string(log.imageHeight()) + "x" +
                             std::to_string(log.imageWidth()) + ", variant '" + variant.name + "' renders " +
                             std::to_string(h) + "x" + std::to_string(w));
  }
  hw::RendererOptions r = hw::rendererOptionsFor(variant.game, map->colors, n);
  r.render_threads = render_threads;
  hw::Renderer renderer(r);
  std::vector<hw::Arena> arenas;
  for (int i = 0; i < n; ++i) arenas.emplace_back(variant.game, map);

  torch::NoGradGuard no_grad;
  MemoryReplay out;
  std::vector<torch::Tensor> hidden;
  for (auto* net : nets) {
    (*net)->eval();
    hidden.push_back((*net)->initialHidden(n));
    out.memory.push_back(torch::zeros({log.numImages(), hideseek_hider::kHidden}));
  }
  const size_t bytes = static_cast<size_t>(h) * w * 3;
  std::vector<uint8_t> rendered(bytes * n);
  std::vector<hw::ViewRequest> views(n);
  const auto& records = log.records();
  for (size_t d = 0; d < log.decisions(); ++d) {
    torch::Tensor starts = torch::zeros({1, n});
    for (int i = 0; i < n; ++i) {
      const ArenaStepRecord& rec = records[d * n + i];
      if (d == 0 && rec.step != 0) {
        throw std::runtime_error("arena " + std::to_string(i) + " is logged from step " + std::to_string(rec.step) +
                                 " of episode " + std::to_string(rec.seed) +
                                 ", not from its start: its GRU state before that step is unknown");
      }
      if (rec.step == 0) {
        arenas[i].reset(rec.seed);
        renderer.setScene(i, arenas[i].layout());
        starts[0][i] = 1.0;
      }
      views[i].scene = i;
      views[i].viewer.position = {rec.hider_x, rec.hider_y};
      views[i].viewer.yaw = rec.hider_yaw;
      views[i].other.position = {rec.seeker_x, rec.seeker_y};
      views[i].other.yaw = rec.seeker_yaw;
      views[i].other_is_hider = false;
    }
    renderer.render(views, hw::RenderMode::kColor, rendered.data());
    for (int i = 0; i < n; ++i) {
      const ArenaStepRecord& rec = records[d * n + i];
      if (rec.image < 0) continue;
      const uint8_t* recorded = log.images().data() + static_cast<size_t>(rec.image) * bytes;
      const uint8_t* again = rendered.data() + static_cast<size_t>(i) * bytes;
      int worst = 0;
      for (size_t k = 0; k < bytes; ++k) worst = std::max(worst, std::abs(int(recorded[k]) - int(again[k])));
      out.max_pixel_difference = std::max(out.max_pixel_difference, worst);
      ++out.images_compared;
      if (worst > tolerance) {
        throw std::runtime_error("the hider image of episode " + std::to_string(rec.seed) + ", step " +
                                 std::to_string(rec.step) + " (arena " + std::to_string(i) + ", decision " +
                                 std::to_string(rec.decision) + ") rendered again from the recorded poses differs " +
                                 "from the recorded one by " + std::to_string(worst) + " in a pixel (tolerance " +
                                 std::to_string(tolerance) + "): was it recorded with another variant or map?");
      }
    }
    const torch::Tensor images = torch::from_blob(rendered.data(), {1, n, h, w, 3}, torch::kUInt8);
    for (size_t k = 0; k < nets.size(); ++k) {
      const torch::Tensor memory = (*nets[k])->forwardSequence(images, hidden[k], starts, &hidden[k]).memory[0];
      for (int i = 0; i < n; ++i) {
        const ArenaStepRecord& rec = records[d * n + i];
        if (rec.image >= 0) out.memory[k][rec.image].copy_(memory[i]);
      }
    }
  }
  return out;
}

namespace {

// steps_trained.csv: the trained policy's states, episode by episode; returns the episodes' seeds.
std::set<uint32_t> writeTrainedSteps(const std::vector<ArenaStepRecord>& records, const std::string& dir) {
  std::set<uint32_t> seeds;
  std::ofstream out = openOrThrow(dir + "/steps_trained.csv");
  out << kStepsHeader;
  for (const ArenaStepRecord* r : byEpisode(records)) {
    writeStepRow(out, *r);
    seeds.insert(r->seed);
  }
  return seeds;
}

// features.csv (each image's labels) and the features of every recorded image through the
// trained network and a random one (features_*.npy); a recurrent policy's memory too (memory_*.npy).
void writeFeatures(const StepLog& log, hideseek_hider::HiderNet& trained, const hw::VariantConfig& variant,
                   std::shared_ptr<const hw::MapSpec> map, const AnalysisInputsOptions& options, const std::string& dir,
                   AnalysisInputsSummary& summary) {
  const int h = log.imageHeight(), w = log.imageWidth();
  if (h != trained->imageHeight() || w != trained->imageWidth()) {
    throw std::runtime_error("the recorded images are " + std::to_string(h) + "x" + std::to_string(w) +
                             ", the policy's network takes " + std::to_string(trained->imageHeight()) + "x" +
                             std::to_string(trained->imageWidth()));
  }
  std::ofstream labels = openOrThrow(dir + "/features.csv");
  labels << "episode,step,S,H,O\n";
  for (const auto& r : log.records()) {
    if (r.image < 0) continue;
    labels << r.seed << ',' << r.step << ',' << r.hider_sees_seeker << ',' << r.seeker_sees_hider << ','
           << r.obstacle_in_view << '\n';
  }
  torch::manual_seed(options.random_init_seed);
  hideseek_hider::HiderNet random_init(h, w, trained->network());
  for (auto [name, net] : {std::pair<const char*, hideseek_hider::HiderNet*>{"trained", &trained},
                           std::pair<const char*, hideseek_hider::HiderNet*>{"random", &random_init}}) {
    const torch::Tensor f = extractFeatures(*net, log.images().data(), summary.images, h, w, options.batch);
    writeNpy(dir + "/features_" + name + ".npy", f.data_ptr<float>(), f.size(0), f.size(1));
  }
  if (trained->recurrent()) {
    const MemoryReplay replay = replayMemory(log, {&trained, &random_init}, variant, map, options.pixel_tolerance);
    summary.memory_images_compared = replay.images_compared;
    summary.max_pixel_difference = replay.max_pixel_difference;
    for (auto [name, k] : {std::pair<const char*, size_t>{"trained", 0}, std::pair<const char*, size_t>{"random", 1}}) {
      const torch::Tensor m = replay.memory[k].contiguous();
      writeNpy(dir + "/memory_" + name + ".npy", m.data_ptr<float>(), m.size(0), m.size(1));
    }
  }
}

// One step of a scripted episode as the step log records it.
ArenaStepRecord toRecord(const hideseek_play::ScriptedStep& s) {
  ArenaStepRecord r;
  r.seed = s.seed;
  r.step = static_cast<uint32_t>(s.step);
  r.hider_x = s.hider.position.x;
  r.hider_y = s.hider.position.y;
  r.hider_yaw = s.hider.yaw;
  r.seeker_x = s.seeker.position.x;
  r.seeker_y = s.seeker.position.y;
  r.seeker_yaw = s.seeker.yaw;
  r.distance = hw::distance(s.hider.position, s.seeker.position);
  r.hider_sees_seeker = s.labels.hider_sees_seeker;
  r.seeker_sees_hider = s.labels.seeker_sees_hider;
  r.obstacle_in_view = s.labels.obstacle_in_view;
  r.hider_action = static_cast<int>(s.hider_action);
  return r;
}

// steps_random.csv: the random policy over at least as many steps as the trained one, in whole
// episodes, from the trained rollout's first seed on.
void writeRandomSteps(const hw::VariantConfig& variant, std::shared_ptr<const hw::MapSpec> map, uint32_t first_seed,
                      const std::string& dir, AnalysisInputsSummary& summary) {
  std::ofstream out = openOrThrow(dir + "/steps_random.csv");
  out << kStepsHeader;
  uint32_t next_seed = first_seed;
  while (summary.random_steps < summary.steps) {
    std::vector<ArenaStepRecord> episode;
    const auto played =
        hideseek_play::playScriptedHider(variant, map, hideseek_hider::EvaderKind::kRandom, next_seed, 1,
                                         [&](const hideseek_play::ScriptedStep& s) { episode.push_back(toRecord(s)); });
    // The episode's last step carries how it ended (rewards are the trained rollout's only).
    if (!episode.empty()) episode.back().outcome = played.front().survived ? 2 : 1;
    for (const auto& r : episode) writeStepRow(out, r);
    summary.random_steps += episode.size();
    ++summary.random_episodes;
    ++next_seed;
  }
}

// layouts.csv: the layouts of the complete episodes with the smallest seeds (not the first to
// end, which would favour short episodes), rebuilt from their seeds and checked against the
// recorded start: a bag of another variant or map would not match.
void writeLayouts(const std::vector<ArenaStepRecord>& records, const hw::VariantConfig& variant,
                  std::shared_ptr<const hw::MapSpec> map, const AnalysisInputsOptions& options, const std::string& dir,
                  AnalysisInputsSummary& summary) {
  std::map<uint32_t, const ArenaStepRecord*> start;
  std::set<uint32_t> complete;
  for (const auto& r : records) {
    if (r.step == 0) start[r.seed] = &r;
    if (r.outcome != 0 && start.count(r.seed)) complete.insert(r.seed);
  }
  std::ofstream out = openOrThrow(dir + "/layouts.csv");
  out << "episode,half_extent,x,y,size_x,size_y,yaw\n";
  hw::Arena arena(variant.game, map);
  for (uint32_t seed : complete) {
    if (static_cast<int>(summary.trajectory_seeds.size()) >= options.trajectory_episodes) break;
    arena.reset(seed);
    const ArenaStepRecord& s = *start[seed];
    if (std::abs(arena.hider().position.x - s.hider_x) > 1e-3 ||
        std::abs(arena.hider().position.y - s.hider_y) > 1e-3) {
      throw std::runtime_error("episode " + std::to_string(seed) + " of the recording does not start where variant '" +
                               variant.name + "' starts it: was it recorded with another variant or map?");
    }
    for (const hw::Box& b : arena.layout().obstacles) {
      out << seed << ',' << arena.layout().half_extent << ',' << b.center.x << ',' << b.center.y << ',' << b.size.x
          << ',' << b.size.y << ',' << b.yaw << '\n';
    }
    summary.trajectory_seeds.push_back(seed);
  }
}

}  // namespace

AnalysisInputsSummary writeAnalysisInputs(const StepLog& log, hideseek_hider::HiderNet& trained,
                                          const hw::VariantConfig& variant, std::shared_ptr<const hw::MapSpec> map,
                                          const AnalysisInputsOptions& options, const std::string& dir) {
  if (log.numImages() == 0) {
    // Before any file is written: the report's probes and t-SNE are of the recorded images.
    throw std::runtime_error(
        "the recording holds no hider image (recorded with record_images:=false, or image_every 0): the probes "
        "and the t-SNE are of the images, so record again with them; nothing was analysed");
  }
  AnalysisInputsSummary summary;
  summary.steps = log.records().size();
  const std::set<uint32_t> seeds = writeTrainedSteps(log.records(), dir);
  summary.episodes = seeds.size();
  summary.images = log.numImages();
  writeFeatures(log, trained, variant, map, options, dir, summary);
  writeRandomSteps(variant, map, seeds.empty() ? 0 : *seeds.begin(), dir, summary);
  writeLayouts(log.records(), variant, map, options, dir, summary);
  return summary;
}

}  // namespace hideseek_analysis
