"""The sweep's queue: trains every missing run of config/sweep.yaml's phases from a git worktree
built at the phase's commit, evaluates each run the moment it finishes (seeds 0-99, greedy and
sampled), records it into the checkout (docs/runs/<run>/ and policies/policies.yaml), analyses it
and ships each variant's median run. Runs resume from their checkpoints.

The sweep's folder (SWEEP_DIR, default ~/hideseek_sweep) holds the worktrees (trees/<commit>/), the
runs' weights and checkpoints (runs/<run>/), the logs (logs/) and the queue's state (state/): its
lock and PID, one job.<run> file per training run holding its PID, the pause, the runs queued for
retraining.
"""
import multiprocessing
import os
import signal
import subprocess
import sys
import time

from hideseek_pipeline import processes as proc
from hideseek_pipeline.records import SWEEP_NOTE
from hideseek_pipeline.sweep_config import Run

RETRAIN_SUFFIX = "_retrain"


class SweepError(Exception):
    """Stops the command with a message naming what is wrong (exit status 2)."""


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
        try:
            with open(self.state_file("retrain")) as f:
                return [line.strip() for line in f if line.strip()]
        except OSError:
            return []

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

    def tree(self, phase):
        return os.path.join(self.dir, "trees", phase.commit[:12])

    def prepare_tree(self, phase):
        """The worktree at the phase's commit, built (catkin_make, Release, no tests) once."""
        if self.git("rev-parse", "--verify", "-q", phase.commit + "^{commit}").returncode != 0:
            raise SweepError("phase %s: commit %s is not in this repository (fetch it first)" % (phase.name, phase.commit))
        full = self.git("rev-parse", phase.commit).stdout.strip()
        tree = self.tree(phase)
        self.git("worktree", "prune")
        if not os.path.exists(os.path.join(tree, ".git")):
            say("creating the worktree %s at %s" % (tree, full))
            os.makedirs(os.path.dirname(tree), exist_ok=True)
            r = self.git("worktree", "add", "--detach", tree, full)
            if r.returncode != 0:
                raise SweepError("git worktree add %s failed: %s" % (tree, r.stderr.strip()))
        elif self.git("rev-parse", "HEAD", cwd=tree).stdout.strip() != full:
            raise SweepError("the worktree %s is not at %s" % (tree, full))
        if self.git("status", "--porcelain", cwd=tree).stdout.strip():
            raise SweepError("the worktree %s has uncommitted changes; a sweep run trains from a clean tree "
                             "(git -C %s status)" % (tree, tree))
        built = self.state_file("built." + full[:12])
        if not os.path.exists(built):
            log = os.path.join(self.logs, "build.%s.log" % full[:12])
            say("building the worktree at %s (log: %s)" % (full[:12], log))
            cmd = ("source scripts/env.sh && catkin_make -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 "
                   "-DPython3_EXECUTABLE=/usr/bin/python3 -DCATKIN_ENABLE_TESTING=OFF -j%d" % os.cpu_count())
            with open(log, "w") as f:
                if subprocess.run(["bash", "-c", cmd], cwd=tree, stdout=f, stderr=subprocess.STDOUT).returncode:
                    raise SweepError("the worktree's build failed: %s" % log)
            open(built, "w").write(full + "\n")
        return tree

    # ---- one run --------------------------------------------------------------------------------

    def job(self, run, slot):
        """Trains (or resumes) one run, exports, records and evaluates it into the records' checkout,
        then analyses it and ships its variant's median run. Returns the exit status."""
        phase = run.phase
        port = self.config.port + 10 * slot
        for p in (port, port + 1, port + 2):
            if not proc.port_free(p):
                say("%s: port %d is in use; not started" % (run.name, p))
                return 3
        tree = self.tree(phase)
        if self.git("status", "--porcelain", cwd=tree).stdout.strip():
            say("%s: the worktree is not clean; not started" % run.name)
            return 3
        log = os.path.join(self.logs, run.name + ".log")
        say("%s: training (phase %s, slot %d, port %d, %d learner threads; log %s)" % (
            run.name, phase.name, slot, port, phase.hider_threads, log))
        paused = os.path.join(self.runs_dir, run.name, "paused_s")
        script = os.path.join(tree, "scripts", "train_variant.sh")
        if os.path.isfile(script):
            # A pin from before this command: its own shell trainer.
            env = dict(os.environ, RECORD_ROOT=self.records.root, PRECISION=phase.precision, GAME=phase.game,
                       HIDER_THREADS=str(phase.hider_threads), ROS_PORT=str(port), HIDESEEK_PORT=str(port + 1),
                       EVAL_MODES="greedy sampled", PAUSED_FILE=paused)
            cmd = [script, run.variant, str(run.seed), str(phase.steps), self.runs_dir, phase.network, run.name]
        else:
            # hideseek_pipeline train with the pinned tree as its workspace (its launch files and tools).
            env = dict(os.environ, PYTHONPATH=_package_path() + os.pathsep + os.environ.get("PYTHONPATH", ""))
            cmd = [sys.executable, "-m", "hideseek_pipeline", "train", run.variant, "--seed", str(run.seed),
                   "--steps", str(phase.steps), "--runs-dir", self.runs_dir, "--network", phase.network,
                   "--name", run.name, "--game", phase.game, "--precision", phase.precision, "--hider-threads",
                   str(phase.hider_threads), "--port", str(port), "--eval-port", str(port + 1), "--eval-modes",
                   "greedy", "sampled", "--paused-file", paused, "--workspace", tree, "--record-root",
                   self.records.root]
        with open(log, "w") as f:
            rc = subprocess.run(cmd, env=env, stdout=f, stderr=subprocess.STDOUT).returncode
        if rc != 0:
            say("%s: failed (exit %d); see %s" % (run.name, rc, log))
            return rc
        fields = {"note": "%s, phase %s, pinned at %s" % (SWEEP_NOTE, phase.name, phase.commit[:12])}
        if run.retrain:
            fields.update(draw="retrain", retrain_of=run.name[:-len(RETRAIN_SUFFIX)])
        self.records.registry.record(run.name, fields, self.records.registry_path)
        self.analyze(run.name)
        self.ship(run.variant, phase)
        say("%s: done: greedy %s, sampled %s (living steps/success)" % (
            run.name, self.records.evaluation(run.name), self.records.evaluation(run.name, "sampled")))
        return 0

    def analyze(self, name, part=None):
        """The per-run analysis (hideseek_pipeline analyze, with the records' checkout as its
        workspace: the analysis is not pinned, since it trains nothing), or one `part` of it (tsne or
        memoryless). Its failure does not undo the run: `sweep analyze` retries."""
        if not self.has_weights(name):
            say("%s: no weights in %s: not analysed" % (name, os.path.dirname(self.weights(name))))
            return False
        cmd = [sys.executable, "-m", "hideseek_pipeline", "analyze", name, self.weights(name), "--part", part or "all",
               "--record-root", self.records.root, "--workspace", self.records.root]
        log = os.path.join(self.logs, name + ".analysis.log")
        env = dict(os.environ, PYTHONPATH=_package_path() + os.pathsep + os.environ.get("PYTHONPATH", ""))
        with open(log, "a") as f:
            ok = subprocess.run(cmd, env=env, stdout=f, stderr=subprocess.STDOUT).returncode == 0
        what = part or "analysed"
        if ok:
            say("%s: %s into %s" % (name, what if part else "analysed", self.records.docs(name, "analysis")))
        else:
            say("%s: the %s failed; see %s" % (name, "%s part" % part if part else "analysis", log))
        return ok

    def ship(self, variant, phase):
        """Ships the variant's median sweep run of the phase's game, network and budget, from its
        weights here; where they are not, the shipped run stays and the message names the run to
        retrain. A phase with `ship: false` (a longer budget's check) ships nothing."""
        if not phase.ship:
            return
        reg = self.records.registry
        try:
            say(reg.ship_median(variant, self.runs_dir, phase.network, phase.game, self.records.registry_path,
                                self.records.root, SWEEP_NOTE, phase.steps))
        except (reg.WeightsMissing, reg.RegistryError) as e:
            say(str(e))

    # ---- commands -------------------------------------------------------------------------------

    def run(self):
        """The queue in the foreground: starts runs in order while slots are free, each in a process
        of its own (forked: a running queue keeps the code it started with)."""
        self.make_dirs()
        lock = proc.FileLock(self.state_file("queue.lock"), wait=False)
        try:
            lock.__enter__()
        except BlockingIOError:
            raise SweepError("a queue is already running (pid %s)" % proc.read_pid(self.state_file("queue.pid")))
        try:
            self._run_locked()
        finally:
            _remove(self.state_file("queue.pid"))
            lock.__exit__(None, None, None)

    def _run_locked(self):
        open(self.state_file("queue.pid"), "w").write("%d\n" % os.getpid())
        for f in os.listdir(self.state):
            if f.startswith("job.") or f == "stop":
                _remove(self.state_file(f))
        if os.path.exists(self.state_file("paused")):
            say("a pause from an earlier queue is cleared (its runs were stopped)")
            _remove(self.state_file("paused"))
        if not proc.native_bf16() and any(p.precision == "bf16" for p in self.config.phases):
            raise SweepError(NO_BF16)
        for phase in self.config.phases:
            self.prepare_tree(phase)
        say("queue: %d runs in %d phases (%s) from %s" % (
            len(self.config.runs()), len(self.config.phases), ", ".join(p.name for p in self.config.phases), self.dir))
        running, failed = {}, set()  # name -> (process, slot, phase jobs)
        ctx = multiprocessing.get_context("fork")

        def stop_runs(*_):
            say("stopping")
            for process, _, _ in running.values():
                proc.signal_tree(process.pid, signal.SIGINT)
            for process, _, _ in running.values():
                process.join()
            sys.exit(143)

        signal.signal(signal.SIGINT, stop_runs)
        signal.signal(signal.SIGTERM, stop_runs)
        while not os.path.exists(self.state_file("stop")):
            started = False
            if not os.path.exists(self.state_file("paused")):
                with proc.FileLock(self.state_file("launch.lock")):
                    started = not os.path.exists(self.state_file("paused")) and self._start_next(running, failed, ctx)
            if started:
                continue
            if not running and not os.path.exists(self.state_file("paused")):
                left = [r.name for r in self.to_train()]
                say("every run of the queue is done" if not left else
                    "nothing left to start: %d runs failed (see the logs); start again to retry them" % len(left))
                return
            time.sleep(5)
            for name, (process, _, _) in list(running.items()):
                if not process.is_alive():
                    process.join()
                    if process.exitcode != 0:
                        failed.add(name)
                    _remove(self.state_file("job." + name))
                    del running[name]

    def _start_next(self, running, failed, ctx):
        """Starts the first run left in order, if its phase's number of runs at once allows it."""
        for run in self.to_train():
            if run.name in running or run.name in failed:
                continue
            if len(running) >= run.phase.jobs or any(jobs < len(running) + 1 for _, _, jobs in running.values()):
                return False
            used = {slot for _, slot, _ in running.values()}
            slot = min(s for s in range(len(running) + 1) if s not in used)
            process = ctx.Process(target=self._job_process, args=(run, slot), name=run.name)
            process.start()
            open(self.state_file("job." + run.name), "w").write("%d\n" % process.pid)
            running[run.name] = (process, slot, run.phase.jobs)
            return True
        return False

    def _job_process(self, run, slot):
        # A handler, not SIG_IGN (which the training would inherit): the stop's SIGINT reaches the
        # whole tree, and this process waits for the training to end rather than leave it.
        signal.signal(signal.SIGINT, lambda *_: None)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        sys.exit(self.job(run, slot))

    def start(self):
        if self.queue_pid():
            print("sweep: the queue is already running (pid %s); hideseek_pipeline sweep status" % self.queue_pid())
            return 0
        if not proc.native_bf16() and any(p.precision == "bf16" for p in self.config.phases):
            raise SweepError(NO_BF16)
        self.make_dirs()
        log = os.path.join(self.logs, "queue.log")
        with open(log, "a") as f:
            subprocess.Popen([sys.executable, "-m", "hideseek_pipeline", "sweep", "--config", self.config.path, "run"],
                             stdout=f,
                             stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, start_new_session=True,
                             env=dict(os.environ, PYTHONPATH=_package_path() + os.pathsep +
                                      os.environ.get("PYTHONPATH", "")))
        print("sweep: queue started (log: %s; hideseek_pipeline sweep status)" % log)
        return 0

    def status(self):
        out = []
        queue = ("running (pid %s)" % self.queue_pid()) if self.queue_pid() else "not running"
        if os.path.exists(self.state_file("paused")):
            since = float(open(self.state_file("paused")).read().split()[0])
            queue += ", PAUSED since %s" % time.strftime("%H:%M:%S", time.localtime(since))
        out.append("sweep: %d phases (%s), runs %s; queue %s" % (
            len(self.config.phases), ", ".join("%s at %s" % (p.name, p.commit[:12]) for p in self.config.phases),
            self.runs_dir, queue))
        if not proc.native_bf16():
            out.append("sweep: this CPU has no native bf16: the queue will not train bf16 phases here")
        jobs = self.job_pids()
        for run in self.all_runs():
            out.append(self._status_line(run, run.name in jobs))
        queued = [r.name[:-len(RETRAIN_SUFFIX)] for r in self.retrain_runs() if self.wants_retrain(r)]
        if queued:
            out.append("sweep: queued for retraining (weights lost; after every other run): " + " ".join(queued))
        out.append("sweep: left to train, in order: " + (" ".join(r.name for r in self.to_train()) or "nothing"))
        print("\n".join(out))
        return 0

    def _status_line(self, run, training):
        name, rec = run.name, self.records
        if training:
            last = _last_line(os.path.join(self.runs_dir, name, "training_log.csv")).split(",")
            return "%-34s training  %s steps of %d, %s s%s" % (name, last[1] if len(last) > 2 else "?", run.phase.steps,
                                                               last[2] if len(last) > 2 else "?",
                                                               " (retraining)" if run.retrain else "")
        if rec.is_done(run):
            return "%-34s done      greedy %s, sampled %s (living steps, success); %s; %s" % (
                name, rec.evaluation(name), rec.evaluation(name, "sampled"),
                "analysed" if rec.analysed(name) else "NOT analysed",
                "weights in %s" % os.path.dirname(self.weights(name)) if self.has_weights(name)
                else "weights not on this machine")
        if os.path.isfile(os.path.join(self.runs_dir, name, "checkpoint.pt")):
            return "%-34s partial   checkpoint in %s (resumes at the next start)" % (
                name, os.path.join(self.runs_dir, name))
        return "%-34s missing" % name

    def retrain(self, names):
        if not names:
            raise SweepError("retrain: name the runs to train again (sweep ship names the ones a variant needs)")
        by_name = {r.name: r for r in self.config.runs()}
        self.make_dirs()
        for name in names:
            if name not in by_name:
                raise SweepError("retrain: '%s' is not a run of the queue (sweep status lists them)" % name)
            if not self.records.is_done(by_name[name]):
                raise SweepError("retrain: '%s' is not done: the queue trains it anyway" % name)
            if self.has_weights(name):
                print("sweep: %s: its weights are here (%s); nothing to retrain" % (name, self.weights(name)))
                continue
            if name not in self.retrain_list():
                with open(self.state_file("retrain"), "a") as f:
                    f.write(name + "\n")
            print("sweep: %s queued for retraining, after every other run of the queue, as %s%s beside its "
                  "first draw" % (name, name, RETRAIN_SUFFIX))
        if self.queue_pid():
            print("sweep: the running queue takes it up when a slot frees")
        return 0

    def pause(self):
        """SIGSTOP every training run's process tree; the queue starts no new run until resume."""
        if os.path.exists(self.state_file("paused")):
            print("sweep: already paused")
            return 0
        self.make_dirs()
        with proc.FileLock(self.state_file("launch.lock")):
            open(self.state_file("paused"), "w").write("%d\n" % time.time())
            held = self.job_pids()
            for pid in held.values():
                proc.stop_tree(pid)
            with open(self.state_file("paused.runs"), "w") as f:
                f.writelines("%s %d\n" % item for item in held.items())
        print("sweep: paused (%d runs held; the queue starts no new run until 'hideseek_pipeline sweep resume')"
              % len(held))
        return 0

    def resume(self, book=True):
        """SIGCONT the runs the pause held; with `book`, adds the held time to each one's paused_s
        (not when they are being stopped: they restart from a checkpoint older than the pause)."""
        if not os.path.exists(self.state_file("paused")):
            print("sweep: not paused")
            return 0
        held = int(time.time() - float(open(self.state_file("paused")).read().split()[0]))
        for line in _lines(self.state_file("paused.runs")):
            name, pid = line.split()
            if not proc.alive(int(pid)):
                continue
            proc.continue_tree(int(pid))
            if book:
                path = os.path.join(self.runs_dir, name, "paused_s")
                os.makedirs(os.path.dirname(path), exist_ok=True)
                before = int(float(_last_line(path) or 0))
                open(path, "w").write("%d\n" % (before + held))
        _remove(self.state_file("paused"))
        _remove(self.state_file("paused.runs"))
        print("sweep: resumed after %d s" % held)
        return 0

    def stop(self):
        queue = self.queue_pid()
        self.make_dirs()
        open(self.state_file("stop"), "w").close()
        if os.path.exists(self.state_file("paused")):
            with open(os.devnull, "w") as null:
                stdout, sys.stdout = sys.stdout, null
                try:
                    self.resume(book=False)
                finally:
                    sys.stdout = stdout
        for pid in self.job_pids().values():
            proc.signal_tree(pid, signal.SIGINT)
        if isinstance(queue, int):
            proc.signal_tree(queue, signal.SIGTERM)
        for _ in range(60):
            if not self.queue_pid() and not self.job_pids():
                break
            time.sleep(1)
        for pid in self.job_pids().values():
            proc.signal_tree(pid, signal.SIGKILL)
        print("sweep: stopped; 'hideseek_pipeline sweep start' resumes each run from its last checkpoint")
        return 0

    def hold(self, command):
        """Pauses a running queue, runs `command`, resumes the queue whatever its exit; with no queue
        running, just the command. make bench and make test run under it."""
        if not command:
            raise SweepError("hold: name the command to run while the sweep is paused")
        if not self.queue_pid() or os.path.exists(self.state_file("paused")):
            return subprocess.run(command).returncode
        self.pause()
        try:
            return subprocess.run(command).returncode
        except KeyboardInterrupt:
            return 130
        finally:
            self.resume()

    def analyze_all(self):
        """The per-run analysis of every done run that lacks it and whose weights are here (the
        t-SNE, or a GRU's memoryless ablation, alone where only that is missing)."""
        self.make_dirs()
        n = 0
        for run in self.all_runs():
            if not self.records.is_done(run):
                continue
            if not self.records.analysed(run.name):
                n += self.analyze(run.name)
                continue
            if not self.has_weights(run.name):
                continue
            if not self.records.has_tsne(run.name):
                n += self.analyze(run.name, "tsne")
            if run.phase.network == "gru" and not self.records.has_memoryless(run.name):
                n += self.analyze(run.name, "memoryless")
        say("%d runs or parts of runs analysed" % n)
        return 0

    def ship_all(self):
        for phase in self.config.phases:
            for variant in phase.variants:
                self.ship(variant, phase)
        return 0


NO_BF16 = ("this CPU has no native bf16 (avx512_bf16 or amx_bf16): sweep runs train only in bf16 on such a CPU; "
           "evaluate and analyse here instead")


def _package_path():
    return os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _remove(path):
    try:
        os.remove(path)
    except FileNotFoundError:
        pass


def _lines(path):
    try:
        with open(path) as f:
            return [line for line in f.read().splitlines() if line.strip()]
    except OSError:
        return []


def _last_line(path):
    lines = _lines(path)
    return lines[-1] if lines else ""
