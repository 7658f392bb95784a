"""hideseek_pipeline sweep: the queue's phases and order, what counts as done, retrain, pause and
resume with the paused time kept apart, hold and analyze, on small made-up registries and configs:
no training, no ROS master."""
import io
import os
import re
import signal
import subprocess
import sys
import time
import types
import zipfile

import numpy as np
import pytest
import yaml
from stand_ins import stand_in_workspace

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
PACKAGE = os.path.join(ROOT, "src", "hideseek_pipeline", "python")
sys.path.insert(0, PACKAGE)
from hideseek_pipeline import runner, sweep_config  # noqa: E402

TWO_PHASES = """
precision: bf16
jobs: 2
hider_threads: 1
steps: 2000000
network: ff
port: 12100
phases:
  - {name: first, commit: "0123456789ab", game: v2, variants: [basic, slowerhider], seeds: [0, 1]}
  - {name: later, commit: "0123456789ab", game: v3, network: gru, variants: [basic], seeds: [0], steps: 8000000,
     jobs: 1, hider_threads: 2, ship: false}
"""


def evaluation(variant, name, living):
    """An evaluation.csv's text: its one row, for the episodes' living steps."""
    living = np.array(living)
    return "variant,policy,episodes,avg_living_steps,success_rate\n%s,%s,%d,%.2f,%.4f\n" % (
        variant, name, len(living), living.mean(), (living >= 1000).mean())


def make_records(tmp_path, runs, foreign=()):
    """A checkout-like folder: a registry of sweep runs `runs` (name -> variant, seed, steps, greedy
    and sampled living steps; those named in `foreign` without the sweep's note, as another command
    records them) and, for each, both evaluations and its trajectories."""
    rec = tmp_path / "records"
    (rec / "policies").mkdir(parents=True)
    note = "sweep run (config/sweep.yaml), pinned at 0123456789ab"
    entries = {name: {"variant": v, "network": "gru" if "_gru" in name else "ff", "game": "v2", "training_seed": seed,
                      "steps": steps, "note": note} for name, (v, seed, steps, _, _) in runs.items()}
    for name in foreign:
        del entries[name]["note"]
    for name, (variant, _, _, greedy, sampled) in runs.items():
        run = rec / "docs" / "runs" / name
        (run / "sampled").mkdir(parents=True)
        (run / "trajectories.png").write_bytes(b"png")
        (run / "evaluation.csv").write_text(evaluation(variant, name, greedy))
        (run / "sampled" / "evaluation.csv").write_text(evaluation(variant, name, sampled))
    (rec / "policies" / "policies.yaml").write_text(yaml.safe_dump(entries, sort_keys=False))
    return rec


def config_file(tmp_path, text=None, variants="basic slowerhider", seeds="0 1", network="ff"):
    path = tmp_path / "sweep.yaml"
    path.write_text(text or "precision: bf16\njobs: 2\nhider_threads: 1\nsteps: 2000000\nport: 12100\nphases:\n"
                    "  - {name: only, commit: '0123456789ab', game: v2, network: %s, variants: [%s], seeds: [%s]}\n"
                    % (network, ", ".join(variants.split()), ", ".join(seeds.split())))
    return path


def sweep(tmp_path, rec, *args, config=None, **env):
    e = dict(os.environ, SWEEP_DIR=str(tmp_path / "sweep"), SWEEP_RECORD_ROOT=str(rec), PYTHONPATH=PACKAGE,
             CALLS=str(tmp_path / "calls.txt"), PATH="/usr/bin:" + os.environ["PATH"])
    e.update(env)
    config = config or config_file(tmp_path)
    return subprocess.run([sys.executable, "-m", "hideseek_pipeline", "sweep", "--config", str(config)] + list(args),
                          env=e, capture_output=True, text=True, timeout=120)


def rows(stdout):
    return [line.split()[:2] for line in stdout.splitlines() if not line.startswith("sweep:")]


def test_status_lists_runs_seed_major_with_their_state(tmp_path):
    rec = make_records(tmp_path, {
        "basic_seed0": ("basic", 0, 2000000, [30, 1000], [20, 40]),
        # recorded but short of the steps: not done
        "slowerhider_seed0": ("slowerhider", 0, 1000000, [30], [30]),
        # all steps and both evaluations, but trained by another command (no sweep note): not done
        "basic_seed1": ("basic", 1, 2000000, [30], [30]),
    }, foreign=["basic_seed1"])
    ck = tmp_path / "sweep" / "runs" / "slowerhider_seed1"
    ck.mkdir(parents=True)
    (ck / "checkpoint.pt").write_bytes(b"x")
    r = sweep(tmp_path, rec, "status")
    assert r.returncode == 0, r.stderr
    assert rows(r.stdout) == [["basic_seed0", "done"], ["slowerhider_seed0", "missing"], ["basic_seed1", "missing"],
                              ["slowerhider_seed1", "partial"]]
    assert "greedy 515.00/0.5000" in r.stdout


