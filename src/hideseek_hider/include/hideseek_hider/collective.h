// The ranks of a data-parallel training (DD-PPO, as Habitat trains its agents): each rank plays
// its own arenas, and the ranks average their gradients before every optimiser step so that
// their weights stay identical. The transport is libtorch's own c10d: a TCPStore for the
// rendezvous (hosted by rank 0) and a Gloo process group for the collectives. ROS-free.
#pragma once

#include <torch/torch.h>

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace hideseek_hider {

// What the ranks must agree on: variant, network, precision, code version, PPO options, ...
// (name -> value). A rank whose fingerprint differs from rank 0's is refused at rendezvous.
using Fingerprint = std::map<std::string, std::string>;

struct RendezvousOptions {
  int world_size = 1;
  int rank = 0;
  // host:port of the TCPStore rank 0 hosts; every rank connects to it. The Gloo process group
  // binds to the address this host reaches that host through (`interface_host` overrides it).
  std::string address = "127.0.0.1:29500";
  std::string interface_host;  // empty: the local address that routes to the rendezvous host
  // Seconds a collective or the rendezvous waits for the other ranks before it fails, naming the
  // ranks that stopped.
  double timeout_s = 120.0;
  Fingerprint fingerprint;
};

// A rank stopped, hung or disagreed: what() names the rank and what happened.
class CollectiveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What PPO needs from the ranks. Every call is collective: all ranks make the same calls in the
// same order, with tensors of the same shapes.
class Collective {
 public:
  virtual ~Collective() = default;
  virtual int rank() const = 0;
  virtual int worldSize() const = 0;
  // Sums the tensors across ranks, in place.
  virtual void allReduceSum(std::vector<torch::Tensor>& tensors) = 0;
  // Copies rank `root`'s tensors into every rank's, in place.
  virtual void broadcast(std::vector<torch::Tensor>& tensors, int root) = 0;
  // Tells the other ranks that this one is stopping because of `reason` (best effort), so that
  // their next collective fails naming it instead of waiting out the timeout.
  virtual void abort(const std::string& reason) = 0;
};

// "host:port" -> (host, port); throws std::invalid_argument naming `what`.
std::pair<std::string, int> parseHostPort(const std::string& address, const std::string& what);

// The address (dotted quad) of the local interface that routes to `host`.
std::string localAddressTowards(const std::string& host);

// Joins the ranks: rank 0 hosts the store; every rank publishes its fingerprint and checks the
// others' against rank 0's, then the Gloo group connects. Throws CollectiveError on a timeout or
// a mismatch (naming the rank and the field), std::invalid_argument on bad options.
std::unique_ptr<Collective> joinRanks(const RendezvousOptions& options);

// Averages the gradients of `parameters` across the ranks, in place, with one all-reduce of a
// flat buffer (parameters without a gradient contribute zeros, so that all ranks agree).
void averageGradients(Collective& collective, const std::vector<torch::Tensor>& parameters);

// Copies rank 0's parameters and buffers into every rank's.
void broadcastModule(Collective& collective, torch::nn::Module& module);

// Bytes from rank 0 to every rank (rank 0's `bytes` in; every rank's out).
std::string broadcastBytes(Collective& collective, const std::string& bytes);

}  // namespace hideseek_hider
