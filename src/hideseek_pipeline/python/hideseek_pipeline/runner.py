"""The sweep's runner: trains every missing run of config/sweep.yaml's phases from a git worktree
built at the phase's commit, evaluates each run the moment it finishes (seeds 0-99, greedy and
sampled), records it into the checkout (docs/runs/<run>/ and policies/policies.yaml), analyses it
and ships each variant's median run. Runs resume from their checkpoints.
"""
import csv
import multiprocessing
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

from hideseek_pipeline import analyze as analysis
from hideseek_pipeline import evaluate
from hideseek_pipeline import processes as proc
from hideseek_pipeline.control import drop_pauses_after_checkpoint, logged_rows
from hideseek_pipeline.queue import NO_BF16, RETRAIN_SUFFIX, SweepError, last_line, package_path, remove_file, say
from hideseek_pipeline.sweep_config import start_window
from hideseek_pipeline.workspace import ToolError, Workspace


def prepare_tree(sweep, phase):
    """The worktree at the phase's commit, built (catkin_make, Release, no tests) once."""
    if sweep.git("rev-parse", "--verify", "-q", phase.commit + "^{commit}").returncode != 0:
        raise SweepError("phase %s: commit %s is not in this repository (fetch it first)" % (phase.name, phase.commit))
    full = sweep.commit(phase)
    tree = sweep.tree(phase)
    sweep.git("worktree", "prune")
    if not os.path.exists(os.path.join(tree, ".git")):
        say("creating the worktree %s at %s" % (tree, full))
        os.makedirs(os.path.dirname(tree), exist_ok=True)
        r = sweep.git("worktree", "add", "--detach", tree, full)
        if r.returncode != 0:
            raise SweepError("git worktree add %s failed: %s" % (tree, r.stderr.strip()))
    else:
        if _link_lost(tree):
            relink_tree(sweep, tree, full)
        if sweep.git("rev-parse", "HEAD", cwd=tree).stdout.strip() != full:
            raise SweepError("the worktree %s is not at %s" % (tree, full))
        _read_index(sweep, tree)
    if sweep.git("status", "--porcelain", cwd=tree).stdout.strip():
        raise SweepError("the worktree %s has uncommitted changes; a sweep run trains from a clean tree "
                         "(git -C %s status)" % (tree, tree))
    built = sweep.state_file("built." + full[:12])
    if not os.path.exists(built):
        log = os.path.join(sweep.logs, "build.%s.log" % full[:12])
        say("building the worktree at %s (log: %s)" % (full[:12], log))
        cmd = ("source scripts/env.sh && catkin_make -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 "
               "-DPython3_EXECUTABLE=/usr/bin/python3 -DCATKIN_ENABLE_TESTING=OFF -j%d" % os.cpu_count())
        with open(log, "w") as f:
            if subprocess.run(["bash", "-c", cmd], cwd=tree, stdout=f, stderr=subprocess.STDOUT).returncode:
                raise SweepError("the worktree's build failed: %s" % log)
        open(built, "w").write(full + "\n")
    return tree

def _link_lost(tree):
    """Whether the worktree's `.git` file names a folder of the checkout's `.git/worktrees/` that is
    gone (the checkout was cloned or restored anew while the sweep's folder stayed)."""
    try:
        line = open(os.path.join(tree, ".git")).read().strip()
    except (OSError, UnicodeDecodeError):  # a folder (a checkout of its own), or unreadable: git says
        return False
    return line.startswith("gitdir: ") and not os.path.isdir(os.path.join(tree, line[len("gitdir: "):]))


def _read_index(sweep, tree):
    """A linked tree without its index (a relink stopped before reading it) reads it from its HEAD,
    so that its files are compared with the pin's rather than all shown as deleted."""
    index = sweep.git("rev-parse", "--git-path", "index", cwd=tree).stdout.strip()
    if index and not os.path.exists(os.path.join(tree, index)):
        r = sweep.git("-C", tree, "reset", "-q")
        if r.returncode != 0:
            raise SweepError("git -C %s reset failed: %s" % (tree, r.stderr.strip()))