def test_status_shows_a_training_run_s_progress_and_the_time_left(tmp_path):
    """While the queue trains a run, status says how far it is, how long it has trained (less the
    time the sweep held it paused) and, at its rate over the last two updates, how long it has
    left, passing over a line the trainer is still writing; a run that has logged nothing yet, or
    has trained all its steps, says so."""
    import fcntl
    rec = make_records(tmp_path, {})
    state, runs = tmp_path / "sweep" / "state", tmp_path / "sweep" / "runs"
    state.mkdir(parents=True)
    header = ("update,steps,wall_s,steps_per_s,episodes,mean_length,mean_return,policy_loss,value_loss,entropy,"
              "approx_kl,clip_fraction,learning_rate\n")

    def row(update, steps, wall_s):
        return "%d,%d,%.1f,300,900,60,-0.9,0,0,1.2,0,0,0.0003\n" % (update, steps, wall_s)

    logs = {
        # 2,048 steps in 4 s between the last two updates: 512 steps/s; 1,497,216 steps left: 48.7 min.
        "basic_seed0": header + row(488, 500736, 1796.0) + row(489, 502784, 1800.0) + "490,504832,18",
        "slowerhider_seed0": header,
        "basic_seed1": header + row(1953, 1999872, 4000.0) + row(1954, 2000896, 4002.0),
    }
    for name, text in logs.items():
        (runs / name).mkdir(parents=True)
        (runs / name / "training_log.csv").write_text(text)
        (state / ("job." + name)).write_text("%d\n" % os.getpid())  # a live PID: this test's
    (runs / "basic_seed0" / "paused_s").write_text("600\n")
    (state / "queue.pid").write_text("%d\n" % os.getpid())
    config = config_file(tmp_path, seeds="0 1")
    with open(state / "queue.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # held, as a running queue holds it
        r = sweep(tmp_path, rec, "status", config=config)
    assert r.returncode == 0, r.stderr
    lines = {line.split()[0]: line.split(None, 1)[1] for line in r.stdout.splitlines() if not line.startswith("sweep:")}
    assert lines["basic_seed0"] == ("training  502,784 of 2,000,000 steps (25 %), 20 min of training, about 49 min "
                                    "left at 512 steps/s")
    assert lines["slowerhider_seed0"] == "training  started, no update logged yet"
    assert lines["basic_seed1"] == "training  all 2,000,896 steps trained in 67 min; being evaluated and recorded"
    assert "queue running (pid %d)" % os.getpid() in r.stdout


def test_partial_records_each_unfinished_run_s_log_and_curve_and_clears_a_done_run_s(tmp_path):
    """Before a machine goes: an unfinished run's training log and curve land in its records'
    partial/ (no weights); a done run's stale partial/ goes; a run that has not trained, or has
    trained all its steps and is being recorded, writes nothing."""
    rec = make_records(tmp_path, {"basic_seed0": ("basic", 0, 2000000, [30, 1000], [20, 40])})
    stale = rec / "docs" / "runs" / "basic_seed0" / "partial"
    stale.mkdir()
    (stale / "training_log.csv").write_text("old")
    header = ("update,steps,wall_s,steps_per_s,episodes,mean_length,mean_return,policy_loss,value_loss,entropy,"
              "approx_kl,clip_fraction,learning_rate\n")
    log = header + "".join("%d,%d,%.1f,450,%d,%d,-0.9,0,0,1.6,0,0,0.0003\n" % (u, 1024 * u, 2.3 * u, 10 * u, 40 + u)
                           for u in range(1, 40))
    runs = tmp_path / "sweep" / "runs"
    (runs / "slowerhider_seed0").mkdir(parents=True)
    (runs / "slowerhider_seed0" / "training_log.csv").write_text(log)
    (runs / "slowerhider_seed0" / "checkpoint.pt").write_bytes(b"x")
    (runs / "slowerhider_seed0" / "paused_s").write_text("60\n")  # a make test held it 60 s of its 89.7
    (runs / "basic_seed1").mkdir()
    (runs / "basic_seed1" / "training_log.csv").write_text(header)  # started, nothing logged yet
    (runs / "slowerhider_seed1").mkdir()  # trained all its steps, its evaluation under way: not partial
    (runs / "slowerhider_seed1" / "training_log.csv").write_text(header + "1954,2000896,4800.2,450,9000,300,-0.4,0,0,"
                                                                 "0.5,0,0,0\n")
    r = sweep(tmp_path, rec, "partial")
    assert r.returncode == 0, r.stdout + r.stderr
    unfinished = rec / "docs" / "runs" / "slowerhider_seed0" / "partial"
    assert (unfinished / "training_log.csv").read_text() == log
    assert (unfinished / "learning_curve.png").read_bytes()[:4] == b"\x89PNG"
    assert "slowerhider_seed0: 39,936 of 2,000,000 steps, 29 s of training" in r.stdout
    assert not stale.exists() and (rec / "docs" / "runs" / "basic_seed0" / "evaluation.csv").exists()
    assert not (rec / "docs" / "runs" / "basic_seed1").exists()
    assert not (rec / "docs" / "runs" / "slowerhider_seed1").exists()
    assert "slowerhider_seed1: trained all its steps; the queue is evaluating and recording it" in r.stdout
    assert r.stdout.strip().splitlines()[-1].startswith("sweep: 1 unfinished runs recorded, 1 done runs' partial")


def test_hours_sums_each_phase_s_recorded_training_time_per_machine(tmp_path):
    rec = make_records(tmp_path, {
        "basic_seed0": ("basic", 0, 2000000, [30], [30]),
        "slowerhider_seed0": ("slowerhider", 0, 2000000, [30], [30]),
        "basic_seed0_retrain": ("basic", 0, 2000000, [30], [30]),
        "basic_v3_gru_8m_seed0": ("basic", 0, 8000000, [30], [30]),
        "basic_v3_seed0": ("basic", 0, 2000000, [30], [30]),
        # short of its steps: not done, not counted
        "basic_seed1": ("basic", 1, 1000000, [30], [30]),
    })
    registry = rec / "policies" / "policies.yaml"
    entries = yaml.safe_load(registry.read_text())
    for name, wall in (("basic_seed0", 3600), ("slowerhider_seed0", 5760), ("basic_seed0_retrain", 2160),
                       ("basic_v3_gru_8m_seed0", 7200), ("basic_v3_seed0", 2160), ("basic_seed1", 99999)):
        entries[name]["wall_s"] = wall
    registry.write_text(yaml.safe_dump(entries, sort_keys=False))
    three = TWO_PHASES + (
        '  - {name: v3ff, commit: "0123456789ab", game: v3, variants: [basic], seeds: [0]}\n'
        '  - {name: longer, commit: "0123456789ab", game: v2, variants: [basic], seeds: [0], steps: 4000000}\n'
        '  - {name: longer3, commit: "0123456789ab", game: v3, variants: [basic], seeds: [1], steps: 4000000}\n'
        '  - {name: seeker, commit: "0123456789ab", role: seeker, variants: [basic], seeds: [0]}\n')
    r = sweep(tmp_path, rec, "hours", config=config_file(tmp_path, three))
    assert r.returncode == 0, r.stderr
    table = {line.split("|")[1].strip(): [c.strip() for c in line.split("|")[2:-1]]
             for line in r.stdout.splitlines() if line.startswith("| ") and not line.startswith("| phase")}
    # first: two of four runs, 2.6 run-hours, two at once: 1.3 machine-hours, 39 min a run; a retrain of
    # 0.6 h; its two runs left at its own 39 min a run
    assert table["first"] == ["v2", "2 of 4", "2.6", "2", "1.3", "39", "1, 0.3", "2, 1.3 (its runs)"]
    # later: one run alone (jobs 1): its run-hours are machine-hours
    assert table["later"] == ["v3", "1 of 1", "2.0", "1", "2.0", "120", "-", "-"]
    # a phase with no run done: at the machine time per step of the nearest earlier phase of its kind
    # (the same role and network, the same game first: v2's first for longer, though v3ff is nearer;
    # v3ff for longer3), over its own steps; a seeker's phase has no phase of its kind
    assert table["v3ff"][-1] == "-" and table["v3ff"][4] == "0.3"
    assert table["longer"][-1] == "1, 1.3 (first)"
    assert table["longer3"][-1] == "1, 0.6 (v3ff)"
    assert table["seeker"][-1] == "1, - (no run of its kind done)"
    assert "In all: 3.9 machine-hours" in r.stdout
    assert "Left: about 3.2 machine-hours of training, estimated" in r.stdout
    # a retrain queued (a done run whose weights are lost) is a run left of its phase
    r = sweep(tmp_path, rec, "retrain", "slowerhider_seed0", config=config_file(tmp_path, three))
    assert r.returncode == 0 and "queued for retraining" in r.stdout, r.stdout + r.stderr
    r = sweep(tmp_path, rec, "hours", config=config_file(tmp_path, three))
    table = {line.split("|")[1].strip(): [c.strip() for c in line.split("|")[2:-1]]
             for line in r.stdout.splitlines() if line.startswith("| ") and not line.startswith("| phase")}
    # at its own 39 min a run: 3 x 0.65 h (printed to one decimal)
    left, h, why = re.match(r"(\d+), ([\d.]+) \((.*)\)$", table["first"][-1]).groups()
    assert (left, why) == ("3", "its runs; 1 of them a retrain") and abs(float(h) - 1.95) < 0.051, r.stdout
    total = float(re.search(r"Left: about ([\d.]+) machine-hours", r.stdout).group(1))
    assert abs(total - (3.2 + 0.65)) < 0.11, r.stdout
    # once its weights are back, the retrain is no longer left
    (tmp_path / "sweep" / "runs" / "slowerhider_seed0").mkdir(parents=True, exist_ok=True)
    (tmp_path / "sweep" / "runs" / "slowerhider_seed0" / "policy.pt").write_bytes(b"weights")
    r = sweep(tmp_path, rec, "hours", config=config_file(tmp_path, three))
    assert "| 2, 1.3 (its runs) |" in r.stdout and "Left: about 3.2 machine-hours" in r.stdout, r.stdout


def test_phases_run_in_order_each_seed_major_and_names_tell_the_runs_apart(tmp_path):
    rec = make_records(tmp_path, {})
    r = sweep(tmp_path, rec, "status", config=config_file(tmp_path, TWO_PHASES))
    assert r.returncode == 0, r.stderr
    assert [row[0] for row in rows(r.stdout)] == [
        "basic_seed0", "slowerhider_seed0", "basic_seed1", "slowerhider_seed1", "basic_v3_gru_8m_seed0"]
    assert "2 phases (first at 0123456789ab, later at 0123456789ab)" in r.stdout
    # SWEEP_PHASES keeps the phases named; SWEEP_<KEY> overrides a key in every phase
    r = sweep(tmp_path, rec, "status", config=config_file(tmp_path, TWO_PHASES), SWEEP_PHASES="later",
              SWEEP_SEEDS="3 4")
    assert [row[0] for row in rows(r.stdout)] == ["basic_v3_gru_8m_seed3", "basic_v3_gru_8m_seed4"]


def test_a_phase_keeps_its_own_budget_and_runs_at_once():
    config = sweep_config.load(_write(TWO_PHASES), ["basic", "slowerhider"], ["basic", "slowerhider"], "v2", {})
    first, later = config.phases
    assert (first.steps, first.jobs, first.hider_threads, first.game) == (2000000, 2, 1, "v2")
    assert (later.steps, later.jobs, later.hider_threads, later.network, later.ship) == (8000000, 1, 2, "gru", False)
    assert sweep_config.run_name("basic", 0, "v2", "ff", 2_000_000) == "basic_seed0"
    assert sweep_config.run_name("basic", 1, "v3", "ff", 500_000) == "basic_v3_500k_seed1"


def _write(text):
    import tempfile
    f = tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False)
    f.write(text)
    f.close()
    return f.name


def test_two_phases_holding_one_run_and_bad_keys_are_refused_by_name(tmp_path):
    rec = make_records(tmp_path, {})
    twice = TWO_PHASES.replace("game: v3, network: gru, variants: [basic], seeds: [0], steps: 8000000",
                               "game: v2, variants: [basic], seeds: [0], steps: 2000000")
    r = sweep(tmp_path, rec, "status", config=config_file(tmp_path, twice))
    assert r.returncode == 2 and "phases first and later both hold the run basic_seed0" in r.stderr
    r = sweep(tmp_path, rec, "status", config=config_file(tmp_path, TWO_PHASES + "colour: blue\n"))
    assert r.returncode == 2 and "unknown key colour" in r.stderr
    r = sweep(tmp_path, rec, "status", config=config_file(tmp_path, TWO_PHASES), SWEEP_PHASES="nosuchphase")
    assert r.returncode == 2 and "no phase nosuchphase" in r.stderr


def test_more_seeds_only_lengthen_the_queue(tmp_path):
    rec = make_records(tmp_path, {})
    r = sweep(tmp_path, rec, "status", config=config_file(tmp_path, variants="basic", seeds="0 1 2 3 4"))
    assert [row[0] for row in rows(r.stdout)] == ["basic_seed%d" % s for s in range(5)]


def test_an_unknown_variant_or_bad_number_is_refused_by_name(tmp_path):
    rec = make_records(tmp_path, {})
    r = sweep(tmp_path, rec, "status", config=config_file(tmp_path, variants="basic nosuchvariant"))
    assert r.returncode == 2 and "no variant 'nosuchvariant'" in r.stderr
    r = sweep(tmp_path, rec, "status", SWEEP_STEPS="2M")
    assert r.returncode == 2 and "'2M' is not a whole number" in r.stderr
    r = sweep(tmp_path, rec, "status", SWEEP_START_WITHIN_MIN="soon")
    assert r.returncode == 2 and "start_within_min: 'soon' is not a number of minutes >= 0" in r.stderr
    r = sweep(tmp_path, rec, "frobnicate")
    assert r.returncode == 2 and "invalid choice: 'frobnicate'" in r.stderr


