// The hideseek module's C++ layer (hideseek._core): VecGame's arrays as numpy arrays. The Gymnasium
// interface itself is Python (python/hideseek/env.py). Stepping and resetting release the GIL.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "hideseek_game/config_error.h"
#include "hideseek_game/game_selection.h"
#include "hideseek_game/package_paths.h"
#include "hideseek_python/vec_game.h"

namespace py = pybind11;
using hideseek_python::VecGame;

namespace {

template <typename T>
py::array_t<T> toArray(const std::vector<T>& v) {
  py::array_t<T> out(static_cast<py::ssize_t>(v.size()));
  if (!v.empty()) std::memcpy(out.mutable_data(), v.data(), v.size() * sizeof(T));
  return out;
}

py::array_t<uint8_t> images(const VecGame& g, const std::vector<uint8_t>& bytes) {
  py::array_t<uint8_t> out({g.numEnvs(), g.height(), g.width(), 3});
  std::memcpy(out.mutable_data(), bytes.data(), bytes.size());
  return out;
}

py::array_t<uint8_t> observations(const VecGame& g) { return images(g, g.observations()); }

// The terminal images of the episodes the last step ended (zeros, or an earlier episode's, elsewhere).
py::array_t<uint8_t> terminalObservations(const VecGame& g) {
  if (g.terminalObservations().empty()) throw std::logic_error("keep_terminal_views() was not called");
  return images(g, g.terminalObservations());
}

py::array_t<uint8_t> seekerObservations(const VecGame& g) {
  if (!g.seekerOutside()) throw std::invalid_argument("the scripted seeker renders no images: seeker_outside=True");
  return images(g, g.seekerObservations());
}

std::vector<uint8_t> actionVector(const py::array_t<uint8_t, py::array::c_style | py::array::forcecast>& a,
                                  const char* what) {
  if (a.ndim() != 1) throw std::invalid_argument(std::string(what) + " must be one-dimensional, one per environment");
  return std::vector<uint8_t>(a.data(), a.data() + a.size());
}

py::array_t<bool> flags(const std::vector<uint8_t>& v) {
  py::array_t<bool> out(static_cast<py::ssize_t>(v.size()));
  for (size_t i = 0; i < v.size(); ++i) out.mutable_data()[i] = v[i] != 0;
  return out;
}

// The state of every arena (ObservationBatch's labels, poses, seed, step, episode).
py::dict infos(const VecGame& g) {
  const int n = g.numEnvs();
  py::array_t<bool> s(n), h(n), o(n);
  py::array_t<double> hider({n, 3}), seeker({n, 3});
  py::array_t<int64_t> seed(n), step(n), episode(n);  // int64: differences of them do not wrap
  for (int i = 0; i < n; ++i) {
    const hideseek_python::ArenaInfo a = g.info(i);
    s.mutable_data()[i] = a.hider_sees_seeker;
    h.mutable_data()[i] = a.seeker_sees_hider;
    o.mutable_data()[i] = a.obstacle_in_view;
    for (int k = 0; k < 3; ++k) {
      hider.mutable_data()[3 * i + k] = a.hider_pose[k];
      seeker.mutable_data()[3 * i + k] = a.seeker_pose[k];
    }
    seed.mutable_data()[i] = a.seed;
    step.mutable_data()[i] = a.step;
    episode.mutable_data()[i] = a.episode;
  }
  py::dict d;
  d["S"] = s;
  d["H"] = h;
  d["O"] = o;
  d["hider_pose"] = hider;
  d["seeker_pose"] = seeker;
  d["seed"] = seed;
  d["step"] = step;
  d["episode_index"] = episode;
  return d;
}

// The episodes the last step ended: their length, return, outcome and terminal state (zeros where
// none ended; "_mask" says where one did).
py::dict finished(const VecGame& g) {
  const int n = g.numEnvs();
  py::array_t<bool> mask(n), s(n), h(n), o(n);
  py::array_t<int32_t> length(n);
  py::array_t<double> ret(n), seeker_ret(n), hider({n, 3}), seeker({n, 3});
  py::array_t<uint8_t> outcome(n);
  py::array_t<int64_t> seed(n), episode(n);
  for (int i = 0; i < n; ++i) {
    const auto& f = g.finished(i);
    const hideseek_game::EpisodeSummary e = f ? *f : hideseek_game::EpisodeSummary{};
    mask.mutable_data()[i] = f.has_value();
    s.mutable_data()[i] = e.labels.hider_sees_seeker;
    h.mutable_data()[i] = e.labels.seeker_sees_hider;
    o.mutable_data()[i] = e.labels.obstacle_in_view;
    length.mutable_data()[i] = e.steps;
    ret.mutable_data()[i] = e.episode_return;
    seeker_ret.mutable_data()[i] = e.seeker_return;
    outcome.mutable_data()[i] = static_cast<uint8_t>(e.outcome);
    const double hp[3] = {e.hider.position.x, e.hider.position.y, e.hider.yaw};
    const double sp[3] = {e.seeker.position.x, e.seeker.position.y, e.seeker.yaw};
    for (int k = 0; k < 3; ++k) {
      hider.mutable_data()[3 * i + k] = hp[k];
      seeker.mutable_data()[3 * i + k] = sp[k];
    }
    seed.mutable_data()[i] = e.seed;
    episode.mutable_data()[i] = e.episode;
  }
  py::dict d;
  d["_mask"] = mask;
  d["length"] = length;
  d["return"] = ret;
  d["seeker_return"] = seeker_ret;
  d["outcome"] = outcome;
  d["S"] = s;
  d["H"] = h;
  d["O"] = o;
  d["hider_pose"] = hider;
  d["seeker_pose"] = seeker;
  d["seed"] = seed;
  d["episode_index"] = episode;
  return d;
}

// A reader of the game's state, run under its lock (the GIL is held: a thread stepping the same
// game holds the lock without the GIL and never waits for it, so this cannot deadlock).
template <typename F>
auto locked(F f) {
  return [f](const VecGame& g) {
    std::lock_guard<std::mutex> lock(g.mutex());
    return f(g);
  };
}

hideseek_hider::EvaderKind evader(const std::string& name) {
  const auto kind = hideseek_hider::evaderKind(name);
  if (!kind)
    throw std::invalid_argument("'" + name + "' names no scripted hider: random, backpedal, flee, hide or lap");
  return *kind;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "Visual Hide and Seek's game in process (C++ core of the hideseek module)";
  py::register_exception<hideseek_game::ConfigError>(m, "ConfigError", PyExc_ValueError);
  m.def("config_directory", &hideseek_game::configDirectory,
        "the installed config folder of the hideseek_game package (needs the workspace's setup.bash sourced)");
  m.def("default_game", &hideseek_game::defaultGame, py::arg("config_dir"),
        "the game played where none is named: config_dir/games.yaml's default");
  m.attr("num_actions") = hideseek_game::kNumActions;

  py::class_<VecGame>(m, "VecGame")
      .def(py::init([](const std::string& config_dir, const std::string& game, const std::string& variant, int num_envs,
                       uint32_t seed, int render_threads, bool seeker_outside, const std::string& variant_file) {
             return new VecGame(hideseek_python::loadVariant(config_dir, game, variant, variant_file), num_envs, seed,
                                render_threads, seeker_outside);
           }),
           py::arg("config_dir"), py::arg("game"), py::arg("variant"), py::arg("num_envs"), py::arg("seed"),
           py::arg("render_threads") = 2, py::arg("seeker_outside") = false, py::arg("variant_file") = "")
      .def_property_readonly("seeker_outside", &VecGame::seekerOutside)
      .def_property_readonly("seeker_actions", &VecGame::seekerActions)
      .def_property_readonly("num_envs", &VecGame::numEnvs)
      .def_property_readonly("height", &VecGame::height)
      .def_property_readonly("width", &VecGame::width)
      .def_property_readonly("max_steps", &VecGame::maxSteps)
      .def_property_readonly(
          "step_duration", [](const VecGame& g) { return g.variant().game.stepDuration(); },
          "seconds of game time a decision step lasts (action_repeat physics frames)")
      .def_property_readonly("seeker_policy", [](const VecGame& g) { return g.variant().seeker_policy; })
      .def_property_readonly("map_file", [](const VecGame& g) { return g.variant().map_file; })
      .def_property_readonly("decisions", &VecGame::decisions)
      .def(
          "reset",
          [](VecGame& g, const std::vector<int64_t>& seeds) {
            py::gil_scoped_release release;
            std::lock_guard<std::mutex> lock(g.mutex());
            g.reset(seeds);
          },
          py::arg("seeds"), "new episodes: seeds per environment, one seed (seed + i), or [] (the next ones)")
      .def(
          "reset_env",
          [](VecGame& g, int env, int64_t seed) {
            py::gil_scoped_release release;
            std::lock_guard<std::mutex> lock(g.mutex());
            g.resetEnv(env, seed);
          },
          py::arg("env"), py::arg("seed") = -1)
      .def(
          "step",
          [](VecGame& g, py::array_t<uint8_t, py::array::c_style | py::array::forcecast> actions,
             std::optional<py::array_t<uint8_t, py::array::c_style | py::array::forcecast>> seeker) {
            const std::vector<uint8_t> a = actionVector(actions, "actions");
            const std::vector<uint8_t> s = seeker ? actionVector(*seeker, "seeker actions") : std::vector<uint8_t>{};
            {
              py::gil_scoped_release release;
              std::lock_guard<std::mutex> lock(g.mutex());
              if (g.seekerOutside() || seeker) {
                g.step(a, s);
              } else {
                g.step(a);
              }
            }
          },
          py::arg("actions"), py::arg("seeker_actions") = py::none(),
          "one step: the hider's actions, and the seeker's where it plays from outside (seeker_outside)")
      .def("observations", locked(&observations), "uint8 [num_envs, height, width, 3], rgb, rows top down")
      .def(
          "keep_terminal_views",
          [](VecGame& g, bool seeker) {
            std::lock_guard<std::mutex> lock(g.mutex());
            g.keepTerminalViews(seeker);
          },
          py::arg("seeker") = false,
          "from now on, render each ended episode's terminal state as one side's camera shows it (the seeker's: "
          "seeker_outside only)")
      .def("terminal_observations", locked(&terminalObservations),
           "where the last step ended an episode: its terminal state's image, uint8 [num_envs, height, width, 3]; "
           "elsewhere zeros or an earlier episode's")
      .def("rewards", locked([](const VecGame& g) { return toArray(g.rewards()); }))
      .def("seeker_observations", locked(&seekerObservations),
           "seeker_outside: the seekers' camera images, uint8 [num_envs, height, width, 3]")
      .def("seeker_rewards", locked([](const VecGame& g) { return toArray(g.seekerRewards()); }),
           "the seeker's rewards (the game file's seeker_rewards)")
      .def("random_seeker_actions", locked([](const VecGame& g) { return toArray(g.randomSeekerActions()); }),
           "the uniformly random seeker's actions for the current state (seed and step)")
      .def("done", locked([](const VecGame& g) { return flags(g.done()); }))
      .def("outcomes", locked([](const VecGame& g) { return toArray(g.outcomes()); }),
           "0 running, 1 captured, 2 survived")
      .def("infos", locked(&infos))
      .def("finished", locked(&finished))
      .def(
          "scripted_actions",
          [](VecGame& g, const std::string& name) {
            const hideseek_hider::EvaderKind kind = evader(name);
            std::vector<uint8_t> a;
            {
              py::gil_scoped_release release;
              std::lock_guard<std::mutex> lock(g.mutex());
              a = g.scriptedActions(kind);
            }
            return toArray(a);
          },
          py::arg("name"));
}