def relink_tree(sweep, tree, full):
    """Registers again, at `full`, a worktree whose link to the checkout is lost, keeping its files
    and its build: git makes a new link (without checking anything out), the tree takes it, and its
    index is read from `full`. A tree whose files are not `full`'s then shows them as changes, which
    the caller refuses."""
    say("the worktree %s lost its link to the checkout (%s); linking it again at %s, its build kept"
        % (tree, open(os.path.join(tree, ".git")).read().strip(), full[:12]))
    scratch = tree + ".link"
    if os.path.lexists(scratch):  # left by a relink that stopped before the tree took its link
        if os.path.isdir(scratch) and not os.path.islink(scratch):
            shutil.rmtree(scratch)
        else:
            os.remove(scratch)
        sweep.git("worktree", "prune")
    r = sweep.git("worktree", "add", "--no-checkout", "--detach", scratch, full)
    if r.returncode != 0:
        raise SweepError("git worktree add %s failed: %s" % (scratch, r.stderr.strip()))
    os.replace(os.path.join(scratch, ".git"), os.path.join(tree, ".git"))
    os.rmdir(scratch)
    r = sweep.git("worktree", "repair", tree)
    if r.returncode != 0:
        raise SweepError("git worktree repair %s failed: %s" % (tree, r.stderr.strip()))
    # the index is read by the caller (_read_index), as after a relink that stopped here


# ---- one run --------------------------------------------------------------------------------


def job(sweep, run, slot):
    """Trains (or resumes) one run, exports, records and evaluates it into the records' checkout,
    then analyses it and ships its variant's median run. Returns the exit status."""
    phase = run.phase
    port = sweep.config.port + 10 * slot
    for p in (port, port + 1, port + 2):
        if not proc.port_free(p):
            say("%s: port %d is in use; not started" % (run.name, p))
            return 3
    tree = sweep.tree(phase)
    if sweep.git("status", "--porcelain", cwd=tree).stdout.strip():
        say("%s: the worktree is not clean; not started" % run.name)
        return 3
    log = os.path.join(sweep.logs, run.name + ".log")
    checkpoint = os.path.join(sweep.runs_dir, run.name, "checkpoint.pt")
    start = ("training" if phase.role == "selfplay"  # (it resumes from its saved generations)
             else "resuming from its checkpoint" if os.path.isfile(checkpoint) else "training from step 0")
    say("%s: %s (phase %s, slot %d, port %d, %d learner thread%s; log %s)" % (
        run.name, start, phase.name, slot, port, phase.hider_threads, "" if phase.hider_threads == 1 else "s", log))
    paused = os.path.join(sweep.runs_dir, run.name, "paused_s")
    script = os.path.join(tree, "scripts", "train_variant.sh")
    if os.path.isfile(script) and phase.role != "hider":
        say("%s: phase %s (role %s) needs hideseek_pipeline at its pin; %s has only the shell trainer: pin a "
            "later commit" % (run.name, phase.name, phase.role, sweep.commit(phase)[:12]))
        return 3
    if phase.role == "selfplay":  # (a shell trainer's pin was refused just above)
        return _selfplay_job(sweep, run, port, tree, log)
    # (Self-play resumes from its saved generations, not from one checkpoint: its pauses stay booked.)
    lost = drop_pauses_after_checkpoint(os.path.dirname(paused))
    if lost and os.path.isfile(os.path.join(os.path.dirname(paused), "checkpoint.pt")):
        say("%s: %d s of pauses after its last checkpoint left out of its paused_s (the training after the "
            "checkpoint was lost, and the run resumes from it)" % (run.name, lost))
    elif lost:
        say("%s: %d s of pauses left out of its paused_s: it has no checkpoint, and starts afresh" % (run.name, lost))
    if os.path.isfile(script):
        # A pin from before this command: its own shell trainer.
        env = dict(os.environ, RECORD_ROOT=sweep.records.root, PRECISION=phase.precision,
                   HIDER_THREADS=str(phase.hider_threads), ROS_PORT=str(port), HIDESEEK_PORT=str(port + 1),
                   EVAL_MODES="greedy sampled", PAUSED_FILE=paused)
        if phase.game != "v2":  # v2 is those trainers' default: the recorded command stays as the sweep's was
            env["GAME"] = phase.game
        cmd = [script, run.variant, str(run.seed), str(phase.steps), sweep.runs_dir, phase.network, run.name]
    else:
        env = _pinned_env(tree)
        cmd = [sys.executable, "-m", "hideseek_pipeline", "train", run.variant, "--seed", str(run.seed),
               "--steps", str(phase.steps), "--runs-dir", sweep.runs_dir, "--network", phase.network,
               "--name", run.name, "--game", phase.game, "--precision", phase.precision, "--hider-threads",
               str(phase.hider_threads), "--port", str(port), "--eval-port", str(port + 1), "--eval-modes",
               "greedy", "sampled", "--paused-file", paused, "--workspace", tree, "--record-root",
               sweep.records.root]
        if phase.role != "hider":
            cmd += ["--role", phase.role]
        if phase.opponent:
            cmd += ["--opponent", phase.opponent]
    rc = _logged(cmd, env, log, "w")
    if rc != 0:
        say(ended_early(run.name, rc, log, os.path.isfile(checkpoint)))
        return rc
    # paused_s again, the training's part of the held time (none when 0): a trainer of an older pin
    # kept an earlier training's paused time in an entry of the same name when it read none.
    held = last_line(paused).split(".")[0]
    held = int(held) if held.isdigit() else 0
    in_training = held_in_training(sweep, run.name, held)
    if held > in_training:
        say("%s: held %d s more while it was evaluated after training: left out of its wall_s and of its "
            "paused_s (%d s, held in training)" % (run.name, held - in_training, in_training))
    fields = {"note": "%s, phase %s, pinned at %s" % (sweep.records.note, phase.name, sweep.commit(phase)[:12]),
              "paused_s": in_training or None}
    if run.retrain:
        fields.update(draw="retrain", retrain_of=run.name[:-len(RETRAIN_SUFFIX)])
    sweep.records.registry.record(run.name, fields, sweep.records.registry_path)
    if sweep.records.clear_partial(run.name):
        say("%s: its partial records %s removed" % (run.name, sweep.records.partial(run.name)))
    if phase.role != "hider":
        say("%s: done: %s" % (run.name, sweep.records.seeker_evaluation(run.name)))
        return 0  # a seeker's run: no hider analysis, nothing shipped
    analyze(sweep, run.name)
    baseline(sweep, run.variant, phase.game)
    ship(sweep, run.variant, phase, port + 1)
    say("%s: done: greedy %s, sampled %s (living steps/success)" % (
        run.name, sweep.records.evaluation(run.name), sweep.records.evaluation(run.name, "sampled")))
    return 0


