#include "hideseek_hider/hider_net.h"

#include <ATen/CPUGeneratorImpl.h>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>

#include "hideseek_hider/checkpoint_archive.h"
#include "hideseek_hider/gru_sequence.h"

namespace hideseek_hider {

namespace {

int convOut(int size, int kernel, int stride) { return (size - kernel) / stride + 1; }

torch::Tensor leaky(const torch::Tensor& x) { return torch::leaky_relu(x, 0.01); }

// FNV-1a over every parameter's name and bytes, in registration order: a flipped byte in the
// weights, which the archive format itself does not notice, changes it.
int64_t weightsChecksum(HiderNet& net) {
  uint64_t h = 1469598103934665603ULL;
  auto mix = [&h](const uint8_t* p, size_t n) {
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ULL;
  };
  for (const auto& p : net->named_parameters()) {
    mix(reinterpret_cast<const uint8_t*>(p.key().data()), p.key().size());
    const torch::Tensor t = p.value().detach().to(torch::kCPU, torch::kFloat32).contiguous();
    mix(static_cast<const uint8_t*>(t.data_ptr()), static_cast<size_t>(t.numel()) * sizeof(float));
  }
  return static_cast<int64_t>(h);
}

}  // namespace

const char* networkName(NetworkKind kind) { return kind == NetworkKind::kGru ? "gru" : "ff"; }

NetworkKind parseNetwork(const std::string& name, const std::string& what) {
  if (name == "ff") return NetworkKind::kFeedForward;
  if (name == "gru") return NetworkKind::kGru;
  throw std::invalid_argument(what + " must be ff or gru, got '" + name + "'");
}

HiderNetImpl::HiderNetImpl(int image_height, int image_width, NetworkKind network)
    : image_height_(image_height), image_width_(image_width), network_(network) {
  const int h = convOut(convOut(convOut(image_height, 8, 4), 4, 2), 3, 1);
  const int w = convOut(convOut(convOut(image_width, 8, 4), 4, 2), 3, 1);
  if (h < 1 || w < 1) {
    throw std::invalid_argument("hider network: images of " + std::to_string(image_height) + "x" +
                                std::to_string(image_width) + " are too small for the encoder (at least 36x36)");
  }
  conv1_ = register_module("conv1", torch::nn::Conv2d(torch::nn::Conv2dOptions(3, 32, 8).stride(4)));
  conv2_ = register_module("conv2", torch::nn::Conv2d(torch::nn::Conv2dOptions(32, 64, 4).stride(2)));
  conv3_ = register_module("conv3", torch::nn::Conv2d(torch::nn::Conv2dOptions(64, 64, 3).stride(1)));
  features_ = register_module("features", torch::nn::Linear(64 * h * w, kFeatures));
  if (recurrent()) gru_ = register_module("gru", torch::nn::GRUCell(torch::nn::GRUCellOptions(kFeatures, kHidden)));
  const int head_in = recurrent() ? kHidden : kFeatures;
  actor_hidden_ = register_module("actor_hidden", torch::nn::Linear(head_in, 512));
  actor_out_ = register_module("actor_out", torch::nn::Linear(512, kActions));
  critic_hidden_ = register_module("critic_hidden", torch::nn::Linear(head_in, 512));
  critic_out_ = register_module("critic_out", torch::nn::Linear(512, 1));
}

torch::Tensor HiderNetImpl::encode(const torch::Tensor& images) {
  TORCH_CHECK(
      images.dim() == 4 && images.size(1) == image_height_ && images.size(2) == image_width_ && images.size(3) == 3,
      "hider network expects [B, ", image_height_, ", ", image_width_, ", 3] images, got ", images.sizes());
  const AutocastScope autocast(precision_, conv1_->weight.device());
  torch::Tensor x = images.permute({0, 3, 1, 2}).to(torch::kFloat32).div(255.0);
  x = leaky(conv1_->forward(x));
  x = leaky(conv2_->forward(x));
  x = leaky(conv3_->forward(x));
  return leaky(features_->forward(x.flatten(1)));
}

void HiderNetImpl::heads(const torch::Tensor& x, HiderOutput& out) {
  torch::Tensor actor, critic;
  {
    const AutocastScope autocast(precision_, conv1_->weight.device());
    actor = leaky(actor_hidden_->forward(x));
    critic = leaky(critic_hidden_->forward(x));
  }
  // The two output layers run in fp32 (a negligible share of the work): a bf16 value would be
  // rounded to about 0.004 near 1, coarser than the 0.001 per-step reward GAE works with.
  // Losses, softmax and probes then work in fp32 whatever precision the layers ran in.
  out.logits = actor_out_->forward(actor.to(torch::kFloat32));
  out.value = critic_out_->forward(critic.to(torch::kFloat32)).squeeze(1);
}

HiderOutput HiderNetImpl::forward(const torch::Tensor& images) {
  TORCH_CHECK(!recurrent(), "a GRU hider network needs its state: call forwardSequence");
  HiderOutput out;
  out.features = encode(images).to(torch::kFloat32);
  heads(out.features, out);
  return out;
}

HiderOutput HiderNetImpl::forwardSequence(const torch::Tensor& images, const torch::Tensor& hidden,
                                          const torch::Tensor& starts, torch::Tensor* hidden_out) {
  TORCH_CHECK(images.dim() == 5, "forwardSequence expects [T, B, H, W, 3] images, got ", images.sizes());
  const int64_t steps = images.size(0), batch = images.size(1);
  TORCH_CHECK(starts.dim() == 2 && starts.size(0) == steps && starts.size(1) == batch, "starts must be [", steps, ", ",
              batch, "], got ", starts.sizes());
  HiderOutput out;
  const torch::Tensor features = encode(images.flatten(0, 1)).to(torch::kFloat32);
  out.features = features.view({steps, batch, kFeatures});
  torch::Tensor x = features;
  if (recurrent()) {
    TORCH_CHECK(hidden.dim() == 2 && hidden.size(0) == batch && hidden.size(1) == kHidden, "hidden must be [", batch,
                ", ", kHidden, "], got ", hidden.sizes());
    // The input side of every step's gates in one matrix product: only the recurrent product is
    // sequential (gruSequence).
    const torch::Tensor input_gates =
        torch::nn::functional::linear(out.features, gru_->weight_ih, gru_->bias_ih);  // [T, B, 1536]
    out.memory = gruSequence(input_gates, 1.0 - starts.to(torch::kFloat32), hidden.to(torch::kFloat32), gru_->weight_hh,
                             gru_->bias_hh);
    x = out.memory.flatten(0, 1);
    if (hidden_out) *hidden_out = out.memory[steps - 1];
  } else if (hidden_out) {
    *hidden_out = hidden;
  }
  heads(x, out);
  out.logits = out.logits.view({steps, batch, kActions});
  out.value = out.value.view({steps, batch});
  return out;
}

HiderNetImpl::Flops HiderNetImpl::forwardFlops() const {
  const int h1 = convOut(image_height_, 8, 4), w1 = convOut(image_width_, 8, 4);
  const int h2 = convOut(h1, 4, 2), w2 = convOut(w1, 4, 2);
  const int h3 = convOut(h2, 3, 1), w3 = convOut(w2, 3, 1);
  // 2 x outputs x inputs per output, layer by layer.
  auto conv = [](int h, int w, int out, int kernel, int in) { return 2.0 * h * w * out * kernel * kernel * in; };
  auto fc = [](int in, int out) { return 2.0 * in * out; };
  Flops f;
  f.first_conv = conv(h1, w1, 32, 8, 3);
  f.total = f.first_conv + conv(h2, w2, 64, 4, 32) + conv(h3, w3, 64, 3, 64) + fc(64 * h3 * w3, kFeatures);
  if (recurrent()) f.total += fc(kFeatures, 3 * kHidden) + fc(kHidden, 3 * kHidden);
  const int head_in = recurrent() ? kHidden : kFeatures;
  f.total += 2 * fc(head_in, 512) + fc(512, kActions) + fc(512, 1);
  return f;
}

torch::Tensor HiderNetImpl::initialHidden(int64_t batch) const {
  return torch::zeros({batch, kHidden}, torch::TensorOptions().device(conv1_->weight.device()).dtype(torch::kFloat32));
}

void saveCheckpoint(const std::string& path, HiderNet& net, const CheckpointInfo& info,
                    torch::optim::Optimizer* optimizer) {
  torch::serialize::OutputArchive archive;
  archive.write("architecture", c10::IValue(info.architecture));
  archive.write("image_height", c10::IValue(static_cast<int64_t>(info.image_height)));
  archive.write("image_width", c10::IValue(static_cast<int64_t>(info.image_width)));
  archive.write("variant", c10::IValue(info.variant));
  archive.write("game", c10::IValue(info.game));
  archive.write("steps", c10::IValue(info.steps));
  archive.write("wall_s", c10::IValue(info.wall_s));
  archive.write("episodes", c10::IValue(info.episodes));
  if (info.recent_lengths.size() != info.recent_returns.size()) {
    throw std::invalid_argument("saveCheckpoint: recent_lengths and recent_returns differ in size");
  }
  archive.write("recent_lengths", torch::tensor(info.recent_lengths, torch::kInt64));
  archive.write("recent_returns", torch::tensor(info.recent_returns, torch::kFloat64));
  torch::serialize::OutputArchive weights;
  net->save(weights);
  archive.write("model", weights);
  archive.write("weights_checksum", c10::IValue(weightsChecksum(net)));
  if (optimizer) {
    torch::serialize::OutputArchive state;
    optimizer->save(state);
    archive.write("optimizer", state);
    archive.write("rng", at::globalContext().defaultGenerator(at::kCPU).get_state());
  }
  // Serialised in memory first: libtorch's file writer ends a file it cannot finish (a full disk)
  // by throwing from a destructor, which terminates the process. Our own writes report the error.
  std::ostringstream bytes;
  archive.save_to(bytes);
  const std::string data = bytes.str();
  writeFileAtomically(path, data);
}

void writeFileAtomically(const std::string& path, const std::string& data) {
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw std::runtime_error("cannot write " + tmp + ": " + std::strerror(errno));
  size_t done = 0;
  int error = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error = n < 0 ? errno : ENOSPC;
      break;
    }
    done += static_cast<size_t>(n);
  }
  if (!error && ::fsync(fd) != 0) error = errno;
  if (::close(fd) != 0 && !error) error = errno;
  if (error) {
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot write " + path + " (" + std::strerror(error) + " after " + std::to_string(done) +
                             " of " + std::to_string(data.size()) + " bytes); the previous file is left as it was");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    error = errno;
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot move " + tmp + " to " + path + ": " + std::strerror(error));
  }
}

