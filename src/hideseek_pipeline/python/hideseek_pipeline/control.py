"""Reporting on and steering the sweep's queue: status, hours, partial, retrain, pause, resume, stop,
hold."""
import os
import shutil
import signal
import subprocess
import sys
import time

import yaml

from hideseek_pipeline import processes as proc
from hideseek_pipeline import selfplay
from hideseek_pipeline.workspace import Workspace
from hideseek_pipeline.queue import (PAUSES_LOG, RETRAIN_SUFFIX, SweepError, last_line, read_lines, remove_file,
                                     write_atomically)
from hideseek_pipeline.sweep_config import start_window


def status(sweep):
    out = []
    queue = ("running (pid %s)" % sweep.queue_pid()) if sweep.queue_pid() else "not running"
    if os.path.exists(sweep.state_file("paused")):
        queue += ", PAUSED since %s" % time.strftime("%H:%M:%S", time.localtime(paused_since(sweep)))
    out.append("sweep: %d phases (%s), runs %s; queue %s" % (
        len(sweep.config.phases), ", ".join("%s at %s" % (p.name, sweep.commit(p)[:12]) + (
            " (%s)" % start_window(p) if p.start_within_min else "") for p in sweep.config.phases),
        sweep.runs_dir, queue))
    if not proc.native_bf16():
        out.append("sweep: this CPU has no native bf16: the queue will not train bf16 phases here")
    jobs = sweep.job_pids()
    for run in sweep.all_runs():
        out.append(_status_line(sweep, run, run.name in jobs))
    queued = [r.name[:-len(RETRAIN_SUFFIX)] for r in sweep.retrain_runs() if sweep.wants_retrain(r)]
    if queued:
        out.append("sweep: queued for retraining (weights lost; after every other run): " + " ".join(queued))
    out.append("sweep: left to train, in order: " + (" ".join(r.name for r in sweep.to_train()) or "nothing"))
    print("\n".join(out))
    return 0


def logged_rows(log, count=2):
    """The last `count` complete rows of a training log, as (steps, wall_s) pairs, oldest first: a
    row counts when it has the header's fields and numbers where they belong, so a line the trainer
    is still writing is passed over."""
    lines = read_lines(log)
    if not lines:
        return []
    width, rows = len(lines[0].split(",")), []
    for line in reversed(lines[1:]):
        fields = line.split(",")
        try:
            if len(fields) == width:
                rows.append((int(fields[1]), float(fields[2])))
        except ValueError:
            continue
        if len(rows) == count:
            break
    return rows[::-1]


def progress(log, steps, paused_s=0):
    """A training's progress, for a person watching it: steps trained of `steps`, its training time
    so far (less `paused_s`, the time the sweep held it paused) and the time left at its rate over
    the last two updates; or that it has logged nothing yet, or trained all its steps."""
    rows = logged_rows(log)
    if not rows:
        return "started, no update logged yet"
    done, wall_s = rows[-1]
    minutes = max(wall_s - paused_s, 0.0) / 60.0
    if done >= steps:
        return "all {:,} steps trained in {:.0f} min; being evaluated and recorded".format(done, minutes)
    text = "{:,} of {:,} steps ({:d} %), {:.0f} min of training".format(done, steps, 100 * done // max(steps, 1),
                                                                       minutes)
    if len(rows) == 2 and rows[1][0] > rows[0][0] and rows[1][1] > rows[0][1]:
        rate = (rows[1][0] - rows[0][0]) / (rows[1][1] - rows[0][1])
        text += ", about {:.0f} min left at {:.0f} steps/s".format((steps - done) / rate / 60.0, rate)
    return text


def _held_s(sweep, name):
    """The seconds the sweep held a run paused, as its paused_s on this machine books them (0: none)."""
    held = last_line(os.path.join(sweep.runs_dir, name, "paused_s")).split(".")[0]
    return int(held) if held.isdigit() else 0


def _record_log(ws, log, dest, prefix, so_far, wall_s):
    """A training log and its learning curve, unfinished, into `dest` as <prefix>training_log.csv
    and <prefix>learning_curve.png."""
    os.makedirs(dest, exist_ok=True)
    shutil.copyfile(log, os.path.join(dest, prefix + "training_log.csv"))
    ws.python("plot_learning_curve.py", log, os.path.join(dest, prefix + "learning_curve.png"),
              so_far.replace(":", ", unfinished:", 1))
    print("sweep: %s, %d s of training: log and curve in %s" % (so_far, int(wall_s), dest))


