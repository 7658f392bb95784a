"""make bench: this machine's throughput figures, one `name value` line each (timing goals live
here, never in tests), with `#` lines saying what each group measures. Progress goes to stderr.

The groups: the world core in one process; the same from Python; the world node in lockstep with
two minimal agents; the full game graph; the training floor (network and PPO update in one
process) in fp32 and the default precision, its arithmetic, the GRU's floor, both again in NCHW
order; PPO through the ROS graph with where the hider's loop went, timed after the warm-up
(hideseek_pipeline.measure); training across machines with both ranks here, and one gradient
all-reduce. This machine's speed drifts by 10 % and more over minutes: the floor is timed again
right after the graph, and the efficiency divides by the mean of the floors on either side.
Every group plays game v2, whatever the default game, so that its figures compare over time.
"""
import os
import re
import socket
import subprocess
import tempfile

from tqdm import tqdm

from hideseek_pipeline import measure

PORT = 11433
DD_PORT = 11435


class Options:
    """ARENAS (16), SECONDS_PER_RUN (10), ROS_UPDATES (20: the updates each run through the graph
    is timed over, after measure.WARMUP it warms up on) and FLOOR_UPDATES (4), from the environment."""

    def __init__(self, env=os.environ):
        self.arenas = int(env.get("ARENAS", 16))
        self.seconds = int(env.get("SECONDS_PER_RUN", 10))
        self.ros_updates = int(env.get("ROS_UPDATES", 20))
        self.floor_updates = int(env.get("FLOOR_UPDATES", 4))


def field(text, pattern):
    """The value of the first `name value` line whose name matches `pattern`."""
    for line in text.splitlines():
        parts = line.split()
        if len(parts) >= 2 and re.search(pattern, parts[0]):
            return parts[1]
    raise measure.MeasureError("no line matching %r in:\n%s" % (pattern, text))


def ratio(a, b):
    return "%.2f" % (float(a) / float(b))