def held_in_training(sweep, name, held):
    """The part of `held` (the seconds the sweep held a run, in training and in its evaluation after)
    that fell in its training: its training log's last wall time less the wall_s its trainer
    recorded, which left out the held time it read as training ended. `held` where either is missing."""
    entry = sweep.records.registry.runs(sweep.records.registry_path).get(name) or {}
    rows = logged_rows(sweep.records.docs(name, "training_log.csv"), 1)
    try:  # the shell trainer of an older pin records wall_s as text
        return min(max(int(rows[-1][1]) - int(float(entry["wall_s"])), 0), held)
    except (IndexError, KeyError, TypeError, ValueError):
        return held


def _pinned_env(tree):
    """hideseek_pipeline with the pinned tree as its workspace (its launch files and tools), and the
    tree's own copy of the command where it has one: edits to the checkout never change what trains
    and records."""
    pinned = os.path.join(tree, "src", "hideseek_pipeline", "python")
    code = pinned if os.path.isdir(pinned) else package_path()
    env = dict(os.environ, PYTHONPATH=code + os.pathsep + os.environ.get("PYTHONPATH", ""),
               HIDESEEK_ROOT=tree if os.path.isdir(pinned) else os.environ.get("HIDESEEK_ROOT", ""))
    if not env["HIDESEEK_ROOT"]:
        del env["HIDESEEK_ROOT"]
    return env


def _own_env():
    """hideseek_pipeline as this checkout has it (the analysis and records, which train nothing)."""
    return dict(os.environ, PYTHONPATH=package_path() + os.pathsep + os.environ.get("PYTHONPATH", ""))


