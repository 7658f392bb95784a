// Every read and write of a checkpoint (checkpoint.h): the network with its description, and for
// training the optimiser and the random generator; written atomically, read only after the zip
// layout is checked.
#include "hideseek_hider/checkpoint.h"

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

namespace hideseek_hider {

namespace {

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

void saveCheckpoint(const std::string& path, HiderNet& net, const CheckpointInfo& info,
                    torch::optim::Optimizer* optimizer) {
  torch::serialize::OutputArchive archive;
  archive.write("architecture", c10::IValue(info.architecture));
  archive.write("image_height", c10::IValue(static_cast<int64_t>(info.image_height)));
  archive.write("image_width", c10::IValue(static_cast<int64_t>(info.image_width)));
  archive.write("variant", c10::IValue(info.variant));
  archive.write("game", c10::IValue(info.game));
  archive.write("role", c10::IValue(info.role));
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
  if (archive.try_read("role", v)) info.role = v.toStringRef();  // absent: written before the seeker learned
  info.steps = read("steps").toInt();
  if (const std::optional<ArchitectureParts> parts = parseArchitecture(info.architecture)) {
    info.network = parts->network;
    info.actions = parts->actions;
  }
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
                        std::optional<NetworkKind> expected_network, const std::string& expected_role,
                        int expected_actions) {
  auto archive = openArchive(path);
  const CheckpointInfo info = infoOf(archive, path);
  if (info.role != expected_role) {
    throw std::runtime_error("checkpoint " + path + " is a " + info.role + "'s policy (role " + info.role +
                             "), not a " + expected_role + "'s: the " + expected_role +
                             "'s nodes and tools play and train " + expected_role + "s only; give a " + expected_role +
                             "'s checkpoint");
  }
  if (!parseArchitecture(info.architecture)) {
    throw std::runtime_error("checkpoint " + path + " holds architecture '" + info.architecture +
                             "', this build runs '" + kArchitecture + "' (network ff) or '" + kArchitectureGru +
                             "' (network gru), with 2 to " + std::to_string(kMaxActions) + " actions");
  }
  if (info.actions != expected_actions) {
    throw std::runtime_error("checkpoint " + path + " chooses among " + std::to_string(info.actions) +
                             " actions, this game gives the " + expected_role + " " + std::to_string(expected_actions) +
                             " (a seeker's actions differ between games: train it on this game)");
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
  HiderNet net(info.image_height, info.image_width, info.network, info.actions);
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