def test_retrain_queues_a_done_run_without_weights_after_every_other_run(tmp_path):
    rec = make_records(tmp_path, {"basic_seed0": ("basic", 0, 2000000, [30, 1000], [20, 40])})
    r = sweep(tmp_path, rec, "retrain", "basic_seed9")
    assert r.returncode == 2 and "'basic_seed9' is not a run of the queue" in r.stderr
    r = sweep(tmp_path, rec, "retrain", "slowerhider_seed0")
    assert r.returncode == 2 and "is not done" in r.stderr
    r = sweep(tmp_path, rec, "retrain", "basic_seed0")
    assert r.returncode == 0 and "basic_seed0 queued for retraining" in r.stdout, r.stderr
    assert "as basic_seed0_retrain beside its first draw" in r.stdout
    status = sweep(tmp_path, rec, "status").stdout
    assert "queued for retraining (weights lost; after every other run): basic_seed0" in status
    # the missing runs first, seed-major, then the retraining, a run of its own beside the first draw
    assert "left to train, in order: slowerhider_seed0 basic_seed1 slowerhider_seed1 basic_seed0_retrain" in status
    assert re.search(r"^basic_seed0_retrain +missing", status, re.M), status
    # once its weights are here (the retrained run, or the old ones found), it is not trained again
    w = tmp_path / "sweep" / "runs" / "basic_seed0"
    w.mkdir(parents=True)
    (w / "policy.pt").write_bytes(b"weights")
    status = sweep(tmp_path, rec, "status").stdout
    assert "queued for retraining" not in status
    assert "left to train, in order: slowerhider_seed0 basic_seed1 slowerhider_seed1\n" in status
    r = sweep(tmp_path, rec, "retrain", "basic_seed0")
    assert r.returncode == 0 and "nothing to retrain" in r.stdout


def test_the_config_s_retrain_list_is_trained_on_a_machine_that_never_queued_it(tmp_path):
    """`sweep retrain` queues a run on this machine only (its state folder), and a new machine loses
    it; config/sweep.yaml's `retrain:` keeps the same wish in the repository."""
    rec = make_records(tmp_path, {"basic_seed0": ("basic", 0, 2000000, [30, 1000], [20, 40])})
    text = config_file(tmp_path).read_text()
    config = config_file(tmp_path, text + "retrain: [basic_seed0]\n")
    status = sweep(tmp_path, rec, "status", config=config).stdout
    assert "queued for retraining (weights lost; after every other run): basic_seed0" in status, status
    assert "left to train, in order: slowerhider_seed0 basic_seed1 slowerhider_seed1 basic_seed0_retrain" in status
    assert not (tmp_path / "sweep" / "state" / "retrain").exists()
    r = sweep(tmp_path, rec, "retrain", "basic_seed0", config=config)
    assert r.returncode == 0 and "queued on this machine only" not in r.stdout, r.stdout
    # queued by hand only: said to be this machine's alone
    r = sweep(tmp_path, rec, "retrain", "basic_seed0", config=config_file(tmp_path, text))
    assert r.returncode == 0 and "queued on this machine only; add it to the retrain: list of" in r.stdout, r.stdout
    # weights back: nothing left to retrain, though the config still names it
    w = tmp_path / "sweep" / "runs" / "basic_seed0"
    w.mkdir(parents=True)
    (w / "policy.pt").write_bytes(b"weights")
    status = sweep(tmp_path, rec, "status", config=config_file(tmp_path, text + "retrain: [basic_seed0]\n")).stdout
    assert "queued for retraining" not in status and "basic_seed0_retrain" not in status.split("in order:")[-1]
    for bad, said in (("[basic_seed9]", "retrain: 'basic_seed9' is not a run of the queue"),
                      ("basic_seed0 nobody", "retrain: 'nobody' is not a run of the queue")):
        r = sweep(tmp_path, rec, "status", config=config_file(tmp_path, text + "retrain: %s\n" % bad))
        assert r.returncode == 2 and said in r.stderr, r.stderr
    # a phase left out by SWEEP_PHASES leaves its runs out of the list, not refused; a seeker's run is refused
    two = TWO_PHASES + "retrain: [slowerhider_seed1, basic_v3_gru_8m_seed0]\n"
    variants = ["basic", "slowerhider"]
    assert sweep_config.load(_write(two), variants, variants, "v2", {}).retrain == ["slowerhider_seed1",
                                                                                     "basic_v3_gru_8m_seed0"]
    assert sweep_config.load(_write(two), variants, variants, "v2", {"SWEEP_PHASES": "first"}).retrain == [
        "slowerhider_seed1"]
    with pytest.raises(sweep_config.ConfigError, match="retrain: 'basic_seeker_seed0' is a seeker phase's run"):
        sweep_config.load(_write(SEEKER_PHASE + "retrain: [basic_seeker_seed0]\n"), ["basic"], ["basic"], "v2", {})


def proc_state(pid, want=None, wait=10.0):
    """A process's state letter; with `want`, waits (a signal lands asynchronously) until it is one of them."""
    end = time.time() + wait
    while True:
        with open("/proc/%d/stat" % pid) as f:
            state = f.read().rsplit(")", 1)[1].split()[0]
        if want is None or state in want or time.time() > end:
            return state
        time.sleep(0.05)


def fake_queue(state):
    """A process that holds the queue's lock, as a running queue does (one process: a TERM ends it
    and frees the lock)."""
    q = subprocess.Popen([sys.executable, "-c", "import fcntl, sys, time; f = open(sys.argv[1], 'a'); "
                          "fcntl.flock(f, fcntl.LOCK_EX); time.sleep(300)", str(state / "queue.lock")])
    (state / "queue.pid").write_text("%d\n" % q.pid)
    end = time.time() + 10
    while subprocess.run(["flock", "-n", str(state / "queue.lock"), "true"]).returncode == 0:
        assert time.time() < end, "the fake queue did not take its lock"
        time.sleep(0.05)
    return q


def test_pause_stops_the_runs_processes_and_resume_books_the_paused_time(tmp_path):
    rec = make_records(tmp_path, {})
    state = tmp_path / "sweep" / "state"
    state.mkdir(parents=True)
    # A queue holds its lock; a running run as the queue leaves it: state/job.<run> holds the PID
    # of its process tree.
    queue = fake_queue(state)
    job = subprocess.Popen(["bash", "-c", "sleep 300 & wait"])
    try:
        time.sleep(0.3)
        child = int(subprocess.check_output(["ps", "-o", "pid=", "--ppid", str(job.pid)]).split()[0])
        (state / "job.basic_seed1").write_text("%d\n" % job.pid)
        t0 = time.time()
        r = sweep(tmp_path, rec, "pause")
        assert r.returncode == 0 and "1 runs held" in r.stdout, r.stdout + r.stderr
        assert proc_state(job.pid, "T") == "T" and proc_state(child, "T") == "T"
        assert "PAUSED" in sweep(tmp_path, rec, "status").stdout
        time.sleep(2.2)
        r = sweep(tmp_path, rec, "resume")
        held = time.time() - t0
        assert r.returncode == 0, r.stderr
        assert proc_state(child, "SR") in ("S", "R")
        paused = int((tmp_path / "sweep" / "runs" / "basic_seed1" / "paused_s").read_text())
        assert 2 <= paused <= held + 1
        # and when the pause ended, for drop_pauses_after_checkpoint
        ended, booked = (tmp_path / "sweep" / "runs" / "basic_seed1" / "paused.log").read_text().split()
        assert int(booked) == paused and abs(float(ended) - time.time()) < 5
        # A second pause adds to the first.
        sweep(tmp_path, rec, "pause")
        time.sleep(1.1)
        sweep(tmp_path, rec, "resume")
        assert int((tmp_path / "sweep" / "runs" / "basic_seed1" / "paused_s").read_text()) >= paused + 1
        # a stop while paused does not book the held time: the run restarts from a checkpoint
        # older than the pause
        booked = int((tmp_path / "sweep" / "runs" / "basic_seed1" / "paused_s").read_text())
        sweep(tmp_path, rec, "pause")
        time.sleep(1.1)
        sweep(tmp_path, rec, "stop")
        assert int((tmp_path / "sweep" / "runs" / "basic_seed1" / "paused_s").read_text()) == booked
    finally:
        subprocess.run(["pkill", "-KILL", "-P", str(job.pid)])
        for p in (job, queue):
            p.kill()
            p.wait()


def test_hold_runs_a_command_with_the_sweep_paused_and_resumes_it(tmp_path):
    rec = make_records(tmp_path, {})
    state = tmp_path / "sweep" / "state"
    state.mkdir(parents=True)
    queue = fake_queue(state)  # hold acts only where a queue runs
    job = subprocess.Popen(["sleep", "300"])
    try:
        (state / "job.basic_seed0").write_text("%d\n" % job.pid)
        probe = "import sys; s = open('/proc/%d/stat').read().rsplit(')', 1)[1].split()[0]; sys.exit(0 if s == 'T' else 3)"
        r = sweep(tmp_path, rec, "hold", sys.executable, "-c", probe % job.pid)
        assert r.returncode == 0, r.stdout + r.stderr  # the job was stopped while the command ran
        assert proc_state(job.pid, "SR") in ("S", "R")
        assert not (state / "paused").exists()
        # the command's failure is passed on, and the sweep is resumed all the same
        r = sweep(tmp_path, rec, "hold", "false")
        assert r.returncode == 1 and proc_state(job.pid, "SR") in ("S", "R")
    finally:
        for p in (queue, job):
            p.kill()
            p.wait()
    # a TERM to hold reaches the command, is waited out, and the queue is resumed all the same
    queue, job = fake_queue(state), subprocess.Popen(["sleep", "300"])
    try:
        (state / "job.basic_seed0").write_text("%d\n" % job.pid)
        e = dict(os.environ, SWEEP_DIR=str(tmp_path / "sweep"), SWEEP_RECORD_ROOT=str(rec), PYTHONPATH=PACKAGE,
                 PATH="/usr/bin:" + os.environ["PATH"])
        held = subprocess.Popen([sys.executable, "-m", "hideseek_pipeline", "sweep", "--config",
                                 str(config_file(tmp_path)), "hold", "sleep", "60"], env=e)
        assert proc_state(job.pid, "T") == "T"
        held.terminate()
        assert held.wait(timeout=30) == 143
        assert proc_state(job.pid, "SR") in ("S", "R") and not (state / "paused").exists()
    finally:
        for p in (queue, job):
            p.kill()
            p.wait()
    # without a queue, hold only runs the command, and creates no sweep folder
    r = sweep(tmp_path, rec, "hold", "true", SWEEP_DIR=str(tmp_path / "none"))
    assert r.returncode == 0 and not (tmp_path / "none").exists()


