"""The sweep's queue, its state and its order: which runs config/sweep.yaml's phases hold, which are
done, which a running queue is training. `runner` trains them; `control` reports and steers a
running queue (status, pause, resume, stop, hold, retrain).

The sweep's folder (SWEEP_DIR, default ~/hideseek_sweep) holds the worktrees (trees/<commit>/), the
runs' weights and checkpoints (runs/<run>/), the logs (logs/) and the queue's state (state/): its
lock and PID, one job.<run> file per training run holding its PID, the pause, the runs queued for
retraining.
"""
import os
import subprocess
import time

from hideseek_pipeline import processes as proc
from hideseek_pipeline.sweep_config import Run

RETRAIN_SUFFIX = "_retrain"


class SweepError(Exception):
    """Stops the command with a message naming what is wrong (exit status 2)."""


PAUSES_LOG = "paused.log"  # beside a run's paused_s: one `end_time held_s` line per pause booked


def say(message):
    print("sweep %s: %s" % (time.strftime("%H:%M:%S"), message), flush=True)


class Sweep:
    def __init__(self, checkout, records, config, sweep_dir):
        """`checkout`: where git, the worktrees and the analysis come from; `records`: the Records of
        the checkout that receives them; `config`: the SweepConfig; `sweep_dir`: the sweep's folder."""
        self.checkout, self.records, self.config = checkout, records, config
        self.dir = os.path.realpath(sweep_dir)
        self.runs_dir = os.path.join(self.dir, "runs")
        self.state = os.path.join(self.dir, "state")
        self.logs = os.path.join(self.dir, "logs")

    def make_dirs(self):
        for d in (self.runs_dir, self.state, self.logs):
            os.makedirs(d, exist_ok=True)

    def state_file(self, name):
        return os.path.join(self.state, name)

    def weights(self, name):
        return os.path.join(self.runs_dir, name, "policy.pt")

    def has_weights(self, name):
        path = self.weights(name)
        return os.path.isfile(path) and os.path.getsize(path) > 0

    # ---- the queue's order ----------------------------------------------------------------------

    def retrain_list(self):
        """The runs to train again: config/sweep.yaml's `retrain` (kept in the repository, so a new
        machine trains them too), then those `sweep retrain` queued on this machine."""
        return list(dict.fromkeys(self.config.retrain + read_lines(self.state_file("retrain"))))

    def retrain_runs(self):
        """A retrain is a run of its own, <run>_retrain, recorded beside its first draw (which Table 2
        and the claims keep counting), after every other run of the queue."""
        wanted = set(self.retrain_list())
        return [Run(r.name + RETRAIN_SUFFIX, r.variant, r.seed, r.phase, retrain=True)
                for r in self.config.runs() if r.name in wanted]

    def all_runs(self):
        return self.config.runs() + self.retrain_runs()

    def wants_retrain(self, run):
        first = run.name[:-len(RETRAIN_SUFFIX)]
        return (first in self.retrain_list() and not self.has_weights(first) and not self.has_weights(run.name)
                and not self.records.is_done(run))

    def to_train(self):
        """The runs the queue would start, in order: every run not done, phase by phase and
        seed-major within each, then every run queued for retraining."""
        return [r for r in self.all_runs()
                if (self.wants_retrain(r) if r.retrain else not self.records.is_done(r))]

    # ---- the running queue ----------------------------------------------------------------------

    def queue_running(self):
        return proc.lock_held(self.state_file("queue.lock"))

    def queue_pid(self):
        if not self.queue_running():
            return None
        return proc.read_pid(self.state_file("queue.pid")) or "?"

    def job_pids(self):
        """{run name: PID} of the training runs of a running queue."""
        if not self.queue_running() or not os.path.isdir(self.state):
            return {}
        out = {}
        for f in sorted(os.listdir(self.state)):
            if f.startswith("job."):
                pid = proc.read_pid(self.state_file(f))
                if proc.alive(pid):
                    out[f[4:]] = pid
        return out

    # ---- worktrees --------------------------------------------------------------------------------

    def git(self, *args, cwd=None):
        return subprocess.run(["git"] + list(args), cwd=cwd or self.checkout, capture_output=True, text=True)

    def commit(self, phase):
        """The phase's commit resolved to its full hash (as written where it does not resolve)."""
        r = self.git("rev-parse", "--verify", "-q", phase.commit + "^{commit}")
        return r.stdout.strip() if r.returncode == 0 else phase.commit

    def tree(self, phase):
        """The phase's worktree, named by its resolved commit: two spellings of one commit share it."""
        return os.path.join(self.dir, "trees", self.commit(phase)[:12])



NO_BF16 = ("this CPU has no native bf16 (avx512_bf16 or amx_bf16): sweep runs train only in bf16 on such a CPU; "
           "evaluate and analyse here instead")


def package_path():
    return os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def write_atomically(path, text):
    """`text` into `path` whole or not at all (an interrupted write leaves the old file)."""
    with open(path + ".tmp", "w") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


def remove_file(path):
    try:
        os.remove(path)
    except FileNotFoundError:
        pass


def read_lines(path):
    try:
        with open(path) as f:
            return [line for line in f.read().splitlines() if line.strip()]
    except OSError:
        return []


def last_line(path):
    lines = read_lines(path)
    return lines[-1] if lines else ""