def _partial_selfplay(ws, sweep, run, dest):
    """An unfinished self-play's records: its generations.yaml and each side's training log and curve
    so far (no weights); whether there was anything to record."""
    out = os.path.join(sweep.runs_dir, run.name)
    recorded = False
    for role in selfplay.ROLES:
        log = os.path.join(out, role, "training_log.csv")
        rows = logged_rows(log, 1)
        if rows:
            done, wall_s = rows[-1]
            _record_log(ws, log, dest, role + "_", "{} ({}): {:,} of {:,} steps".format(
                run.name, role, done, run.phase.steps), wall_s)
            recorded = True
    generations = os.path.join(out, "generations.yaml")
    if recorded and os.path.isfile(generations):
        shutil.copyfile(generations, os.path.join(dest, "generations.yaml"))
    if recorded:
        print("sweep: %s: generations saved: %s (of %d a side); they and the checkpoints resume only on this "
              "machine (%s)" % (run.name, _saved(generations), run.phase.generations, out))
    return int(recorded)


def _saved(generations):
    """A self-play's saved generations, as generations.yaml lists them: 'seeker_g001, hider_g001'."""
    return ", ".join("%s_g%03d" % (g["role"], g["generation"]) for g in _generations(generations)) or "none"


def _status_line(sweep, run, training):
    name, rec = run.name, sweep.records
    if training and run.phase.role == "selfplay":
        return "%-34s training  generations saved: %s (of %d a side), then its cross-play" % (
            name, _saved(os.path.join(sweep.runs_dir, name, "generations.yaml")), run.phase.generations)
    if training:
        return "%-34s training  %s%s" % (name, progress(os.path.join(sweep.runs_dir, name, "training_log.csv"),
                                                        run.phase.steps, _held_s(sweep, name)),
                                         " (retraining)" if run.retrain else "")
    if rec.is_done(run) and run.phase.role == "selfplay":
        return "%-34s done      %d generations, cross-play and records in %s" % (
            name, run.phase.generations, rec.docs(name))
    if rec.is_done(run) and run.phase.role != "hider":
        return "%-34s done      %s (capture rate, seeds 0-99)" % (name, rec.seeker_evaluation(name))
    if rec.is_done(run):
        return "%-34s done      greedy %s, sampled %s (living steps, success); %s; %s" % (
            name, rec.evaluation(name), rec.evaluation(name, "sampled"),
            "analysed" if rec.analysed(name) else "NOT analysed",
            "weights in %s" % os.path.dirname(sweep.weights(name)) if sweep.has_weights(name)
            else "weights not on this machine")
    saved = _generations(os.path.join(sweep.runs_dir, name, "generations.yaml"))
    if run.phase.role == "selfplay" and (saved or os.path.isfile(os.path.join(sweep.runs_dir, name, "seeker",
                                                                              "checkpoint.pt"))):
        return "%-34s partial   generations saved: %s (of %d a side) in %s (resumes at the next start)" % (
            name, _saved(os.path.join(sweep.runs_dir, name, "generations.yaml")), run.phase.generations,
            os.path.join(sweep.runs_dir, name))
    if os.path.isfile(os.path.join(sweep.runs_dir, name, "checkpoint.pt")):
        return "%-34s partial   checkpoint in %s (resumes at the next start)" % (
            name, os.path.join(sweep.runs_dir, name))
    return "%-34s missing" % name


def partial(sweep):
    """Brings the records of every unfinished run up to date, for a machine that may not come back:
    the training log of each run that has trained but is not done, copied into the records'
    docs/runs/<run>/partial/ with its learning curve (no weights: a run is recorded only whole); and
    the partial/ of every done run removed (the queue removes it as it records a run). An unfinished
    self-play gives its generations.yaml and each side's log and curve; its saved generations and
    checkpoints, which only this machine can resume, are named, not copied."""
    ws = Workspace(sweep.checkout)
    written = removed = 0
    for run in sweep.all_runs():
        dest = sweep.records.partial(run.name)
        if sweep.records.is_done(run):
            if sweep.records.clear_partial(run.name):
                removed += 1
                print("sweep: %s is done: removed its partial records %s" % (run.name, dest))
            continue
        if run.phase.role == "selfplay":
            written += _partial_selfplay(ws, sweep, run, dest)
            continue
        log = os.path.join(sweep.runs_dir, run.name, "training_log.csv")
        rows = logged_rows(log, 1)
        if not rows:
            continue  # nothing trained yet (or only the header)
        done, wall_s = rows[-1]
        if done >= run.phase.steps:
            print("sweep: %s: trained all its steps; the queue is evaluating and recording it (or its records "
                  "failed: %s)" % (run.name, os.path.join(sweep.logs, run.name + ".log")))
            continue
        # The log's wall time counts the time a pause held the run; its training time does not.
        _record_log(ws, log, dest, "", "{}: {:,} of {:,} steps".format(run.name, done, run.phase.steps),
                    max(wall_s - _held_s(sweep, run.name), 0.0))
        written += 1
    print("sweep: %d unfinished runs recorded, %d done runs' partial records removed%s" % (
        written, removed, " (commit docs/runs/*/partial)" if written or removed else ""))
    return 0