class Bench:
    def __init__(self, ws, options, out=print):
        self.ws, self.o, self.out = ws, options, out
        self.rollout = measure.rollout_steps(os.path.join(ws.root, "config", "ppo.yaml"))

    def floor(self, precision, network, memory_format="auto"):
        """train_floor_bench's output: the network and PPO update in one process, 2 threads."""
        return self.ws.command([self.ws.tool("hideseek_hider", "train_floor_bench"), "config/ppo.yaml", self.o.arenas,
                                self.o.floor_updates, 2, precision, network, memory_format])

    def launch_lines(self, launch, pattern):
        text = self.ws.command(["roslaunch", "-p", PORT, "hideseek_world", launch, "num_arenas:=%d" % self.o.arenas,
                                "duration:=%d" % self.o.seconds], env={"ROS_MASTER_URI": "http://localhost:%d" % PORT},
                               check=False)
        lines = [line for line in text.splitlines() if line.startswith(pattern)]
        if not lines:
            raise measure.MeasureError("%s printed no %s line (roslaunch -p %d hideseek_world %s to see why)"
                                       % (launch, pattern, PORT, launch))
        return lines

    def train_through_graph(self, out, network, memory_format="auto"):
        """PPO through the ROS graph (world, seeker, hider in train mode) for WARMUP + ROS_UPDATES
        updates: (samples/s, (update, inference, wait, other) shares of the loop's time)."""
        steps = self.o.arenas * self.rollout * (measure.WARMUP + self.o.ros_updates)
        self.ws.command(["roslaunch", "-p", PORT, "hideseek_world", "train.launch", "game:=v2",
                         "num_arenas:=%d" % self.o.arenas,
                         "steps:=%d" % steps, "output_dir:=" + out, "checkpoint_interval:=100000",
                         "network:=" + network, "memory_format:=" + memory_format],
                        env={"ROS_MASTER_URI": "http://localhost:%d" % PORT}, check=False)
        # As printed: whole samples/s, shares to 3 decimals (the efficiencies below use these).
        return (float("%.0f" % measure.samples_per_s(os.path.join(out, "training_log.csv"))),
                tuple(float("%.3f" % x) for x in measure.loop_shares(os.path.join(out, "loop_profile.csv"))))

    def ros_train(self, network, memory_format="auto"):
        with tempfile.TemporaryDirectory() as run:
            return self.train_through_graph(run, network, memory_format)

    def dd_train(self):
        """2 ranks of 1 learner thread, each its own graph on its own master, rank 0's samples/s
        (its log counts both ranks' samples)."""
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            port = s.getsockname()[1]
        steps = 2 * self.o.arenas * self.rollout * (measure.WARMUP + self.o.ros_updates)
        with tempfile.TemporaryDirectory() as run0, tempfile.TemporaryDirectory() as run1:
            ranks = [subprocess.Popen(
                ["bash", "-c", 'source scripts/env.sh && exec "$@"', "bench", "roslaunch", "-p", str(DD_PORT + r),
                 "hideseek_world", "train.launch", "game:=v2", "num_arenas:=%d" % self.o.arenas, "hider_threads:=1",
                 "world_size:=2", "rank:=%d" % r, "rendezvous:=127.0.0.1:%d" % port, "steps:=%d" % steps,
                 "output_dir:=" + (run0, run1)[r], "checkpoint_interval:=100000"], cwd=self.ws.root,
                env=dict(os.environ, ROS_MASTER_URI="http://localhost:%d" % (DD_PORT + r)),
                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL) for r in (0, 1)]
            try:
                for p in ranks:
                    p.wait()
            finally:  # Ctrl-C: no rank outlives the bench (their output folders go with it)
                for p in ranks:
                    if p.poll() is None:
                        p.terminate()
                        p.wait()
            return float("%.0f" % measure.samples_per_s(os.path.join(run0, "training_log.csv")))

    # The groups, each printing its lines through self.out.

    def graph_groups(self):
        o, out = self.o, self.out
        out("# world core: physics, labels and rendering of %d arenas at 84x84 in one process" % o.arenas)
        out(self.ws.command([self.ws.tool("hideseek_game", "world_core_bench"), "config/game.yaml",
                             "config/variants/basic.yaml", o.arenas, o.seconds]).rstrip())
        out("# the same from Python (hideseek.make_vec, random hider actions, the scripted seeker planning), %d "
            "environments" % o.arenas)
        out(self.ws.command(["/usr/bin/python3", "src/hideseek_python/bench/python_env_bench.py", o.arenas,
                             o.seconds]).rstrip())
        out("# world node in lockstep with two minimal agents as separate processes, %d arenas" % o.arenas)
        for line in self.launch_lines("bench_world.launch", "world_ros_steps_per_s"):
            out(line)
        out("# full game graph in lockstep: world, seeker node, random hider node, %d arenas" % o.arenas)
        for line in self.launch_lines("bench_game.launch", "game_ros_steps_per_s"):
            out(line)

    def floor_groups(self):
        out = self.out
        out("# training floor: the network and PPO update in one process (2 intra-op threads, as the hider")
        out("# node trains), on observations drawn before timing; in fp32 and in the default precision (auto)")
        floor_fp32 = field(self.floor("fp32", "ff"), "_samples_per_s$")
        out("train_floor_fp32_samples_per_s %s" % floor_fp32)
        self.default = self.floor("auto", "ff")
        for line in self.default.splitlines():
            if line.startswith("#"):
                out(line)
        self.floor_sps = field(self.default, "_samples_per_s$")
        out("train_floor_samples_per_s %s" % self.floor_sps)
        out("train_speedup %s" % ratio(self.floor_sps, floor_fp32))
        out("# the floor's arithmetic: FLOPs per sample counted from the network's layers and PPO's passes,")
        out("# achieved GFLOP/s, and their fraction of the peak of the unit the precision's kernels run on: FMA, or")
        out("# AMX-BF16 tiles in bf16 where the CPU has them (the '# peak' line above names it)")
        for name, key in (("train_flops_per_sample", "^flops_per_sample"), ("train_gflops", "^gflops"),
                          ("train_peak_fraction", "^peak_fraction")):
            out("%s %s" % (name, field(self.default, key)))
        out("# recurrent training floor: the GRU network (network gru) and recurrent PPO over sequences, in process,")
        out("# default precision, and its ratio to the feed-forward floor")
        gru_out = self.floor("auto", "gru")
        self.gru_sps = field(gru_out, "_samples_per_s$")
        out("train_gru_samples_per_s %s" % self.gru_sps)
        out("train_gru_ratio %s" % ratio(self.gru_sps, self.floor_sps))
        out("train_gru_gflops %s" % field(gru_out, "^gflops"))

    def memory_format_group(self):
        # NCHW against channels-last, in the floor and (ros_group) the graph: the layout's effect on any CPU
        # (docs/performance.md: 1.4x with AMX-BF16 in Python, none measurable on Zen 4's native bf16).
        out = self.out
        out("# memory format: the floors again with the images copied into NCHW order (memory_format nchw), against")
        out("# the channels-last layout the hider trains in (the '# memory format' line above); their ratios")
        floor_nchw = field(self.floor("auto", "ff", "nchw"), "_samples_per_s$")
        out("train_floor_nchw_samples_per_s %s" % floor_nchw)
        out("train_channels_last_speedup %s" % ratio(self.floor_sps, floor_nchw))
        gru_nchw = field(self.floor("auto", "gru", "nchw"), "_samples_per_s$")
        out("train_gru_nchw_samples_per_s %s" % gru_nchw)
        out("train_gru_channels_last_speedup %s" % ratio(self.gru_sps, gru_nchw))

    def ros_group(self):
        o, out = self.o, self.out
        out("# training through the ROS graph: world, seeker, hider in train mode, %d arenas, 84x84, default" % o.arenas)
        out("# precision, %d updates; the loop's time in the update, in inference, waiting for the world, other"
            % o.ros_updates)
        ros, (update, inference, wait, other) = self.ros_train("ff")
        out("train_ros_samples_per_s %.0f" % ros)
        after = self.floor("auto", "ff")
        floor_after = field(after, "_samples_per_s$")
        out("train_floor_after_samples_per_s %s" % floor_after)
        out("train_efficiency %.2f" % (2 * ros / (float(self.floor_sps) + float(floor_after))))
        # The same ratio at the graph's own speed: the PPO update is the same computation in the floor
        # and the graph, so the graph's update share times the floor's loop-to-update ratio (the mean of
        # both floors') is what the floor would have reached in the graph's seconds; the host's drift
        # between the floor runs and the graph does not move it; it leans high where the other
        # processes slow the graph's update (see docs/performance.md).
        loop_ratio = (float(field(self.default, "^loop_over_update")) + float(field(after, "^loop_over_update"))) / 2
        out("train_efficiency_own_speed %.2f" % (update * loop_ratio))
        for name, share in (("update", update), ("inference", inference), ("wait", wait), ("other", other)):
            out("train_ros_%s_share %.3f" % (name, share))
        ros_nchw, _ = self.ros_train("ff", "nchw")
        out("train_ros_nchw_samples_per_s %.0f" % ros_nchw)
        out("train_ros_channels_last_speedup %s" % ratio(ros, ros_nchw))
        gru_ros, (_, _, gru_wait, _) = self.ros_train("gru")
        out("train_gru_ros_samples_per_s %.0f" % gru_ros)
        gru_after = field(self.floor("auto", "gru"), "_samples_per_s$")
        out("train_gru_efficiency %.2f" % (2 * gru_ros / (float(self.gru_sps) + float(gru_after))))
        out("train_gru_ros_wait_share %.3f" % gru_wait)
        self.ros = ros

    def ddppo_group(self):
        o, out = self.o, self.out
        out("# training across machines, both ranks here: 2 ranks x 1 learner thread, %d arenas each, against" % o.arenas)
        out("# train_ros_samples_per_s (1 rank x 2 threads); one gradient all-reduce between 2 ranks on loopback")
        dd = self.dd_train()
        out("train_ddppo_2ranks_samples_per_s %.0f" % dd)
        out("train_ddppo_2ranks_ratio %s" % ratio(dd, self.ros))
        for line in self.ws.command([self.ws.tool("hideseek_hider", "allreduce_bench"), 20]).splitlines():
            out("ddppo_" + line)


def bench(ws, options=None):
    """Every group in turn, a progress bar on stderr; returns 0, or raises ToolError / MeasureError
    naming the step that failed."""
    b = Bench(ws, options or Options(), out=tqdm.write)
    groups = [("world and game graph", b.graph_groups), ("training floor", b.floor_groups),
              ("memory format", b.memory_format_group), ("training through the graph", b.ros_group),
              ("training across machines", b.ddppo_group)]
    with tqdm(total=len(groups), desc="bench", unit="group", leave=False) as bar:
        for name, group in groups:
            bar.set_postfix_str(name)
            group()
            bar.update(1)
    return 0