def test_analyze_redoes_only_the_missing_memoryless_ablation_of_a_gru_run(tmp_path):
    """`sweep analyze` on a GRU phase: a done GRU run analysed without its memoryless ablation
    (analysed before it existed, or the part failed) gets that part alone while its weights are
    here; a run that has it, or whose weights are gone, is left as it is. The random hider's
    behaviour, which the claims need beside each variant, is analysed once where it is missing."""
    names = ("basic_gru_seed0", "slowerhider_gru_seed0", "basic_gru_seed1")
    rec = make_records(tmp_path, {n: (n.split("_gru")[0], int(n[-1]), 2000000, [30], [30]) for n in names})
    calls = tmp_path / "calls.txt"
    fake_analysis(rec)
    for n in names:
        d = rec / "docs" / "runs" / n / "analysis"
        (d / "memoryless").mkdir(parents=True)
        for f in ("behaviour.csv", "tsne_neighbours.csv"):
            (d / f).write_text("x\n")
        w = tmp_path / "sweep" / "runs" / n
        w.mkdir(parents=True)
        if n != "basic_gru_seed1":  # its weights are gone: nothing can be redone
            (w / "policy.pt").write_bytes(b"w")
    (rec / "docs" / "runs" / "basic_gru_seed0" / "analysis" / "memoryless" / "behaviour.csv").write_text("x\n")
    gru = config_file(tmp_path, network="gru")
    r = sweep(tmp_path, rec, "analyze", config=gru)
    assert r.returncode == 0, r.stderr
    weights = tmp_path / "sweep" / "runs" / "slowerhider_gru_seed0" / "policy.pt"
    plays = [line.split() for line in calls.read_text().splitlines() if line.startswith("play_episodes")]
    runs = [p for p in plays if p[4] != "random"]
    assert runs and all(p[4] == str(weights) and p[-1] == "memoryless" for p in runs), plays
    # and, once a variant of a game has a done run, its random hider's behaviour where the records lack it
    assert sorted({p[3] for p in plays if p[4] == "random"}) == ["basic", "slowerhider"]
    for variant in ("basic", "slowerhider"):
        assert (rec / "docs" / "analysis" / "baselines" / variant / "random" / "behaviour.csv").is_file()
    assert not [line for line in calls.read_text().splitlines() if line.startswith("probe")]
    assert "slowerhider_gru_seed0: memoryless into" in r.stdout + r.stderr
    # A feed-forward phase never asks a run for a memoryless ablation.
    calls.unlink()
    r = sweep(tmp_path, rec, "analyze")
    assert r.returncode == 0, r.stderr
    assert not calls.exists()


def test_an_analysis_in_a_checkout_not_built_names_the_missing_program_and_the_retry(tmp_path):
    """A machine's first sweep trains from its pinned tree while the records' checkout is not built:
    the run's analysis fails naming the program it lacks and how to redo it, and the run stays done."""
    rec = make_records(tmp_path, {"basic_seed0": ("basic", 0, 2000000, [30], [30])})
    fake_analysis(rec)
    (rec / "devel" / "lib" / "hideseek_analysis" / "probe_set").unlink()
    w = tmp_path / "sweep" / "runs" / "basic_seed0"
    w.mkdir(parents=True)
    (w / "policy.pt").write_bytes(b"w")
    r = sweep(tmp_path, rec, "analyze")
    out = r.stdout + r.stderr
    assert re.search(r"basic_seed0: the analysis failed \(hideseek_pipeline: hideseek_analysis/probe_set is not "
                     r"built in \S+ \(no \S+\): build the workspace first \(make build\)\); see \S+analysis.log; "
                     r"hideseek_pipeline sweep analyze retries it", out), out
    assert not (rec / "docs" / "runs" / "basic_seed0" / "analysis" / "probes.csv").exists()


def test_the_checkout_s_config_is_valid_and_no_v3_run_collides_with_a_v2_run():
    sys.path.insert(0, os.path.join(ROOT, "src", "hideseek_analysis", "python"))
    from hideseek_analysis import registry as reg
    config = sweep_config.load(os.path.join(ROOT, "config", "sweep.yaml"), reg.variants(), reg.paper_order(),
                               reg.default_game(), {})
    names = [r.name for r in config.runs()]
    assert len(names) == len(set(names))
    v2 = {n for n, e in reg.runs().items() if e["game"] == "v2"}
    assert not [r.name for r in config.runs() if r.phase.game != "v2" and r.name in v2]


FAKE_TRAIN = r"""#!/bin/bash
# A stand-in for the pinned tree's train_variant.sh: records the run as the real one does, in a second.
variant=$1 seed=$2 steps=$3 runs=$4 network=$5 name=$6
echo "start $name $(date +%s.%N) threads=$HIDER_THREADS game=${GAME:-v2}" >> "$CALLS"
# as the real trainers do, a Python module imported from the tree: no __pycache__ may stay there
/usr/bin/python3 -c "import sys; sys.path.insert(0, '$(dirname "$0")'); import helper"
mkdir -p "$runs/$name" "$RECORD_ROOT/docs/runs/$name/sampled"
echo weights > "$runs/$name/policy.pt"
sleep 1
for d in "" sampled; do
  printf 'variant,policy,episodes,avg_living_steps,success_rate\n%s,%s,100,%d.00,0.1000\n' "$variant" "$name" \
    $((100 + seed)) > "$RECORD_ROOT/docs/runs/$name/$d/evaluation.csv"
done
echo png > "$RECORD_ROOT/docs/runs/$name/trajectories.png"
/usr/bin/python3 "$REGISTRY_SCRIPT" --registry "$RECORD_ROOT/policies/policies.yaml" record "$name" variant=$variant \
  network=$network game=${GAME:-v2} training_seed=$seed steps=$steps
echo "end $name $(date +%s.%N)" >> "$CALLS"
"""


def shell_trainer_repo(tmp_path):
    """A folder with the stand-in shell trainer (and a module it imports), to commit as a pin."""
    repo = tmp_path / "repo"
    (repo / "scripts").mkdir(parents=True)
    (repo / "scripts" / "train_variant.sh").write_text(FAKE_TRAIN)
    (repo / "scripts" / "train_variant.sh").chmod(0o755)
    (repo / "scripts" / "helper.py").write_text("VALUE = 1\n")
    return repo


def pinned_repo(repo):
    """Commits the folder `repo` as a small git repository and returns the commit."""
    git = ["git", "-C", str(repo), "-c", "user.name=t", "-c", "user.email=t@t"]
    subprocess.run(["git", "init", "-q", str(repo)], check=True)
    subprocess.run(git + ["add", "-A"], check=True)
    subprocess.run(git + ["commit", "-qm", "trainer", "--allow-empty"], check=True)
    return subprocess.check_output(git + ["rev-parse", "HEAD"], text=True).strip()


def queue_in(tmp_path, repo, rec, text, calls):
    """Runs the queue of config `text` (its commit: `repo`'s) in the foreground, the worktree marked
    built; returns the command that runs it, its environment and its result."""
    commit = pinned_repo(repo)
    text = text.replace("0123456789ab", commit).replace("bf16", "fp32").replace("12100", "12900")
    sweep_dir = tmp_path / "sweep"
    (sweep_dir / "state").mkdir(parents=True)
    (sweep_dir / "state" / ("built." + commit[:12])).write_text(commit)  # the stand-ins need no build
    env = dict(os.environ, SWEEP_DIR=str(sweep_dir), SWEEP_RECORD_ROOT=str(rec), PYTHONPATH=PACKAGE, CALLS=str(calls),
               REGISTRY_SCRIPT=os.path.join(ROOT, "src", "hideseek_analysis", "scripts", "hideseek_registry.py"),
               PATH="/usr/bin:" + os.environ["PATH"])
    code = ("import sys; from hideseek_pipeline import cli, runner\n"
            "sweep = cli.make_sweep(%r, %r); sweep.checkout = %r\nsys.exit(runner.run(sweep) or 0)"
            % (ROOT, str(config_file(tmp_path, text)), str(repo)))
    return code, env, subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                                     timeout=120)


def fake_analysis(rec):
    """The records' checkout as the analysis's workspace, of stand-ins."""
    stand_in_workspace(rec)