def ended_early(name, rc, log, has_checkpoint=True):
    """What the queue says of a run whose trainer exited with `rc` (a signal's as negative): a
    stop (sweep stop, Ctrl-C, the end of a session) is no failure; the run resumes from its
    checkpoint, or, stopped before its first, starts again. A trainer that dies of the signal gives
    -2 or -15 (a pin's from before 2026-11-30); one that catches it and stops cleanly, 130
    (hideseek_pipeline train's Interrupted) or 143."""
    stopped = {-signal.SIGINT: "SIGINT", -signal.SIGTERM: "SIGTERM", 130: "SIGINT", 143: "SIGTERM"}
    if rc in stopped:
        then = ("it resumes from its last checkpoint" if has_checkpoint else
                "it had written no checkpoint yet, so it starts again from step 0")
        return "%s: stopped (%s); %s at the queue's next start (log: %s)" % (name, stopped[rc], then, log)
    return "%s: failed (exit %d); see %s" % (name, rc, log)


def _logged(cmd, env, log, mode="a"):
    """Runs `cmd` into `log`; its exit status (a signal's as negative)."""
    with open(log, mode) as f:
        return subprocess.run(cmd, env=env, stdout=f, stderr=subprocess.STDOUT).returncode


def _selfplay_job(sweep, run, port, tree, log):
    """A self-play phase's run: its generations trained at the pin (resuming what <runs>/<run>
    holds), then its cross-play and records with this checkout's code and the records' checkout as
    the workspace, as a run's analysis is (they train nothing)."""
    phase, out = run.phase, os.path.join(sweep.runs_dir, run.name)
    common = ["selfplay", out, "--variant", run.variant, "--game", phase.game, "--generations", str(phase.generations),
              "--steps", str(phase.steps // phase.generations), "--seed", str(run.seed), "--precision",
              phase.precision, "--hider-threads", str(phase.hider_threads), "--port", str(port), "--record-root",
              sweep.records.root]
    if phase.latest_share is not None:  # unset: the pin's default (a pin from before the share: uniform)
        common += ["--latest-share", repr(phase.latest_share)]
    train = [sys.executable, "-m", "hideseek_pipeline"] + common + ["--workspace", tree]
    if _logged(train, _pinned_env(tree), log, "w"):
        say("%s: its self-play stopped; see %s (it resumes from its saved generations)" % (run.name, log))
        return 1
    record = [sys.executable, "-m", "hideseek_pipeline"] + common + ["--workspace", sweep.records.root, "--record",
                                                                     run.name]
    env = _own_env()
    if _logged(record, env, log):
        say("%s: its cross-play or records failed; see %s (the next start plays the pairs left)" % (run.name, log))
        return 1
    if sweep.records.clear_partial(run.name):
        say("%s: its partial records %s removed" % (run.name, sweep.records.partial(run.name)))
    say("%s: done: %s" % (run.name, sweep.records.docs(run.name, "selfplay.md")))
    return 0


def analyze(sweep, name, part=None):
    """The per-run analysis (hideseek_pipeline analyze, with the records' checkout as its
    workspace: the analysis is not pinned, since it trains nothing), or one `part` of it (tsne or
    memoryless). Its failure does not undo the run: `sweep analyze` retries."""
    if not sweep.has_weights(name):
        say("%s: no weights in %s: not analysed" % (name, os.path.dirname(sweep.weights(name))))
        return False
    cmd = [sys.executable, "-m", "hideseek_pipeline", "analyze", name, sweep.weights(name), "--part", part or "all",
           "--record-root", sweep.records.root, "--workspace", sweep.records.root]
    log = os.path.join(sweep.logs, name + ".analysis.log")
    env = _own_env()
    with open(log, "a") as f:
        ok = subprocess.run(cmd, env=env, stdout=f, stderr=subprocess.STDOUT).returncode == 0
    what = part or "analysed"
    if ok:
        say("%s: %s into %s" % (name, what if part else "analysed", sweep.records.docs(name, "analysis")))
    else:
        say("%s: the %s failed (%s); see %s; hideseek_pipeline sweep analyze retries it" % (
            name, "%s part" % part if part else "analysis", last_line(log), log))
    return ok


def baseline(sweep, variant, game):
    """The random hider's behaviour on the variant and game, which the claims set every run of
    them beside (hideseek_pipeline analyze --baseline, into the records' docs/analysis/baselines/),
    once: nothing where the records hold it. Its failure does not undo the run."""
    if os.path.isfile(os.path.join(analysis.baseline_folder(sweep.records.root, variant, "random", game),
                                   "behaviour.csv")):
        return True
    cmd = [sys.executable, "-m", "hideseek_pipeline", "analyze", "--baseline", variant, "random", "--game", game,
           "--record-root", sweep.records.root, "--workspace", sweep.records.root]
    log = os.path.join(sweep.logs, "baseline.%s.%s.log" % (game, variant))
    env = _own_env()
    ok = _logged(cmd, env, log) == 0
    say("%s on %s: the random hider's behaviour %s" % (variant, game, "analysed" if ok else "failed; see " + log))
    return ok


def ship(sweep, variant, phase, port=None):
    """Ships the variant's median sweep run of the phase's game, network and budget, from its
    weights here, or else from git history where they replay its recorded evaluation (recover);
    where neither holds them, the shipped run stays and the message names the run to retrain. A
    phase with `ship: false` (a longer budget's check) ships nothing. `port`: the ROS master port of
    a recovery's evaluation (default: the sweep's port + 90, beside every slot's)."""
    if not phase.ship:
        return
    reg = sweep.records.registry

    def ship_median():
        return reg.ship_median(variant, sweep.runs_dir, phase.network, phase.game, sweep.records.registry_path,
                               sweep.records.root, sweep.records.note, phase.steps)
    try:
        say(ship_median())
    except reg.WeightsMissing as e:
        port = port or sweep.config.port + 90
        if any(recover(sweep, name, phase, port) for name in e.runs):
            say(ship_median())
        else:
            say(str(e))
    except reg.RegistryError as e:
        say(str(e))


def recover(sweep, name, phase, port):
    """A run's weights from git history, where they left this machine but the run once shipped:
    the weights the newest commit shipping it holds, checked by evaluating them again (greedy,
    seeds 0-99, the phase's pinned tree, into a scratch folder) against the run's recorded
    episodes.csv. Only weights that give every episode's recorded living steps go where the queue
    keeps weights (<runs>/<run>/policy.pt, beside recovered_from, the commit); others stay in
    <runs>/<run>/policy.recovered.pt, and the message says how many episodes they replayed.
    Returns whether the run's weights are now here."""
    reg = sweep.records.registry
    found = reg.weights_in_history(name, sweep.records.registry_path)
    if not found:
        return False
    commit, data = found
    recorded = sweep.records.docs(name, "episodes.csv")
    if not os.path.isfile(recorded):
        say("%s: its weights are in git commit %s, but %s is missing to check them against; not recovered "
            "('hideseek_pipeline sweep retrain %s' trains it again)" % (name, commit[:12], recorded, name))
        return False
    folder = os.path.join(sweep.runs_dir, name)
    os.makedirs(folder, exist_ok=True)
    staged = os.path.join(folder, "policy.recovered.pt")
    with open(staged, "wb") as f:
        f.write(data)
    say("%s: its weights are not here but are in git commit %s; evaluating them again (port %d) to check that "
        "they replay its recorded episodes" % (name, commit[:12], port))
    with tempfile.TemporaryDirectory(prefix="hideseek_recover_") as scratch:
        try:
            evaluate.evaluate(Workspace(prepare_tree(sweep, phase)), sweep.records, name, staged, ("greedy",), port,
                              say, docs=scratch)
        except (ToolError, SweepError) as e:
            say("%s: the check of its recovered weights failed (%s); not recovered" % (name, e))
            return False
        same, total = _same_episodes(recorded, os.path.join(scratch, "episodes.csv"))
    if total == 0 or same != total:
        say("%s: the weights of git commit %s replay %d of its %d recorded episodes: not recovered (they stay in "
            "%s; retrain the run, or ship them by hand with hideseek_registry.py ship)" % (
                name, commit[:12], same, total, staged))
        return False
    os.replace(staged, sweep.weights(name))
    with open(os.path.join(folder, "recovered_from"), "w") as f:
        f.write(commit + "\n")
    say("%s: weights recovered from git commit %s; they replay all %d recorded episodes" % (name, commit[:12], total))
    return True


def _same_episodes(recorded, again):
    """(episodes whose living steps and outcome agree, episodes recorded): two episodes.csv files
    (seed,living_steps,outcome) compared seed by seed."""
    def rows(path):
        with open(path) as f:
            return {r["seed"]: (r["living_steps"], r["outcome"]) for r in csv.DictReader(f)}
    first, second = rows(recorded), rows(again) if os.path.isfile(again) else {}
    return sum(second.get(seed) == row for seed, row in first.items()), len(first)

# ---- commands -------------------------------------------------------------------------------


def run(sweep):
    """The queue in the foreground: starts runs in order while slots are free, each in a process
    of its own (forked: a running queue keeps the code it started with)."""
    # No trainer may leave __pycache__ in a pinned worktree (cli.main sets it too).
    os.environ["PYTHONDONTWRITEBYTECODE"] = "1"
    sweep.make_dirs()
    lock = proc.FileLock(sweep.state_file("queue.lock"), wait=False)
    try:
        lock.__enter__()
    except BlockingIOError:
        raise SweepError("a queue is already running (pid %s)" % proc.read_pid(sweep.state_file("queue.pid")))
    try:
        _run_locked(sweep)
    finally:
        remove_file(sweep.state_file("queue.pid"))
        lock.__exit__(None, None, None)


def _run_locked(sweep):
    since = time.time()  # a phase's start_within_min counts from here
    open(sweep.state_file("queue.pid"), "w").write("%d\n" % os.getpid())
    for f in os.listdir(sweep.state):
        if f.startswith("job.") or f == "stop":
            remove_file(sweep.state_file(f))
    if os.path.exists(sweep.state_file("paused")):
        say("a pause from an earlier queue is cleared (its runs were stopped)")
        remove_file(sweep.state_file("paused"))
    if not proc.native_bf16() and any(p.precision == "bf16" for p in sweep.config.phases):
        raise SweepError(NO_BF16)
    # The first phase with runs left is built now, so that a broken pin stops the queue at once; a
    # later phase's tree is built when its first run could start (_build_next), so that a session
    # that never reaches it spends no time on its build. A finished phase's tree is never built.
    prepared = {}  # commit -> whether its tree built
    first = next(iter(sweep.to_train()), None)
    if first:
        prepare_tree(sweep, first.phase)
        prepared[sweep.commit(first.phase)] = True
    say("queue: %d runs in %d phases (%s) from %s" % (
        len(sweep.config.runs()), len(sweep.config.phases), ", ".join(p.name for p in sweep.config.phases), sweep.dir))
    running, failed, waiting = {}, set(), set()  # running: name -> (process, slot, phase jobs)
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
    while not os.path.exists(sweep.state_file("stop")):
        started = False
        if not os.path.exists(sweep.state_file("paused")):
            skip = failed | _late(sweep, since, running, failed, waiting)
            if _build_next(sweep, running, skip, prepared, failed):
                continue  # a tree was built (or failed to build): look again
            with proc.FileLock(sweep.state_file("launch.lock")):
                started = not os.path.exists(sweep.state_file("paused")) and _start_next(sweep, running, skip, ctx)
        if started:
            continue
        if not running and not os.path.exists(sweep.state_file("paused")):
            left = list(sweep.to_train())
            late = [r for r in left if r.name in waiting and r.name not in failed]
            if not left:
                say("every run of the queue is done")
            if len(left) > len(late):
                say("nothing left to start: %d runs failed (see the logs); start again to retry them"
                    % (len(left) - len(late)))
            if late:
                say("nothing left to start now: %s %s for the queue's next start (%s)" % (
                    ", ".join(r.name for r in late), "waits" if len(late) == 1 else "wait", _window_text(late[0].phase)))
            return
        time.sleep(5)
        for name, (process, _, _) in list(running.items()):
            if not process.is_alive():
                process.join()
                if process.exitcode != 0:
                    failed.add(name)
                remove_file(sweep.state_file("job." + name))
                del running[name]


def _window_text(phase):
    return "phase %s %s: start the queue at a session's beginning" % (phase.name, start_window(phase))


def _late(sweep, since, running, failed, waiting):
    """The runs left (not under way, not failed) whose phase's start_within_min has passed since the
    queue's start; the queue starts the runs after them meanwhile. Each is said once, when the queue
    reaches it: when no run before it in the order is still waiting to start."""
    late, reached = set(), True
    for r in sweep.to_train():
        if r.name in running or r.name in failed:
            continue
        if not (r.phase.start_within_min and time.time() - since > 60.0 * r.phase.start_within_min):
            reached = False
            continue
        late.add(r.name)
        if reached and r.name not in waiting:
            say("%s: not started (%s); the queue goes on with the runs after it" % (r.name, _window_text(r.phase)))
            waiting.add(r.name)
    return late


def _next_run(sweep, running, skip):
    """The first run left in order, not under way and not in `skip`, if its phase's number of runs
    at once allows it to start now; else None."""
    # No free slot for any run while a running run's phase allows no more: the list is not even read.
    if running and len(running) >= min(jobs for _, _, jobs in running.values()):
        return None
    for run in sweep.to_train():
        if run.name in running or run.name in skip:
            continue
        if len(running) >= run.phase.jobs or any(jobs < len(running) + 1 for _, _, jobs in running.values()):
            return None
        return run
    return None


def _build_next(sweep, running, skip, prepared, failed):
    """Builds the worktree of the run that could start now if its commit is not built yet, outside
    the launch lock (a pause need not wait for a build; the build runs beside the runs under way).
    A commit that cannot be built fails its phases' runs, by name, and the queue goes on with the
    phases after them. Returns whether it built or failed anything."""
    run = _next_run(sweep, running, skip)
    if run is None or prepared.get(sweep.commit(run.phase)):
        return False
    commit = sweep.commit(run.phase)
    if commit not in prepared:
        try:
            prepare_tree(sweep, run.phase)
            prepared[commit] = True
            return True
        except SweepError as e:
            say("phase %s: %s" % (run.phase.name, e))
            prepared[commit] = False
    names = [r.name for r in sweep.to_train() if r.phase.name == run.phase.name]
    say("phase %s: its tree at %s did not build; its runs are not started (%s)" % (
        run.phase.name, commit[:12], ", ".join(names)))
    failed.update(names)
    return True


def _start_next(sweep, running, skip, ctx):
    """Starts the first run left in order, if its phase's number of runs at once allows it."""
    run = _next_run(sweep, running, skip)
    if run is not None:
        used = {slot for _, slot, _ in running.values()}
        slot = min(s for s in range(len(running) + 1) if s not in used)
        process = ctx.Process(target=_job_process, args=(sweep, run, slot), name=run.name)
        process.start()
        open(sweep.state_file("job." + run.name), "w").write("%d\n" % process.pid)
        running[run.name] = (process, slot, run.phase.jobs)
        return True
    return False


def _job_process(sweep, run, slot):
    # A handler, not SIG_IGN (which the training would inherit): the stop's SIGINT reaches the
    # whole tree, and this process waits for the training to end rather than leave it.
    signal.signal(signal.SIGINT, lambda *_: None)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    sys.exit(job(sweep, run, slot))


def start(sweep):
    if sweep.queue_pid():
        print("sweep: the queue is already running (pid %s); hideseek_pipeline sweep status" % sweep.queue_pid())
        return 0
    if not proc.native_bf16() and any(p.precision == "bf16" for p in sweep.config.phases):
        raise SweepError(NO_BF16)
    sweep.make_dirs()
    log = os.path.join(sweep.logs, "queue.log")
    with open(log, "a") as f:
        subprocess.Popen([sys.executable, "-m", "hideseek_pipeline", "sweep", "--config", sweep.config.path, "run"],
                         stdout=f,
                         stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, start_new_session=True,
                         env=dict(os.environ, PYTHONPATH=package_path() + os.pathsep +
                                  os.environ.get("PYTHONPATH", "")))
    print("sweep: queue started (log: %s; hideseek_pipeline sweep status)" % log)
    return 0


def analyze_all(sweep):
    """The per-run analysis of every done run that lacks it and whose weights are here (the
    t-SNE, or a GRU's memoryless ablation, alone where only that is missing), and the random
    hider's behaviour on each variant and game with a done run, where the records lack it."""
    sweep.make_dirs()
    n = 0
    for run in sweep.all_runs():
        if not sweep.records.is_done(run) or run.phase.role != "hider":
            continue
        baseline(sweep, run.variant, run.phase.game)
        if not sweep.records.analysed(run.name):
            n += analyze(sweep, run.name)
            continue
        if not sweep.has_weights(run.name):
            continue
        if not sweep.records.has_tsne(run.name):
            n += analyze(sweep, run.name, "tsne")
        if run.phase.network == "gru" and not sweep.records.has_memoryless(run.name):
            n += analyze(sweep, run.name, "memoryless")
    say("%d runs or parts of runs analysed" % n)
    return 0


def ship_all(sweep):
    for phase in sweep.config.phases:
        for variant in phase.variants:
            ship(sweep, variant, phase)
    return 0
