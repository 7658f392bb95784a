#include "hideseek_hider/collective.h"

#include <arpa/inet.h>
#include <netdb.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <sstream>
#include <thread>
#include <torch/csrc/distributed/c10d/PrefixStore.hpp>
#include <torch/csrc/distributed/c10d/ProcessGroupGloo.hpp>
#include <torch/csrc/distributed/c10d/TCPStore.hpp>

namespace hideseek_hider {

namespace {

using Ms = std::chrono::milliseconds;

Ms millis(double seconds) { return Ms(static_cast<int64_t>(seconds * 1000.0)); }

std::vector<uint8_t> bytesOf(const std::string& s) { return {s.begin(), s.end()}; }
std::string textOf(const std::vector<uint8_t>& b) { return {b.begin(), b.end()}; }

std::string serialize(const Fingerprint& f) {
  std::string out;
  for (const auto& [key, value] : f) out += key + '=' + value + '\n';
  return out;
}

Fingerprint deserialize(const std::string& text) {
  Fingerprint f;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const size_t eq = line.find('=');
    if (eq != std::string::npos) f[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return f;
}

// What differs between rank `rank`'s fingerprint and rank 0's, or "".
std::string difference(const Fingerprint& mine, const Fingerprint& reference, int rank) {
  std::string out;
  auto add = [&](const std::string& text) { out += (out.empty() ? "" : "; ") + text; };
  for (const auto& [key, value] : reference) {
    const auto it = mine.find(key);
    if (it == mine.end()) {
      add("rank " + std::to_string(rank) + " has no " + key + " (rank 0's is '" + value + "')");
    } else if (it->second != value) {
      add("rank " + std::to_string(rank) + "'s " + key + " is '" + it->second + "', rank 0's is '" + value + "'");
    }
  }
  for (const auto& [key, value] : mine) {
    if (!reference.count(key))
      add("rank 0 has no " + key + " (rank " + std::to_string(rank) + "'s is '" + value + "')");
  }
  return out;
}

class GlooCollective : public Collective {
 public:
  explicit GlooCollective(const RendezvousOptions& o)
      : rank_(o.rank), world_(o.world_size), timeout_(millis(o.timeout_s)), address_(o.address) {
    const auto [host, port] = parseHostPort(o.address, "the rendezvous address");
    c10d::TCPStoreOptions so;
    so.port = static_cast<uint16_t>(port);
    so.isServer = rank_ == 0;
    so.numWorkers = world_;
    so.waitWorkers = false;  // the fingerprints below wait, with an error that names who is missing
    so.timeout = timeout_;
    try {
      store_ = c10::make_intrusive<c10d::TCPStore>(host, so);
      // A second connection for the heartbeat and for diagnosing a failure: it never queues
      // behind the process group's own use of the store.
      c10d::TCPStoreOptions side = so;
      side.isServer = false;
      side.timeout = Ms(5000);
      side_ = c10::make_intrusive<c10d::TCPStore>(host, side);
    } catch (const std::exception& e) {
      throw CollectiveError("DD-PPO rank " + std::to_string(rank_) + ": cannot " + (rank_ == 0 ? "host" : "reach") +
                            " the rendezvous at " + o.address + " within " +
                            std::to_string(static_cast<int>(o.timeout_s)) + " s: " + firstLine(e.what()));
    }
    checkFingerprints(o);
    heartbeat_ = std::thread([this] { beat(); });
    auto options = c10d::ProcessGroupGloo::Options::create(timeout_);
    const std::string local = o.interface_host.empty() ? localAddressTowards(host) : o.interface_host;
    options->devices.push_back(c10d::ProcessGroupGloo::createDeviceForHostname(local));
    try {
      group_ = c10::make_intrusive<c10d::ProcessGroupGloo>(c10::make_intrusive<c10d::PrefixStore>("gloo", store_),
                                                           rank_, world_, options);
    } catch (const std::exception& e) {
      stopHeartbeat();
      throw CollectiveError(diagnose("connecting the ranks", e.what()));
    }
  }

  ~GlooCollective() override {
    stopHeartbeat();
    // Rank 0 hosts the store: it waits (a while) for the others to say they are done with it.
    try {
      side_->add("finished", 1);
      if (rank_ == 0) {
        const auto until = std::chrono::steady_clock::now() + std::min(timeout_, Ms(10000));
        while (side_->add("finished", 0) < world_ && std::chrono::steady_clock::now() < until) {
          std::this_thread::sleep_for(Ms(50));
        }
      }
    } catch (const std::exception&) {
      // The store's host is gone: nothing left to tell it.
    }
  }

  int rank() const override { return rank_; }
  int worldSize() const override { return world_; }

  void allReduceSum(std::vector<torch::Tensor>& tensors) override {
    run("an all-reduce", [&] { return group_->allreduce(tensors); });
  }

  void broadcast(std::vector<torch::Tensor>& tensors, int root) override {
    c10d::BroadcastOptions b;
    b.rootRank = root;
    run("a broadcast", [&] { return group_->broadcast(tensors, b); });
  }

  void abort(const std::string& reason) override {
    try {
      side_->set("abort", bytesOf("rank " + std::to_string(rank_) + " stopped: " + reason));
    } catch (const std::exception&) {
      // Best effort: the store's host may be the one that is gone.
    }
  }

 private:
  static std::string firstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

  template <class Start>
  void run(const char* what, Start start) {
    ++ops_;
    try {
      side_->set("progress/" + std::to_string(rank_), bytesOf(std::to_string(ops_)));
      start()->wait();
    } catch (const std::exception& e) {
      throw CollectiveError(diagnose(what, e.what()));
    }
  }

  void checkFingerprints(const RendezvousOptions& o) {
    Fingerprint mine = o.fingerprint;
    mine["world_size"] = std::to_string(world_);
    const std::string me = std::to_string(rank_);
    try {
      if (store_->add("joined/" + me, 1) > 1) {
        throw CollectiveError("DD-PPO: two processes claim rank " + me + " at " + address_ +
                              " (give each rank its own rank:=)");
      }
      store_->set("fingerprint/" + me, bytesOf(serialize(mine)));
    } catch (const CollectiveError&) {
      throw;
    } catch (const std::exception& e) {
      throw CollectiveError("DD-PPO rank " + me + ": the rendezvous at " + address_ +
                            " failed: " + firstLine(e.what()));
    }
    try {
      compareFingerprints(o, me);
    } catch (const CollectiveError&) {
      throw;
    } catch (const std::exception& e) {
      // The store's host, rank 0, went away while this rank read the others' settings.
      throw CollectiveError(
          "DD-PPO rank " + me + ": the rendezvous at " + address_ +
          " failed while the ranks compared their settings (rank 0, its host, stopped): " + firstLine(e.what()));
    }
  }

  // Waits for every rank's fingerprint, naming those that do not come, and compares them with
  // rank 0's. Rank 0 hosts the store: it stays until every rank has read the fingerprints, so that
  // each rank can name what differs, whichever finds it first.
  void compareFingerprints(const RendezvousOptions& o, const std::string& me) {
    const auto until = std::chrono::steady_clock::now() + timeout_;
    std::vector<int> missing;
    do {
      missing.clear();
      for (int r = 0; r < world_; ++r) {
        if (!store_->check({"fingerprint/" + std::to_string(r)})) missing.push_back(r);
      }
      if (missing.empty()) break;
      std::this_thread::sleep_for(Ms(100));
    } while (std::chrono::steady_clock::now() < until);
    if (!missing.empty()) {
      std::string names;
      for (int r : missing) names += (names.empty() ? "" : ", ") + std::to_string(r);
      throw CollectiveError("DD-PPO rank " + me + ": rank" + (missing.size() > 1 ? "s " : " ") + names +
                            " did not join the rendezvous at " + address_ + " within " +
                            std::to_string(static_cast<int>(o.timeout_s)) + " s (world_size " + std::to_string(world_) +
                            ")");
    }
    const Fingerprint reference = deserialize(textOf(store_->get("fingerprint/0")));
    std::string differences;
    for (int r = 1; r < world_; ++r) {
      const std::string d =
          difference(deserialize(textOf(store_->get("fingerprint/" + std::to_string(r)))), reference, r);
      if (!d.empty()) differences += (differences.empty() ? "" : "; ") + d;
    }
    store_->add("fingerprints_read", 1);
    if (rank_ == 0) {
      while (store_->add("fingerprints_read", 0) < world_ && std::chrono::steady_clock::now() < until) {
        std::this_thread::sleep_for(Ms(20));
      }
    }
    if (!differences.empty()) {
      throw CollectiveError("DD-PPO: the ranks disagree, so none trains: " + differences);
    }
  }

  void beat() {
    const std::string key = "heartbeat/" + std::to_string(rank_);
    std::unique_lock<std::mutex> lock(beat_mutex_);
    while (!stop_) {
      try {
        side_->add(key, 1);
      } catch (const std::exception&) {
        // The store's host is gone; a collective will say so.
      }
      beat_cv_.wait_for(lock, Ms(500), [this] { return stop_.load(); });
    }
  }

  void stopHeartbeat() {
    {
      const std::lock_guard<std::mutex> lock(beat_mutex_);
      stop_ = true;
    }
    beat_cv_.notify_all();
    if (heartbeat_.joinable()) heartbeat_.join();
  }

  // Which rank stopped: an abort message, a rank whose heartbeat no longer moves (dead or
  // frozen), or one behind this rank's collectives (hung); the store's host unreachable is rank 0.
  std::string diagnose(const char* what, const std::string& error) {
    const std::string me = std::to_string(rank_);
    const std::string tail = "; rank " + me + " stops too (" + what + " failed: " + firstLine(error) + ")";
    try {
      if (side_->check({"abort"})) return "DD-PPO: " + textOf(side_->get("abort")) + tail;
      auto beats = [&] {
        std::vector<int64_t> b(world_, 0);
        for (int r = 0; r < world_; ++r) b[r] = side_->add("heartbeat/" + std::to_string(r), 0);
        return b;
      };
      const std::vector<int64_t> before = beats();
      std::this_thread::sleep_for(Ms(2500));
      const std::vector<int64_t> after = beats();
      std::string found;
      for (int r = 0; r < world_; ++r) {
        if (r == rank_) continue;
        std::string why;
        if (after[r] == before[r]) {
          why = "rank " + std::to_string(r) + " stopped (no heartbeat for 2.5 s)";
        } else {
          const std::string key = "progress/" + std::to_string(r);
          const int64_t theirs = side_->check({key}) ? std::stoll(textOf(side_->get(key))) : 0;
          if (theirs < ops_) {
            why = "rank " + std::to_string(r) + " hangs (its last collective is #" + std::to_string(theirs) +
                  ", rank " + me + "'s #" + std::to_string(ops_) + ")";
          }
        }
        if (!why.empty()) found += (found.empty() ? "" : "; ") + why;
      }
      if (!found.empty()) return "DD-PPO: " + found + tail;
      return "DD-PPO: a rank failed" + tail;
    } catch (const std::exception&) {
      return "DD-PPO: rank 0, which hosts the rendezvous at " + address_ +
             ", is unreachable (stopped, or the network failed)" + tail;
    }
  }

  int rank_, world_;
  Ms timeout_;
  std::string address_;
  c10::intrusive_ptr<c10d::TCPStore> store_, side_;
  c10::intrusive_ptr<c10d::ProcessGroupGloo> group_;
  int64_t ops_ = 0;
  std::thread heartbeat_;
  std::mutex beat_mutex_;
  std::condition_variable beat_cv_;
  std::atomic<bool> stop_{false};
};

}  // namespace

std::pair<std::string, int> parseHostPort(const std::string& address, const std::string& what) {
  const size_t colon = address.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == address.size()) {
    throw std::invalid_argument(what + " '" + address + "' is not host:port");
  }
  const std::string host = address.substr(0, colon), port_text = address.substr(colon + 1);
  size_t used = 0;
  int port = -1;
  try {
    port = std::stoi(port_text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != port_text.size() || port < 1 || port > 65535) {
    throw std::invalid_argument(what + " '" + address + "': the port must be a number in 1..65535");
  }
  return {host, port};
}

std::string localAddressTowards(const std::string& host) {
  addrinfo hints{}, *found = nullptr;
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_DGRAM;
  if (getaddrinfo(host.c_str(), "9", &hints, &found) != 0 || !found) {
    throw std::invalid_argument("cannot resolve the rendezvous host '" + host + "'");
  }
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  std::string out;
  // A UDP connect sends nothing: it only asks the kernel which local address routes there.
  if (fd >= 0 && connect(fd, found->ai_addr, found->ai_addrlen) == 0) {
    sockaddr_in local{};
    socklen_t length = sizeof(local);
    if (getsockname(fd, reinterpret_cast<sockaddr*>(&local), &length) == 0) {
      char text[INET_ADDRSTRLEN];
      if (inet_ntop(AF_INET, &local.sin_addr, text, sizeof(text))) out = text;
    }
  }
  if (fd >= 0) close(fd);
  freeaddrinfo(found);
  if (out.empty()) throw std::invalid_argument("no local interface routes to the rendezvous host '" + host + "'");
  return out;
}

std::unique_ptr<Collective> joinRanks(const RendezvousOptions& options) {
  if (options.world_size < 1) throw std::invalid_argument("world_size must be at least 1");
  if (options.rank < 0 || options.rank >= options.world_size) {
    throw std::invalid_argument("rank " + std::to_string(options.rank) + " is not in 0.." +
                                std::to_string(options.world_size - 1) + " (world_size " +
                                std::to_string(options.world_size) + ")");
  }
  if (!(options.timeout_s > 0.0)) throw std::invalid_argument("the DD-PPO timeout must be positive");
  // A rank killed mid-collective closes its sockets; a write to one raises SIGPIPE, whose default
  // action killed this rank before it could name the dead one (seen on one busy core). Ignored, the
  // write fails with EPIPE, Gloo throws, and the rank stops with its message. (roscpp ignores
  // SIGPIPE too, so a ROS node is unchanged.)
  signal(SIGPIPE, SIG_IGN);
  return std::make_unique<GlooCollective>(options);
}

void averageGradients(Collective& collective, const std::vector<torch::Tensor>& parameters) {
  std::vector<torch::Tensor> grads;
  grads.reserve(parameters.size());
  for (const torch::Tensor& p : parameters) {
    grads.push_back(p.grad().defined() ? p.grad().reshape({-1}) : torch::zeros({p.numel()}, p.options()));
  }
  std::vector<torch::Tensor> flat{torch::cat(grads)};
  collective.allReduceSum(flat);
  flat[0].div_(collective.worldSize());
  int64_t offset = 0;
  for (const torch::Tensor& p : parameters) {
    const int64_t n = p.numel();
    if (p.grad().defined()) {
      p.mutable_grad().copy_(flat[0].slice(0, offset, offset + n).view_as(p));
    } else {
      p.mutable_grad() = flat[0].slice(0, offset, offset + n).view_as(p).clone();
    }
    offset += n;
  }
}

void broadcastModule(Collective& collective, torch::nn::Module& module) {
  const torch::NoGradGuard no_grad;
  std::vector<torch::Tensor> tensors;
  for (const torch::Tensor& p : module.parameters()) tensors.push_back(p.detach());
  for (const torch::Tensor& b : module.buffers()) tensors.push_back(b);
  if (tensors.empty()) return;
  // One flat buffer: one broadcast, whatever the layer count.
  std::vector<torch::Tensor> pieces;
  for (const torch::Tensor& t : tensors) pieces.push_back(t.reshape({-1}).to(torch::kFloat64));
  std::vector<torch::Tensor> flat{torch::cat(pieces)};
  collective.broadcast(flat, 0);
  int64_t offset = 0;
  for (torch::Tensor& t : tensors) {
    const int64_t n = t.numel();
    t.copy_(flat[0].slice(0, offset, offset + n).view(t.sizes()));
    offset += n;
  }
}

std::string broadcastBytes(Collective& collective, const std::string& bytes) {
  std::vector<torch::Tensor> size{torch::tensor({static_cast<int64_t>(bytes.size())}, torch::kInt64)};
  collective.broadcast(size, 0);
  const int64_t n = size[0].item<int64_t>();
  std::vector<torch::Tensor> data{torch::zeros({std::max<int64_t>(n, 1)}, torch::kUInt8)};
  if (collective.rank() == 0 && n > 0) std::memcpy(data[0].data_ptr<uint8_t>(), bytes.data(), n);
  collective.broadcast(data, 0);
  return std::string(reinterpret_cast<const char*>(data[0].data_ptr<uint8_t>()), n);
}

}  // namespace hideseek_hider