def test_the_queue_trains_phase_by_phase_records_ships_and_keeps_each_phase_s_runs_at_once(tmp_path):
    """The queue itself, with a stand-in trainer in a worktree of a small repository: every run
    trained once, in order; two at once in the first phase, the later phase's run alone with its
    own threads; each recorded as a sweep run of its phase, analysed, and the median shipped."""
    repo = shell_trainer_repo(tmp_path)
    rec = make_records(tmp_path, {})
    fake_analysis(rec)
    # what `sweep partial` recorded of basic_seed0 before a machine went: gone once the run is recorded
    (rec / "docs" / "runs" / "basic_seed0" / "partial").mkdir(parents=True)
    (rec / "docs" / "runs" / "basic_seed0" / "partial" / "training_log.csv").write_text("steps\n")
    calls = tmp_path / "calls.txt"
    code, env, r = queue_in(tmp_path, repo, rec, TWO_PHASES, calls)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "every run of the queue is done" in r.stdout
    assert "basic_seed0: training from step 0 (phase first, slot 0, port" in r.stdout
    assert "1 learner thread; log" in r.stdout and "2 learner threads; log" in r.stdout
    events = [line.split() for line in calls.read_text().splitlines() if line.split()[0] in ("start", "end")]
    starts = [e[1] for e in events if e[0] == "start"]
    # two at once: the queue starts them in order, and either may write its first line first
    assert [set(starts[:2]), set(starts[2:4]), starts[4:]] == [
        {"basic_seed0", "slowerhider_seed0"}, {"basic_seed1", "slowerhider_seed1"}, ["basic_v3_gru_8m_seed0"]]
    at = {(e[0], e[1]): float(e[2]) for e in events}
    # the first phase ran two at once; the later phase's run started once every other had ended
    assert at[("start", "slowerhider_seed0")] < at[("end", "basic_seed0")]
    assert at[("start", "basic_seed1")] > min(at[("end", "basic_seed0")], at[("end", "slowerhider_seed0")])
    assert at[("start", "basic_v3_gru_8m_seed0")] > max(t for (k, n), t in at.items() if k == "end" and "v3" not in n)
    assert [line for line in calls.read_text().splitlines() if line.startswith("start basic_v3")][0].endswith(
        "threads=2 game=v3")
    entries = yaml.safe_load((rec / "policies" / "policies.yaml").read_text())
    assert entries["basic_v3_gru_8m_seed0"]["note"].startswith("sweep run (config/sweep.yaml), phase later, pinned at ")
    assert entries["basic_v3_gru_8m_seed0"]["game"] == "v3"
    assert (rec / "docs" / "runs" / "slowerhider_seed1" / "analysis" / "behaviour.csv").exists()
    assert not (rec / "docs" / "runs" / "basic_seed0" / "partial").exists()
    # the median of basic's two v2 runs (100 and 101 living steps: the lower) ships as basic.pt
    assert entries["basic_seed0"].get("weights") == "basic.pt" and "weights" not in entries["basic_seed1"]
    # the later phase, a budget check, ships nothing
    assert "weights" not in entries["basic_v3_gru_8m_seed0"] and not (rec / "policies" / "basic_gru_v3.pt").exists()
    # done means done: a second start trains nothing
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and calls.read_text().count("\nstart ") == len(starts) - 1


def test_a_pin_without_the_shell_trainer_trains_through_hideseek_pipeline_train_in_its_worktree(tmp_path):
    """A phase pinned after the shell trainer went: the queue runs `hideseek_pipeline train` with
    the pinned worktree as its workspace (its launch files and tools), its ports and precision."""
    repo = stand_in_workspace(tmp_path / "repo")
    rec = make_records(tmp_path, {})
    fake_analysis(rec)
    calls = tmp_path / "calls.txt"
    one = TWO_PHASES.split("  - {name: later")[0].replace("seeds: [0, 1]", "seeds: [0]").replace(
        "variants: [basic, slowerhider]", "variants: [basic]")
    _, _, r = queue_in(tmp_path, repo, rec, one, calls)
    assert r.returncode == 0, r.stdout + r.stderr
    launched = [line for line in calls.read_text().splitlines() if line.startswith("roslaunch")]
    assert launched[0].startswith("roslaunch -p 12900 hideseek_world train.launch variant:=basic game:=v2 seed:=0 "
                                  "steps:=2000000 network:=ff precision:=fp32")
    assert "hider_threads:=1" in launched[0]
    assert "-p 12901 hideseek_world evaluate.launch" in launched[1] and "-p 12902" in launched[2]
    e = yaml.safe_load((rec / "policies" / "policies.yaml").read_text())["basic_seed0"]
    assert e["command"].startswith("hideseek_pipeline train basic --seed 0 --steps 2000000")
    assert e["note"].startswith("sweep run (config/sweep.yaml), phase first, pinned at ")
    assert e["weights"] == "basic.pt" and (rec / "docs" / "runs" / "basic_seed0" / "analysis" / "behaviour.csv").exists()


def test_a_pause_while_a_run_is_evaluated_stays_out_of_its_recorded_paused_s(tmp_path, monkeypatch):
    """The sweep held the run 20 s in training and 60 s in each of its two evaluations after (three
    pauses booked into its paused_s file): the registry keeps wall_s and paused_s as the training
    gave them (the log's 123 s: 103 trained, 20 held), and the queue's log names the 120 s held in
    evaluation."""
    repo = stand_in_workspace(tmp_path / "repo")
    rec = make_records(tmp_path, {})
    fake_analysis(rec)
    held = tmp_path / "sweep" / "runs" / "basic_seed0" / "paused_s"
    held.parent.mkdir(parents=True)
    held.write_text("20\n")
    monkeypatch.setenv("EVAL_HELD", "60")  # the stand-in evaluate.launch books it into EVAL_HELD_FILE
    monkeypatch.setenv("EVAL_HELD_FILE", str(held))
    one = TWO_PHASES.split("  - {name: later")[0].replace("seeds: [0, 1]", "seeds: [0]").replace(
        "variants: [basic, slowerhider]", "variants: [basic]")
    _, _, r = queue_in(tmp_path, repo, rec, one, tmp_path / "calls.txt")
    assert r.returncode == 0, r.stdout + r.stderr
    assert held.read_text().split()[0] == str(20 + 60 * 2)  # both evaluations (greedy, sampled) were held
    e = yaml.safe_load((rec / "policies" / "policies.yaml").read_text())["basic_seed0"]
    assert (e["wall_s"], e["paused_s"]) == (103, 20)
    assert "basic_seed0: held 120 s more while it was evaluated after training: left out of its wall_s and of its " \
        "paused_s (20 s, held in training)" in r.stdout, r.stdout


def test_pauses_booked_after_a_run_s_last_checkpoint_come_off_its_paused_s_when_it_restarts(tmp_path):
    """A stop (or a crash) lost the training after basic_seed0's last checkpoint, and a 40 s pause
    in it; the run resumes from the checkpoint, whose log holds only the 30 s pause before it. The
    queue takes the 40 s off paused_s before training, so wall_s is the log's 123 s less 30."""
    repo = stand_in_workspace(tmp_path / "repo")
    rec = make_records(tmp_path, {})
    fake_analysis(rec)
    run = tmp_path / "sweep" / "runs" / "basic_seed0"
    run.mkdir(parents=True)
    now = time.time()
    (run / "checkpoint.pt").write_text("ckpt")
    os.utime(run / "checkpoint.pt", (now - 100, now - 100))
    (run / "paused_s").write_text("70\n")
    (run / "paused.log").write_text("%d 30\n%d 40\n" % (now - 200, now - 50))
    one = TWO_PHASES.split("  - {name: later")[0].replace("seeds: [0, 1]", "seeds: [0]").replace(
        "variants: [basic, slowerhider]", "variants: [basic]")
    _, _, r = queue_in(tmp_path, repo, rec, one, tmp_path / "calls.txt")
    assert r.returncode == 0, r.stdout + r.stderr
    assert "basic_seed0: 40 s of pauses after its last checkpoint left out of its paused_s" in r.stdout, r.stdout
    assert "basic_seed0: resuming from its checkpoint (phase" in r.stdout
    e = yaml.safe_load((rec / "policies" / "policies.yaml").read_text())["basic_seed0"]
    assert (e["wall_s"], e["paused_s"]) == (93, 30)


def test_a_run_restarting_without_a_checkpoint_keeps_none_of_its_pauses_and_old_totals_stay(tmp_path):
    """Dropping pauses reads paused.log: a run with no checkpoint (it starts afresh) keeps none of
    those it lists; a total booked before paused.log existed stays as it is."""
    sys.path.insert(0, PACKAGE)
    from hideseek_pipeline import control
    fresh = tmp_path / "fresh"
    fresh.mkdir()
    (fresh / "paused_s").write_text("50\n")
    (fresh / "paused.log").write_text("%d 20\n%d 30\n" % (time.time() - 60, time.time() - 30))
    assert control.drop_pauses_after_checkpoint(str(fresh)) == 50
    assert (fresh / "paused.lock").exists()  # taken, as resume() takes it to book a pause
    assert (fresh / "paused_s").read_text() == "0\n" and (fresh / "paused.log").read_text() == ""
    old = tmp_path / "old"
    old.mkdir()
    (old / "paused_s").write_text("600\n")
    assert control.drop_pauses_after_checkpoint(str(old)) == 0
    assert (old / "paused_s").read_text() == "600\n"