def hours(sweep):
    """Machine time per phase, from the registry (a Markdown table): the training time of each done
    run (recorded with all its steps and evaluated), the time the sweep held it paused left out,
    summed as run-hours (a self-play's: its generations' in all). A phase trains `jobs` runs at once,
    which share the machine, so its machine-hours are its run-hours / jobs. Retrains
    (<run>_retrain) are counted apart, as if trained `jobs` at once too; evaluations and analyses are
    not counted. The runs left, retrains queued among them, are estimated at the machine time per
    step of the phase's own done runs or, where it has none, of the nearest earlier phase with the
    same role and network (the same game first)."""
    entries = sweep.records.entries()
    out = ["| phase | game | runs done | run-hours | jobs | machine-hours | machine minutes per run "
           "| retrains: runs, machine-hours | left: runs, machine-hours (estimated from) |",
           "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    total, left_h, per_step = 0.0, 0.0, {}  # per_step: phase name -> machine seconds per step
    queued_retrains = [r for r in sweep.retrain_runs() if sweep.wants_retrain(r)]
    for phase in sweep.config.phases:
        runs = [r for r in sweep.config.runs() if r.phase is phase]
        done = [r for r in runs if sweep.records.is_done(r)]
        first_s = sum(_run_s(sweep, r, entries) for r in done)
        retrains = [r.name + RETRAIN_SUFFIX for r in runs
                    if sweep.records.recorded_steps(r.name + RETRAIN_SUFFIX) >= phase.steps]
        machine_h = first_s / 3600.0 / phase.jobs
        retrain_h = sum(_wall_s(entries[n]) for n in retrains) / 3600.0 / phase.jobs
        total += machine_h + retrain_h
        if done and first_s > 0:
            per_step[phase.name] = machine_h * 3600.0 / (len(done) * phase.steps)
        queued = sum(1 for r in queued_retrains if r.phase is phase)
        left, estimate = len(runs) - len(done) + queued, "-"
        source = _rate_source(sweep.config.phases, phase, per_step)
        among = "; %d of them %s" % (queued, "a retrain" if queued == 1 else "retrains") if queued else ""
        if left and source:
            h = left * phase.steps * per_step[source.name] / 3600.0
            left_h += h
            estimate = "%d, %.1f (%s%s)" % (left, h, "its runs" if source is phase else source.name, among)
        elif left:
            estimate = "%d, - (no run of its kind done%s)" % (left, among)
        out.append("| %s | %s | %d of %d | %.1f | %d | %.1f | %s | %s | %s |" % (
            phase.name, phase.game, len(done), len(runs), first_s / 3600.0, phase.jobs, machine_h,
            "%.0f" % (machine_h * 60 / len(done)) if done else "-",
            "%d, %.1f" % (len(retrains), retrain_h) if retrains else "-", estimate))
    out.append("")
    out.append("In all: %.1f machine-hours of training recorded (evaluations and analyses not counted)." % total)
    out.append("Left: about %.1f machine-hours of training, estimated (a run under way counts whole; a phase "
               "estimated from another is taken to train as fast per step, rough where the two train a different "
               "number of runs at once)." % left_h)
    print("\n".join(out))
    return 0


def _rate_source(phases, phase, per_step):
    """The phase whose machine time per step estimates `phase`'s runs left: its own, else the nearest
    earlier phase of the same role and network with done runs, one of the same game first."""
    if phase.name in per_step:
        return phase
    earlier = [p for p in phases[:phases.index(phase)][::-1]
               if p.name in per_step and p.role == phase.role and p.network == phase.network]
    return next((p for p in earlier if p.game == phase.game), earlier[0] if earlier else None)


def _run_s(sweep, run, entries):
    """A done run's training seconds: its registry entry's, or a self-play's generations' in all
    (each side's last wall_s counts all its generations), less the time the sweep held it paused
    where this machine kept it."""
    if run.phase.role == "selfplay":
        generations = _generations(sweep.records.docs(run.name, "generations.yaml"))
        return sum(selfplay.generation_seconds(generations)) - _held_s(sweep, run.name)
    return _wall_s(entries.get(run.name))


def _generations(path):
    """The generations a self-play's generations.yaml lists ([] without one)."""
    try:
        with open(path) as f:
            return (yaml.safe_load(f) or {}).get("generations") or []
    except (OSError, yaml.YAMLError):
        return []


def _wall_s(entry):
    """A registry entry's training seconds (wall_s: the paused time already left out); 0 without one."""
    try:
        return float((entry or {}).get("wall_s") or 0)
    except (TypeError, ValueError):
        return 0.0


def retrain(sweep, names):
    if not names:
        raise SweepError("retrain: name the runs to train again (sweep ship names the ones a variant needs)")
    by_name = {r.name: r for r in sweep.config.runs()}
    sweep.make_dirs()
    queued = 0
    for name in names:
        if name not in by_name:
            raise SweepError("retrain: '%s' is not a run of the queue (sweep status lists them)" % name)
        if by_name[name].phase.role != "hider":
            raise SweepError("retrain: '%s' is a %s phase's run, which ships no weights to recover"
                             % (name, by_name[name].phase.role))
        if not sweep.records.is_done(by_name[name]):
            raise SweepError("retrain: '%s' is not done: the queue trains it anyway" % name)
        if sweep.has_weights(name):
            print("sweep: %s: its weights are here (%s); nothing to retrain" % (name, sweep.weights(name)))
            continue
        # Refused only while runner.recover could still check history's weights: not after its check
        # failed (policy.recovered.pt), nor where the recorded episodes to check them against are missing.
        checked = os.path.join(sweep.runs_dir, name, "policy.recovered.pt")
        checkable = not os.path.isfile(checked) and os.path.isfile(sweep.records.docs(name, "episodes.csv"))
        found = checkable and sweep.records.registry.weights_in_history(name, sweep.records.registry_path)
        if found:
            print("sweep: %s: not queued: its weights are in git commit %s, where it shipped; 'hideseek_pipeline "
                  "sweep ship' recovers them where they replay its recorded episodes (a retrain is queued only "
                  "after that check fails)" % (name, found[0][:12]))
            continue
        if name not in sweep.retrain_list():
            with open(sweep.state_file("retrain"), "a") as f:
                f.write(name + "\n")
        print("sweep: %s queued for retraining, after every other run of the queue, as %s%s beside its "
              "first draw" % (name, name, RETRAIN_SUFFIX))
        if name not in sweep.config.retrain:
            print("sweep: %s: queued on this machine only; add it to the retrain: list of %s to keep it on any "
                  "machine" % (name, sweep.config.path or "config/sweep.yaml"))
        queued += 1
    if queued and sweep.queue_pid():
        print("sweep: the running queue takes it up when a slot frees")
    return 0


def pause(sweep):
    """SIGSTOP every training run's process tree; the queue starts no new run until resume."""
    if os.path.exists(sweep.state_file("paused")):
        print("sweep: already paused")
        return 0
    sweep.make_dirs()
    with proc.FileLock(sweep.state_file("launch.lock")):
        open(sweep.state_file("paused"), "w").write("%d\n" % time.time())
        held = sweep.job_pids()
        for pid in held.values():
            proc.stop_tree(pid)
        with open(sweep.state_file("paused.runs"), "w") as f:
            f.writelines("%s %d\n" % item for item in held.items())
    print("sweep: paused (%d runs held; the queue starts no new run until 'hideseek_pipeline sweep resume')"
          % len(held))
    return 0


def paused_since(sweep):
    """When the pause began; now where its file is empty or unreadable (a pause cut short as it was
    written): nothing is booked for it, and the runs are resumed all the same."""
    try:
        return float(last_line(sweep.state_file("paused")))
    except ValueError:
        return time.time()


def resume(sweep, book=True):
    """SIGCONT the runs the pause held; with `book`, adds the held time to each one's paused_s
    (not when they are being stopped: they restart from a checkpoint older than the pause)."""
    if not os.path.exists(sweep.state_file("paused")):
        print("sweep: not paused")
        return 0
    held = int(time.time() - paused_since(sweep))
    for line in read_lines(sweep.state_file("paused.runs")):
        name, pid = (line.split() + ["", ""])[:2]
        if not pid.isdigit() or not proc.alive(int(pid)):
            continue
        ended = time.time()  # before the run goes on: no update of it comes before this
        # SIGCONT before the lock: a job stopped while holding it would hold it for good
        proc.continue_tree(int(pid))
        if book:
            run_dir = os.path.join(sweep.runs_dir, name)
            os.makedirs(run_dir, exist_ok=True)
            with proc.FileLock(os.path.join(run_dir, PAUSES_LOCK)):
                # the total, then when the pause ended (drop_pauses_after_checkpoint reads both)
                path = os.path.join(run_dir, "paused_s")
                write_atomically(path, "%d\n" % (int(float(last_line(path) or 0)) + held))
                with open(os.path.join(run_dir, PAUSES_LOG), "a") as f:
                    f.write("%.3f %d\n" % (ended, held))
    remove_file(sweep.state_file("paused"))
    remove_file(sweep.state_file("paused.runs"))
    print("sweep: resumed after %d s" % held)
    return 0


PAUSES_LOCK = "paused.lock"  # held while either is written: resume() and a run's start may meet


def drop_pauses_after_checkpoint(run_dir):
    """Before a run's training (re)starts: the pauses booked into its paused_s after its last
    checkpoint are taken off it, and their seconds returned. A stop or a crash lost the training
    after that checkpoint, and the log of the resumed run, which goes on from the checkpoint, holds
    none of them; a run without a checkpoint starts afresh and keeps none. Trainers from 2026-12-01
    on date a checkpoint's file at the update it holds (before, at its writing, which follows the
    update at once unless a pause or a stop falls between), and no update happens during a pause,
    so a pause that ended after that date came after the update. Pauses booked before paused.log
    existed are kept as they are."""
    log = os.path.join(run_dir, PAUSES_LOG)
    if not os.path.isfile(log):
        return 0
    with proc.FileLock(os.path.join(run_dir, PAUSES_LOCK)):
        return _drop_pauses(run_dir, log)


def _drop_pauses(run_dir, log):
    checkpoint = os.path.join(run_dir, "checkpoint.pt")
    since = os.path.getmtime(checkpoint) if os.path.isfile(checkpoint) else None
    kept, dropped = [], 0
    for line in read_lines(log):
        fields = line.split()
        try:
            ended, held = float(fields[0]), int(fields[1])
        except (IndexError, ValueError):
            continue  # a line cut short as it was written: its pause stays in paused_s
        if since is not None and ended <= since:
            kept.append(line)
        else:
            dropped += held
    if dropped:
        path = os.path.join(run_dir, "paused_s")
        write_atomically(path, "%d\n" % max(int(float(last_line(path) or 0)) - dropped, 0))
        write_atomically(log, "".join(line + "\n" for line in kept))
    return dropped


def stop(sweep):
    queue = sweep.queue_pid()
    sweep.make_dirs()
    open(sweep.state_file("stop"), "w").close()
    if os.path.exists(sweep.state_file("paused")):
        with open(os.devnull, "w") as null:
            stdout, sys.stdout = sys.stdout, null
            try:
                resume(sweep, book=False)
            finally:
                sys.stdout = stdout
    for pid in sweep.job_pids().values():
        proc.signal_tree(pid, signal.SIGINT)
    if isinstance(queue, int):
        os.kill(queue, signal.SIGTERM)  # the queue stops its runs itself, gracefully
    for _ in range(60):
        if not sweep.queue_pid() and not sweep.job_pids():
            break
        time.sleep(1)
    for pid in sweep.job_pids().values():
        proc.signal_tree(pid, signal.SIGKILL)
    print("sweep: stopped; 'hideseek_pipeline sweep start' resumes each run from its last checkpoint")
    return 0


def hold(sweep, command):
    """Pauses a running queue, runs `command`, resumes the queue whatever its exit; with no queue
    running, just the command. make bench and make test run under it."""
    if not command:
        raise SweepError("hold: name the command to run while the sweep is paused")
    if not sweep.queue_pid() or os.path.exists(sweep.state_file("paused")):
        return subprocess.run(command).returncode
    # As a shell would: a Ctrl-C reaches the command through the terminal, a TERM is passed on to
    # it, and either way the command is waited out, then the queue resumed. The handlers are in
    # place before the pause: a signal that comes before the command has started stops it from
    # starting, and the queue is resumed all the same.
    child, caught = None, []

    def pass_on(signum, _):
        caught.append(signum)
        if child is not None and signum == signal.SIGTERM:
            child.send_signal(signum)

    previous = {s: signal.signal(s, pass_on) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        pause(sweep)
        if caught:
            return 128 + caught[0]
        child = subprocess.Popen(command)
        if signal.SIGTERM in caught:  # it came while the command was being started
            child.terminate()
        rc = child.wait()
        return 128 - rc if rc < 0 else rc
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
        resume(sweep)