namespace {

torch::serialize::InputArchive openArchive(const std::string& path) {
  checkCheckpointArchive(path);  // the zip layout, before libtorch reads a byte of it
  torch::serialize::InputArchive archive;
  try {
    archive.load_from(path);
  } catch (const c10::Error& e) {
    throw std::runtime_error("checkpoint " + path +
                             " cannot be read (missing, truncated or not a checkpoint): " + e.what_without_backtrace());
  }
  return archive;
}

CheckpointInfo infoOf(torch::serialize::InputArchive& archive, const std::string& path) {
  CheckpointInfo info;
  c10::IValue v;
  auto read = [&](const char* key) {
    if (!archive.try_read(key, v)) throw std::runtime_error("checkpoint " + path + " has no '" + key + "' entry");
    return v;
  };
  info.architecture = read("architecture").toStringRef();
  info.image_height = static_cast<int>(read("image_height").toInt());
  info.image_width = static_cast<int>(read("image_width").toInt());
  info.variant = read("variant").toStringRef();
  if (archive.try_read("game", v)) info.game = v.toStringRef();  // absent: written before v3, so v2
  info.steps = read("steps").toInt();
  info.network = info.architecture == kArchitectureGru ? NetworkKind::kGru : NetworkKind::kFeedForward;
  // Progress entries are younger than the format: a checkpoint without them starts from zero.
  if (archive.try_read("wall_s", v)) info.wall_s = v.toDouble();
  if (archive.try_read("episodes", v)) info.episodes = v.toInt();
  torch::Tensor lengths, returns;
  if (archive.try_read("recent_lengths", lengths) && archive.try_read("recent_returns", returns) &&
      lengths.numel() == returns.numel()) {
    lengths = lengths.to(torch::kInt64).contiguous();
    returns = returns.to(torch::kFloat64).contiguous();
    info.recent_lengths.assign(lengths.data_ptr<int64_t>(), lengths.data_ptr<int64_t>() + lengths.numel());
    info.recent_returns.assign(returns.data_ptr<double>(), returns.data_ptr<double>() + returns.numel());
  }
  return info;
}

}  // namespace