def test_the_held_time_in_training_is_read_from_an_older_pin_s_wall_s_recorded_as_text(tmp_path):
    """The shell trainer of an older pin records wall_s as text ('103'): the training's part of the
    held time is read from it all the same; without a log or a wall_s, all the held time counts."""
    rec = make_records(tmp_path, {"basic_seed0": ("basic", 0, 2000000, [100], [90])})
    sys.path.insert(0, os.path.join(ROOT, "src", "hideseek_analysis", "python"))
    from hideseek_analysis import registry as reg
    registry = str(rec / "policies" / "policies.yaml")
    stand_in = types.SimpleNamespace(records=types.SimpleNamespace(
        registry=reg, registry_path=registry, docs=lambda name, *parts: os.path.join(rec, "docs", "runs", name, *parts)))
    assert runner.held_in_training(stand_in, "basic_seed0", 140) == 140  # no log yet: all of it
    (rec / "docs" / "runs" / "basic_seed0" / "training_log.csv").write_text(
        "update,steps,wall_s,x\n1,1024,60.2,0\n2,2048,123.7,0\n")
    assert runner.held_in_training(stand_in, "basic_seed0", 140) == 140  # no wall_s recorded: all of it
    reg.record("basic_seed0", {"wall_s": "103"}, registry)
    assert runner.held_in_training(stand_in, "basic_seed0", 140) == 20
    assert runner.held_in_training(stand_in, "basic_seed0", 15) == 15  # never more than was held


def torch_archive(tag):
    """Bytes shaped as torch.jit.save writes an exported policy (a zip of data.pkl and code)."""
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w") as z:
        for name, text in (("archive/data.pkl", tag), ("archive/code/__torch__.py", "")):
            z.writestr(zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0)), text)  # the same bytes every time
    return out.getvalue()


def test_ship_takes_the_median_run_s_weights_from_git_history_only_where_they_replay_its_episodes(tmp_path):
    """The median run's weights left the machine, but it once shipped: `ship` takes the weights the
    newest commit shipping it holds, evaluates them again in the phase's pinned tree, and ships them
    only where every recorded episode replays. Weights that replay fewer stay aside, the shipped run
    stays, and the message says how many replayed; a run that never shipped has nothing to recover."""
    repo = stand_in_workspace(tmp_path / "repo")  # the pin: its evaluate.launch replays 321 living steps
    pinned_repo(repo)
    rec = make_records(tmp_path, {"basic_seed0": ("basic", 0, 2000000, [321], [300]),
                                  "basic_seed1": ("basic", 1, 2000000, [100], [90]),
                                  "basic_seed2": ("basic", 2, 2000000, [500], [400])})
    episodes = rec / "docs" / "runs" / "basic_seed0" / "episodes.csv"
    git = ["git", "-C", str(rec), "-c", "user.name=t", "-c", "user.email=t@t"]
    subprocess.run(["git", "init", "-q", str(rec)], check=True)
    registry = str(rec / "policies" / "policies.yaml")
    sys.path.insert(0, os.path.join(ROOT, "src", "hideseek_analysis", "python"))
    from hideseek_analysis import registry as reg
    for name in ("basic_seed0", "basic_seed2"):  # seed 0 shipped once, then seed 2 in its place
        (tmp_path / name).write_bytes(torch_archive(name))
        reg.ship(name, str(tmp_path / name), registry)
        subprocess.run(git + ["add", "-A"], check=True)
        subprocess.run(git + ["commit", "-qm", "ship " + name], check=True)
    shipped_seed0 = subprocess.check_output(git + ["rev-parse", "HEAD~1"], text=True).strip()
    assert reg.weights_in_history("basic_seed1", registry) is None
    assert reg.weights_in_history("basic_seed0", registry) == (shipped_seed0, torch_archive("basic_seed0"))
    commit = subprocess.check_output(["git", "-C", str(repo), "rev-parse", "HEAD"], text=True).strip()
    config = config_file(tmp_path, "precision: fp32\njobs: 1\nhider_threads: 1\nsteps: 2000000\nnetwork: ff\n"
                         "port: 12950\nphases:\n"
                         "  - {name: only, commit: '%s', game: v2, variants: [basic], seeds: [0, 1, 2]}\n" % commit)
    (tmp_path / "sweep" / "state").mkdir(parents=True)
    (tmp_path / "sweep" / "state" / ("built." + commit[:12])).write_text(commit)  # the stand-ins need no build
    env = dict(os.environ, SWEEP_DIR=str(tmp_path / "sweep"), SWEEP_RECORD_ROOT=str(rec), PYTHONPATH=PACKAGE,
               CALLS=str(tmp_path / "calls.txt"), PATH="/usr/bin:" + os.environ["PATH"])
    code = ("import sys; from hideseek_pipeline import cli, runner\n"
            "sweep = cli.make_sweep(%r, %r); sweep.checkout = %r\nsys.exit(runner.ship_all(sweep) or 0)"
            % (ROOT, str(config), str(repo)))
    weights = tmp_path / "sweep" / "runs" / "basic_seed0"

    def ship():
        r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
        assert r.returncode == 0, r.stdout + r.stderr
        return r.stdout
    # its recorded evaluation, of another machine: one episode off from what the pin replays
    episodes.write_text("seed,living_steps,outcome\n0,322,captured\n")
    # no retrain while history holds weights that were never checked
    r = sweep(tmp_path, rec, "retrain", "basic_seed0", config=config)
    assert r.returncode == 0 and "basic_seed0: not queued: its weights are in git commit %s" % shipped_seed0[:12] in (
        r.stdout), r.stdout + r.stderr
    # ... unless its recorded episodes are missing: nothing to check the weights against, so a retrain is queued
    recorded = episodes.read_text()
    episodes.unlink()
    said = ship()
    assert "episodes.csv is missing to check them against; not recovered ('hideseek_pipeline sweep retrain " \
        "basic_seed0' trains it again)" in said, said
    assert not (weights / "policy.recovered.pt").exists() and not (weights / "policy.pt").exists()
    r = sweep(tmp_path, rec, "retrain", "basic_seed0", config=config)
    assert r.returncode == 0 and "basic_seed0 queued for retraining" in r.stdout, r.stdout + r.stderr
    (tmp_path / "sweep" / "state" / "retrain").unlink()
    episodes.write_text(recorded)
    # the episode off: not recovered, nothing shipped in its place
    said = ship()
    assert "basic_seed0: its weights are not here but are in git commit %s" % shipped_seed0[:12] in said, said
    assert "replay 0 of its 1 recorded episodes: not recovered" in said, said
    assert "basic_seed0, but its weights" in said and "basic_seed2 stays shipped" in said, said
    assert reg.shipped("basic", game="v2", registry=registry)[0] == "basic_seed2"
    assert (weights / "policy.recovered.pt").read_bytes() == torch_archive("basic_seed0")
    assert not (weights / "policy.pt").exists()
    assert "roslaunch -p 13040 hideseek_world evaluate.launch variant:=basic game:=v2" in (
        tmp_path / "calls.txt").read_text()
    # once the check has failed, a retrain may be queued
    r = sweep(tmp_path, rec, "retrain", "basic_seed0", config=config)
    assert r.returncode == 0 and "basic_seed0 queued for retraining" in r.stdout, r.stdout + r.stderr
    (tmp_path / "sweep" / "state" / "retrain").unlink()
    # the recorded evaluation: every episode replays, and the weights ship as the run's
    episodes.write_text("seed,living_steps,outcome\n0,321,captured\n")
    said = ship()
    assert "basic_seed0: weights recovered from git commit %s; they replay all 1 recorded episodes" % (
        shipped_seed0[:12]) in said, said
    assert "shipped basic_seed0 as the median run of basic (was basic_seed2)" in said, said
    name, path = reg.shipped("basic", game="v2", registry=registry)
    assert name == "basic_seed0" and open(path, "rb").read() == torch_archive("basic_seed0")
    assert (weights / "policy.pt").read_bytes() == torch_archive("basic_seed0")
    assert (weights / "recovered_from").read_text().strip() == shipped_seed0
    # the records' own evaluation is untouched: the check played into a scratch folder
    assert episodes.read_text() == "seed,living_steps,outcome\n0,321,captured\n"
    assert "already shipped" in ship()


def test_a_worktree_whose_link_to_a_new_checkout_is_lost_is_linked_again_with_its_build_kept(tmp_path, monkeypatch,
                                                                                              capsys):
    """The checkout is cloned anew (its .git/worktrees/ gone) while ~/hideseek_sweep stays: the
    pinned tree is linked again at its pin, its build kept, rather than refused, and a relink that
    stopped half-way is finished by the next start; a tree whose files are not the pin's is still
    refused."""
    repo = shell_trainer_repo(tmp_path)
    commit = pinned_repo(repo)
    sweep_dir = tmp_path / "sweep"
    (sweep_dir / "state").mkdir(parents=True)
    (sweep_dir / "state" / ("built." + commit[:12])).write_text(commit)
    monkeypatch.setenv("SWEEP_DIR", str(sweep_dir))
    from hideseek_pipeline import cli
    sweep = cli.make_sweep(ROOT, str(config_file(tmp_path, TWO_PHASES.replace("0123456789ab", commit))))
    sweep.checkout = str(repo)
    phase = sweep.config.phases[0]
    tree = runner.prepare_tree(sweep, phase)
    (repo / ".git" / "info" / "exclude").write_text("build/\n")
    os.makedirs(os.path.join(tree, "build"))
    open(os.path.join(tree, "build", "stamp"), "w").write("built\n")

    def clean_at_the_pin():
        assert subprocess.check_output(["git", "-C", tree, "rev-parse", "HEAD"], text=True).strip() == commit
        assert subprocess.check_output(["git", "-C", tree, "status", "--porcelain"], text=True) == ""
        assert open(os.path.join(tree, "build", "stamp")).read() == "built\n"
        assert not os.path.exists(tree + ".link")

    subprocess.run(["rm", "-rf", str(repo / ".git" / "worktrees")], check=True)
    assert subprocess.run(["git", "-C", tree, "rev-parse", "HEAD"], capture_output=True).returncode != 0
    # and a relink stopped before the tree took its new link left the scratch link behind
    subprocess.run(["git", "-C", str(repo), "worktree", "add", "-q", "--no-checkout", "--detach", tree + ".link",
                    commit], check=True)
    capsys.readouterr()
    assert runner.prepare_tree(sweep, phase) == tree
    said = capsys.readouterr().out
    assert "lost its link to the checkout" in said and "linking it again at %s, its build kept" % commit[:12] in said
    clean_at_the_pin()
    assert runner.prepare_tree(sweep, phase) == tree  # linked: nothing more to do
    # a relink stopped before its index was read: the next start reads it
    index = subprocess.check_output(["git", "-C", tree, "rev-parse", "--git-path", "index"], text=True).strip()
    os.remove(os.path.join(tree, index))
    assert runner.prepare_tree(sweep, phase) == tree
    clean_at_the_pin()
    # the link lost again, and a file of the tree no longer the pin's: linked, then refused
    subprocess.run(["rm", "-rf", str(repo / ".git" / "worktrees")], check=True)
    open(os.path.join(tree, "scripts", "helper.py"), "w").write("VALUE = 2\n")
    with pytest.raises(runner.SweepError, match="has uncommitted changes"):
        runner.prepare_tree(sweep, phase)


def test_a_later_phase_s_tree_is_built_only_when_its_first_run_could_start_and_a_failed_build_fails_only_its_runs(
        tmp_path):
    """A later phase's pin is built once its first run could start (here, once the first phase's
    run is done: the later phase trains alone), not before the first phase trains (a session that
    never reaches it spends nothing); when its build fails, the queue names the phase and its runs,
    goes on with the phase after it, and records what trained."""
    repo = shell_trainer_repo(tmp_path)
    unbuildable = pinned_repo(repo)  # no scripts/env.sh, no catkin workspace: its build fails
    rec = make_records(tmp_path, {})
    fake_analysis(rec)
    calls = tmp_path / "calls.txt"
    text = TWO_PHASES.replace("seeds: [0, 1]", "seeds: [0]").replace(
        "variants: [basic, slowerhider]", "variants: [basic]").replace(
        'name: later, commit: "0123456789ab"', 'name: later, commit: "%s"' % unbuildable) + (
        '  - {name: after, commit: "0123456789ab", game: v3, variants: [basic], seeds: [0], ship: false}\n')
    _, _, r = queue_in(tmp_path, repo, rec, text, calls)  # the first phase: a commit after it, marked built
    assert r.returncode == 0, r.stdout + r.stderr
    out = r.stdout
    assert out.index("basic_seed0: done") < out.index("building the worktree at %s" % unbuildable[:12])
    assert re.search(r"phase later: the worktree's build failed: \S+\n", out), out
    assert ("phase later: its tree at %s did not build; its runs are not started (basic_v3_gru_8m_seed0)"
            % unbuildable[:12]) in out
    assert out.index("did not build") < out.index("basic_v3_seed0: training") < out.index("basic_v3_seed0: done")
    assert "nothing left to start: 1 runs failed" in out
    entries = yaml.safe_load((rec / "policies" / "policies.yaml").read_text())
    assert "basic_seed0" in entries and "basic_v3_seed0" in entries and "basic_v3_gru_8m_seed0" not in entries