CheckpointInfo readCheckpointInfo(const std::string& path) {
  auto archive = openArchive(path);
  return infoOf(archive, path);
}

HiderNet loadCheckpoint(const std::string& path, int expected_height, int expected_width, CheckpointInfo* info_out,
                        std::optional<NetworkKind> expected_network) {
  auto archive = openArchive(path);
  const CheckpointInfo info = infoOf(archive, path);
  if (info.architecture != kArchitecture && info.architecture != kArchitectureGru) {
    throw std::runtime_error("checkpoint " + path + " holds architecture '" + info.architecture +
                             "', this build runs '" + kArchitecture + "' (network ff) or '" + kArchitectureGru +
                             "' (network gru)");
  }
  if (expected_network && *expected_network != info.network) {
    throw std::runtime_error("checkpoint " + path + " holds a " +
                             (info.network == NetworkKind::kGru ? "recurrent (GRU)" : "feed-forward") +
                             " hider (network " + networkName(info.network) + "), but network " +
                             networkName(*expected_network) + " was asked: set network:=" + networkName(info.network) +
                             " or use a " + networkName(*expected_network) + " checkpoint");
  }
  if (info.image_height != expected_height || info.image_width != expected_width) {
    throw std::runtime_error("checkpoint " + path + " was trained on " + std::to_string(info.image_height) + "x" +
                             std::to_string(info.image_width) + " images, the world renders " +
                             std::to_string(expected_height) + "x" + std::to_string(expected_width));
  }
  HiderNet net(info.image_height, info.image_width, info.network);
  torch::serialize::InputArchive weights;
  if (!archive.try_read("model", weights)) throw std::runtime_error("checkpoint " + path + " has no weights");
  // libtorch's load replaces tensors whatever their shape, so compare against the built network.
  // The network is local: a load that fails part way never escapes half-loaded.
  std::map<std::string, std::vector<int64_t>> expected;
  for (const auto& p : net->named_parameters()) expected[p.key()] = p.value().sizes().vec();
  try {
    net->load(weights);
  } catch (const c10::Error& e) {
    throw std::runtime_error("checkpoint " + path + " does not match the network: " + e.what_without_backtrace());
  }
  for (const auto& p : net->named_parameters()) {
    if (p.value().sizes().vec() != expected[p.key()]) {
      std::ostringstream s;
      s << "checkpoint " << path << " does not match the network: " << p.key() << " has shape " << p.value().sizes()
        << ", the network needs " << c10::IntArrayRef(expected[p.key()]);
      throw std::runtime_error(s.str());
    }
  }
  // Checkpoints written before the checksum existed carry none and are taken as they are.
  c10::IValue stored;
  if (archive.try_read("weights_checksum", stored) && stored.toInt() != weightsChecksum(net)) {
    throw std::runtime_error("checkpoint " + path + " is corrupt: its weights do not match their checksum");
  }
  for (const auto& p : net->named_parameters()) {
    if (!p.value().isfinite().all().item<bool>()) {
      throw std::runtime_error("checkpoint " + path + " holds non-finite values in " + p.key());
    }
  }
  if (info_out) *info_out = info;
  return net;
}

void loadTrainingState(const std::string& path, torch::optim::Optimizer& optimizer) {
  auto archive = openArchive(path);
  torch::serialize::InputArchive state;
  torch::Tensor rng;
  if (!archive.try_read("optimizer", state) || !archive.try_read("rng", rng)) {
    throw std::runtime_error("checkpoint " + path + " holds no training state (optimiser, random generator)");
  }
  try {
    optimizer.load(state);
  } catch (const c10::Error& e) {
    throw std::runtime_error("checkpoint " + path + ": optimiser state does not match: " + e.what_without_backtrace());
  }
  at::Generator generator = at::detail::getDefaultCPUGenerator();
  generator.set_state(rng);
}

}  // namespace hideseek_hider