def test_a_phase_kept_for_a_session_s_beginning_waits_for_the_next_start_while_the_phases_after_it_train(tmp_path):
    """start_within_min: once the queue has run longer than that, the phase's run is not started
    (said by name, once the queue reaches it, not while runs before it wait) and the phase after it
    trains meanwhile; the next start, within the window (here SWEEP_START_WITHIN_MIN, every phase's
    override), trains it."""
    repo = shell_trainer_repo(tmp_path)
    rec = make_records(tmp_path, {})
    fake_analysis(rec)
    calls = tmp_path / "calls.txt"
    # the first phase's runs, one at a time, take a second at least each (the stand-in sleeps 1 s): the
    # window, 0.3 s, has passed while basic_seed1 and basic_seed2 still wait; the late run is reached
    # once basic_seed2 has started, after basic_seed1 is done (its process says so before it ends)
    text = TWO_PHASES.replace('seeds: [0, 1]}', 'seeds: [0, 1, 2], jobs: 1}').replace(
        "variants: [basic, slowerhider]", "variants: [basic]").replace(
        "jobs: 1, hider_threads: 2, ship: false}", "jobs: 1, hider_threads: 2, ship: false, start_within_min: 0.005}\n"
        '  - {name: after, commit: "0123456789ab", game: v3, variants: [basic], seeds: [0], ship: false}')
    code, env, r = queue_in(tmp_path, repo, rec, text, calls)
    assert r.returncode == 0, r.stdout + r.stderr
    starts = [line.split()[1] for line in calls.read_text().splitlines() if line.startswith("start ")]
    assert starts == ["basic_seed0", "basic_seed1", "basic_seed2", "basic_v3_seed0"]
    said = ("basic_v3_gru_8m_seed0: not started (phase later starts a run only within 0.005 min of the queue's "
            "start: start the queue at a session's beginning); the queue goes on with the runs after it")
    assert r.stdout.count(said) == 1
    assert r.stdout.index("basic_seed1: done") < r.stdout.index(said), r.stdout
    assert "nothing left to start now: basic_v3_gru_8m_seed0 waits for the queue's next start" in r.stdout
    assert "failed" not in r.stdout
    r = subprocess.run([sys.executable, "-c", code], env=dict(env, SWEEP_START_WITHIN_MIN="5"), capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == 0 and "every run of the queue is done" in r.stdout, r.stdout + r.stderr
    starts = [line.split()[1] for line in calls.read_text().splitlines() if line.startswith("start ")]
    assert starts == ["basic_seed0", "basic_seed1", "basic_seed2", "basic_v3_seed0", "basic_v3_gru_8m_seed0"]


SEEKER_PHASE = """
precision: bf16
jobs: 1
hider_threads: 2
steps: 2000000
network: ff
port: 12100
phases:
  - {name: demo, commit: "0123456789ab", game: v2, role: seeker, variants: [basic], seeds: [0]}
"""


def test_a_seeker_s_phase_trains_seekers_against_the_shipped_hider_evaluates_them_as_seekers_and_ships_nothing(
        tmp_path):
    repo = stand_in_workspace(tmp_path / "repo")
    rec = make_records(tmp_path, {})
    (rec / "policies" / "basic.pt").write_text("hider weights")
    (rec / "policies" / "policies.yaml").write_text(
        "basic_seed2: {variant: basic, network: ff, game: v2, training_seed: 2, steps: 2048, weights: basic.pt}\n")
    fake_analysis(rec)
    calls = tmp_path / "calls.txt"
    code, env, r = queue_in(tmp_path, repo, rec, SEEKER_PHASE, calls)
    assert r.returncode == 0, r.stdout + r.stderr
    launched = [line for line in calls.read_text().splitlines() if line.startswith("roslaunch")]
    assert "train.launch" in launched[0] and "role:=seeker" in launched[0]
    assert "opponent:=%s" % (rec / "policies" / "basic.pt") in launched[0]
    assert all("evaluate.launch" in line for line in launched[1:]) and len(launched) == 11
    e = yaml.safe_load((rec / "policies" / "policies.yaml").read_text())["basic_seeker_seed0"]
    assert e["role"] == "seeker" and e["note"].startswith("sweep run (config/sweep.yaml), phase demo, pinned at ")
    assert "weights" not in e and not (rec / "docs" / "runs" / "basic_seeker_seed0" / "analysis").exists()
    assert "basic_seeker_seed0: done: captures basic: learned 1.000, scripted 1.000" in r.stdout
    status = sweep(tmp_path, rec, "status", config=config_file(tmp_path, SEEKER_PHASE.replace("bf16", "fp32")),
                   SWEEP_DIR=str(tmp_path / "sweep"))
    assert rows(status.stdout) == [["basic_seeker_seed0", "done"]]
    # done means done: a second start trains nothing
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and calls.read_text().count("train.launch") == 1


SELFPLAY_PHASE = SEEKER_PHASE.replace("role: seeker", "role: selfplay, generations: 2")


def test_a_self_play_phase_trains_both_sides_in_turn_then_records_its_cross_play_and_its_hiders(tmp_path):
    repo = stand_in_workspace(tmp_path / "repo")
    (repo / "config").mkdir()
    (repo / "config" / "ppo.yaml").write_text("learning_rate: 0.0003\nanneal_learning_rate: true\n")
    rec = make_records(tmp_path, {"basic_seed0": ("basic", 0, 2000896, [400, 500], [300]),  # the steps trained
                                  "basic_seed1": ("basic", 1, 2000000, [100, 200], [300])})
    fake_analysis(rec)
    calls = tmp_path / "calls.txt"
    phase = SELFPLAY_PHASE.replace("generations: 2", "generations: 2, latest_share: 0")
    code, env, r = queue_in(tmp_path, repo, rec, phase, calls)
    assert r.returncode == 0, r.stdout + r.stderr
    saved = yaml.safe_load((tmp_path / "sweep" / "runs" / "basic_selfplay_seed0" / "generations.yaml").read_text())
    assert [g["latest_share"] for g in saved["generations"]] == [0.0] * 4  # the phase's share reached the draws
    launched = [line for line in calls.read_text().splitlines() if line.startswith("roslaunch")]
    trained = [line for line in launched if "train.launch" in line]
    # seeker, hider, seeker, hider: 1M steps a side and generation, 2M in all
    assert [re.search("role:=(\\w+)", t).group(1) for t in trained] == ["seeker", "hider"] * 2
    assert [re.search("steps:=(\\d+)", t).group(1) for t in trained] == ["1000000", "1000000", "2000000", "2000000"]
    # the cross-play: 3 hiders (random, g001, g002) x 4 seekers (scripted, random, g001, g002); then the
    # first and last hider against the scripted seeker
    evaluations = [line for line in launched if "evaluate.launch" in line]
    assert len(evaluations) == 12 + 2 and "hider_g002.pt" in evaluations[-1] and "seeker_mode" not in evaluations[-1]
    docs = rec / "docs" / "runs" / "basic_selfplay_seed0"
    for f in ("crossplay.csv", "crossplay.md", "crossplay.png", "learning_curves.png", "hider_training_log.csv",
              "seeker_training_log.csv", "generations.yaml", "hider_g001/evaluation.csv",
              "hider_g002/trajectories.png", "hider_g002/analysis/behaviour.csv", "trajectories_g001.png",
              "trajectories_g002.png"):
        assert (docs / f).is_file(), f
    assert not (docs / "hider_g001" / "analysis").exists()
    # the self-play's own games: generation k's hider against generation k's seeker
    played = [line for line in calls.read_text().splitlines() if line.startswith("play_episodes")]
    assert any("hider_g002.pt" in p and p.endswith("--seeker-policy %s" % (
        tmp_path / "sweep" / "runs" / "basic_selfplay_seed0" / "generations" / "seeker_g002.pt")) for p in played)
    summary = (docs / "selfplay.md").read_text()
    assert "| basic_seed0 | against the scripted seeker only | 450.0 |" in summary
    assert "lives 321.0 steps against the scripted seeker: within their range of the 2 hiders" in summary
    assert "| measure | hider_g002 (self-play) | basic_seed0 | basic_seed1 |" in summary
    assert str(tmp_path) not in summary
    # nothing entered the registry, nothing shipped
    assert set(yaml.safe_load((rec / "policies" / "policies.yaml").read_text())) == {"basic_seed0", "basic_seed1"}
    status = sweep(tmp_path, rec, "status", config=config_file(tmp_path, SELFPLAY_PHASE.replace("bf16", "fp32")),
                   SWEEP_DIR=str(tmp_path / "sweep"))
    assert rows(status.stdout) == [["basic_selfplay_seed0", "done"]]
    # done means done: a second start trains and plays nothing
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and calls.read_text().count("train.launch") == 4


def test_partial_records_an_unfinished_self_play_s_generations_and_both_sides_logs_and_curves(tmp_path):
    """Before a machine goes, a self-play cut off mid-way leaves what it has learned so far in its
    records' partial/: its generations.yaml and each side's training log and curve, no weights."""
    rec = make_records(tmp_path, {"basic_seed0": ("basic", 0, 2000000, [30], [30])})
    header = ("update,steps,wall_s,steps_per_s,episodes,mean_length,mean_return,policy_loss,value_loss,entropy,"
              "approx_kl,clip_fraction,learning_rate\n")
    out = tmp_path / "sweep" / "runs" / "basic_selfplay_seed0"
    logs = {}
    for role, updates in (("seeker", 40), ("hider", 12)):
        (out / role).mkdir(parents=True)
        logs[role] = header + "".join("%d,%d,%.1f,450,%d,%d,-0.9,0,0,1.6,0,0,0.0003\n" % (
            u, 1024 * u, 2.3 * u, 10 * u, 40 + u) for u in range(1, updates + 1))
        (out / role / "training_log.csv").write_text(logs[role])
        (out / role / "checkpoint.pt").write_bytes(b"x")
    (out / "generations").mkdir()
    (out / "generations" / "seeker_g001.pt").write_bytes(b"x")
    generations = "generations:\n- {role: seeker, generation: 1, checkpoint: generations/seeker_g001.pt}\n"
    (out / "generations.yaml").write_text(generations)
    r = sweep(tmp_path, rec, "partial", config=config_file(tmp_path, SELFPLAY_PHASE))
    assert r.returncode == 0, r.stdout + r.stderr
    partial = rec / "docs" / "runs" / "basic_selfplay_seed0" / "partial"
    assert (partial / "generations.yaml").read_text() == generations
    for role in ("seeker", "hider"):
        assert (partial / ("%s_training_log.csv" % role)).read_text() == logs[role]
        assert (partial / ("%s_learning_curve.png" % role)).read_bytes()[:4] == b"\x89PNG"
    assert sorted(os.listdir(partial)) == ["generations.yaml", "hider_learning_curve.png", "hider_training_log.csv",
                                           "seeker_learning_curve.png", "seeker_training_log.csv"]
    assert "basic_selfplay_seed0 (seeker): 40,960 of 2,000,000 steps, 92 s of training" in r.stdout
    assert "generations saved: seeker_g001 (of 2 a side)" in r.stdout and "resume only on this machine" in r.stdout
    assert r.stdout.strip().splitlines()[-1].startswith("sweep: 1 unfinished runs recorded")
    status = sweep(tmp_path, rec, "status", config=config_file(tmp_path, SELFPLAY_PHASE),
                   SWEEP_DIR=str(tmp_path / "sweep"))
    assert "partial   generations saved: seeker_g001 (of 2 a side)" in status.stdout, status.stdout


def test_a_self_play_phase_is_named_apart_and_refuses_what_it_cannot_do():
    config = sweep_config.load(_write(SELFPLAY_PHASE.replace("game: v2", "game: v3")), ["basic"], ["basic"], "v2")
    assert [r.name for r in config.runs()] == ["basic_selfplay_v3_seed0"]
    assert (config.phases[0].ship, config.phases[0].generations, config.phases[0].latest_share) == (False, 2, None)
    config = sweep_config.load(_write(SELFPLAY_PHASE.replace("generations: 2", "generations: 2, latest_share: 0")),
                               ["basic"], ["basic"], "v2")
    assert config.phases[0].latest_share == 0.0 and [r.name for r in config.runs()] == ["basic_selfplay_seed0"]
    # a share in the name: two self-plays that draw differently never share a folder or records
    both = SELFPLAY_PHASE + "  - {name: latest, commit: \"0123456789ab\", game: v3, role: selfplay, latest_share: 0.5, " \
                            "variants: [basic], seeds: [0]}\n"
    config = sweep_config.load(_write(both), ["basic"], ["basic"], "v2")
    assert [r.name for r in config.runs()] == ["basic_selfplay_seed0", "basic_selfplay_v3_latest50_seed0"]
    for change, message in (("generations: 2", "generations: 3"), "2000000 is not a whole number of generations (3)"), \
            (("role: selfplay", "role: selfplay, ship: true"), "a self-play phase ships nothing"), \
            (("role: selfplay", "role: selfplay, network: gru"), "a self-play phase trains feed-forward learners"), \
            (("role: selfplay", "role: selfplay, latest_share: 1.5"), "latest_share: '1.5' is not a number from 0 to 1"), \
            (("role: selfplay", "role: seeker, latest_share: 0.5"), "only a self-play phase draws its opponents"):
        try:
            sweep_config.load(_write(SELFPLAY_PHASE.replace(*change)), ["basic"], ["basic"], "v2")
            assert False, change
        except sweep_config.ConfigError as e:
            assert message in str(e)


def test_a_seeker_s_phase_is_named_apart_and_ships_nothing():
    config = sweep_config.load(_write(SEEKER_PHASE), ["basic"], ["basic"], "v2")
    assert [r.name for r in config.runs()] == ["basic_seeker_seed0"]
    assert config.phases[0].ship is False and config.phases[0].role == "seeker"
    config = sweep_config.load(_write(SEEKER_PHASE.replace("game: v2", "game: v3, opponent: scripted/flee")),
                               ["basic"], ["basic"], "v2")
    assert [r.name for r in config.runs()] == ["basic_seeker_v3_seed0"] and config.phases[0].opponent == "scripted/flee"
    for change, message in (("role: seeker", "role: seeker, ship: true"), "a seeker's phase ships nothing"), \
            (("role: seeker", "role: referee"), "role: 'referee' is not one of hider, seeker"):
        try:
            sweep_config.load(_write(SEEKER_PHASE.replace(*change)), ["basic"], ["basic"], "v2")
            assert False, change
        except sweep_config.ConfigError as e:
            assert message in str(e)


def test_a_run_stopped_by_a_signal_is_said_to_resume_not_to_have_failed():
    """sweep stop interrupts each run's trainer: the queue's log says it stopped and resumes, where
    a trainer's own error is a failure with its exit status."""
    said = runner.ended_early("basic_v3_seed4", -signal.SIGINT, "/s/logs/basic_v3_seed4.log")
    assert said.startswith("basic_v3_seed4: stopped (SIGINT); it resumes from its last checkpoint") and "fail" not in said
    assert "stopped (SIGTERM)" in runner.ended_early("basic_v3_seed4", -signal.SIGTERM, "l")
    # hideseek_pipeline train catches the SIGINT, lets the training write its checkpoint, and exits 130
    assert "stopped (SIGINT)" in runner.ended_early("basic_v3_seed4", 130, "l")
    # stopped before its first checkpoint (every 300 s), it has nothing to resume from
    said = runner.ended_early("basic_v3_8m_seed0", 130, "l", has_checkpoint=False)
    assert "no checkpoint yet, so it starts again from step 0" in said and "resumes" not in said
    assert runner.ended_early("basic_v3_seed4", 1, "l") == "basic_v3_seed4: failed (exit 1); see l"
    # SIGKILL is no stop the queue sends: something else killed the trainer
    assert "failed (exit -9)" in runner.ended_early("basic_v3_seed4", -signal.SIGKILL, "l")
