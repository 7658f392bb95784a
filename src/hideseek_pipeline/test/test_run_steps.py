"""hideseek_pipeline train / evaluate / analyze against a stand-in workspace (fake roslaunch, resolver,
exporter, player and plotting scripts): what each step runs, what it records and what it refuses;
no ROS master and no training. The real tools' outputs were checked against the shell scripts these
steps replaced (docs/architecture.md, "The scripts' move")."""
import hashlib
import os
import signal
import socket
import subprocess
import sys
import time

import pytest
import yaml
from stand_ins import stand_in_workspace

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
PACKAGE = os.path.join(ROOT, "src", "hideseek_pipeline", "python")

@pytest.fixture
def ws(tmp_path):
    """A workspace of stand-ins, and a records checkout with an empty registry."""
    w = stand_in_workspace(tmp_path / "ws")
    rec = tmp_path / "records"
    (rec / "policies").mkdir(parents=True)
    (rec / "policies" / "policies.yaml").write_text("# runs\n")
    return w, rec, tmp_path / "calls.txt"


def pipeline(w, rec, calls, *args, **env):
    e = dict(os.environ, PYTHONPATH=PACKAGE, CALLS=str(calls), PATH="/usr/bin:" + os.environ["PATH"])
    e.update(env)
    return subprocess.run([sys.executable, "-m", "hideseek_pipeline"] + list(args) +
                          ["--workspace", str(w), "--record-root", str(rec)], env=e, capture_output=True, text=True,
                          timeout=120)


def entries(rec):
    return yaml.safe_load((rec / "policies" / "policies.yaml").read_text())


def test_train_records_the_run_evaluates_it_and_keeps_the_paused_time_apart(ws, tmp_path):
    w, rec, calls = ws
    paused = tmp_path / "paused_s"
    paused.write_text("20\n")
    r = pipeline(w, rec, calls, "train", "basic", "--seed", "3", "--steps", "4096", "--runs-dir",
                 str(tmp_path / "runs"), "--hider-threads", "1", "--eval-modes", "greedy", "sampled",
                 "--paused-file", str(paused), "--port", "12345")
    assert r.returncode == 0, r.stdout + r.stderr
    e = entries(rec)["basic_4096_seed3"]
    assert (e["variant"], e["network"], e["game"], e["training_seed"], e["steps"]) == ("basic", "ff", "v2", 3, 4096)
    assert e["wall_s"] == 103 and e["paused_s"] == 20 and e["precision"] == "fp32"
    assert e["command"] == ("hideseek_pipeline train basic --seed 3 --steps 4096 --network ff --name basic_4096_seed3 "
                            "--hider-threads 1")
    launched = [line for line in calls.read_text().splitlines() if line.startswith("roslaunch")]
    assert launched[0].startswith("roslaunch -p 12345 hideseek_world train.launch variant:=basic game:=v2 seed:=3")
    assert "hider_threads:=1" in launched[0]
    # greedy and sampled evaluations on the run's port + 1000 and the next, naming the run, not its weights
    assert "-p 13345 hideseek_world evaluate.launch" in launched[1] and "greedy:=true" in launched[1]
    assert "-p 13346 hideseek_world evaluate.launch" in launched[2] and "greedy:=false" in launched[2]
    docs = rec / "docs" / "runs" / "basic_4096_seed3"
    assert "basic_4096_seed3" in (docs / "evaluation.csv").read_text()
    assert "policy.pt" not in (docs / "evaluation.md").read_text()
    for f in ("training_log.csv", "learning_curve.png", "trajectories.png", "sampled/evaluation.csv"):
        assert (docs / f).is_file(), f
    assert (tmp_path / "runs" / "basic_4096_seed3" / "policy.pt").read_text() == "ckpt\n"


def test_a_taken_port_is_refused_before_anything_starts(ws, tmp_path):
    """roslaunch -p joins a master already listening at its port, so a training or an evaluation on a
    taken port would share a graph with whatever holds it: each step refuses, naming the port."""
    w, rec, calls = ws
    (rec / "policies" / "policies.yaml").write_text(
        "basic_v3_seed0: {variant: basic, network: ff, game: v3, training_seed: 0, steps: 2048}\n")
    weights = tmp_path / "policy.pt"
    weights.write_text("w")
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as held:
        held.bind(("127.0.0.1", 0))
        held.listen(1)
        port = held.getsockname()[1]
        for args in (["train", "basic", "--steps", "4096", "--runs-dir", str(tmp_path / "runs"), "--port", str(port)],
                     ["evaluate", "basic_v3_seed0", str(weights), "--port", str(port)]):
            r = pipeline(w, rec, calls, *args)
            assert r.returncode == 1, (args, r.stdout + r.stderr)
            assert "port %d is taken" % port in r.stderr and "nothing was started" in r.stderr, r.stderr
            assert not calls.exists() or "roslaunch" not in calls.read_text(), args
    assert not (tmp_path / "runs" / "basic_4096_seed0" / "training_log.csv").exists()
    r = pipeline(w, rec, calls, "evaluate", "basic_v3_seed0", str(weights), "--port", str(port))
    assert r.returncode == 0, r.stdout + r.stderr  # the port free again: the same command runs


def test_a_run_that_stops_short_records_nothing(ws, tmp_path):
    w, rec, calls = ws
    r = pipeline(w, rec, calls, "train", "basic", "--steps", "4096", "--runs-dir", str(tmp_path / "runs"),
                 STOP_AT="2048")
    assert r.returncode == 1 and "stopped at 2048 of 4096 steps" in r.stderr and "nothing recorded" in r.stderr
    assert not entries(rec)


def test_a_run_a_ctrl_c_stops_says_it_resumes_and_exits_130(ws, tmp_path):
    """Ctrl-C at the terminal reaches the whole process group: roslaunch stops the training, which
    writes its checkpoint, and the pipeline, left to wait for it, says where the run stopped and
    exits 130, which the sweep's queue reads as a stop, not a failure."""
    w, rec, calls = ws
    hold = tmp_path / "training"
    e = dict(os.environ, PYTHONPATH=PACKAGE, CALLS=str(calls), PATH="/usr/bin:" + os.environ["PATH"], HOLD=str(hold),
             STOP_AT="2048")
    p = subprocess.Popen([sys.executable, "-m", "hideseek_pipeline", "train", "basic", "--name", "mine", "--steps",
                          "4096", "--runs-dir", str(tmp_path / "runs"), "--workspace", str(w), "--record-root",
                          str(rec)], env=e, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True)
    try:
        deadline = time.time() + 60
        while not hold.exists() and time.time() < deadline and p.poll() is None:
            time.sleep(0.1)
        assert hold.exists(), p.communicate()
        os.killpg(p.pid, signal.SIGINT)
        _, err = p.communicate(timeout=60)
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
    assert p.returncode == 130, err
    assert "mine stopped at 2048 of 4096 steps" in err and "the same command resumes it from its checkpoint" in err
    assert not entries(rec)


def test_train_refuses_a_bad_name_an_unknown_variant_and_another_game_s_run(ws, tmp_path):
    w, rec, calls = ws
    runs = str(tmp_path / "runs")
    r = pipeline(w, rec, calls, "train", "basic", "--name", "../x", "--runs-dir", runs)
    assert r.returncode == 1 and "must be a plain file name" in r.stderr
    r = pipeline(w, rec, calls, "train", "nosuchvariant", "--runs-dir", runs)
    assert r.returncode == 1 and "no variant 'nosuchvariant'" in r.stderr
    (rec / "policies" / "policies.yaml").write_text(
        "basic_seed0: {variant: basic, network: ff, game: v3, training_seed: 0, steps: 2048}\n")
    r = pipeline(w, rec, calls, "train", "basic", "--runs-dir", runs, "--game", "v2")
    assert r.returncode == 1 and "recorded as a run of game v3" in r.stderr and "this is game v2" in r.stderr
    assert not calls.exists() or "train.launch" not in calls.read_text()


def test_an_unnamed_run_is_named_as_the_sweep_names_it_and_never_takes_another_run_s_name(ws, tmp_path):
    """Unnamed, a run carries in its name what tells it apart (as the sweep's runs do): `train basic
    --seed 0` on v3 is basic_v3_seed0 beside v2's basic_seed0, and a run of another budget on v3 is
    basic_v3_<budget>_seed0, so it never resumes or overwrites v3's 2M run. A name the registry holds
    for another network (or game, variant, role) is refused."""
    w, rec, calls = ws
    (rec / "policies" / "policies.yaml").write_text(
        "basic_seed0: {variant: basic, network: ff, game: v2, training_seed: 0, steps: 2048}\n"
        "basic_v3_seed0: {variant: basic, network: ff, game: v3, training_seed: 0, steps: 2000896}\n")
    r = pipeline(w, rec, calls, "train", "basic", "--seed", "0", "--steps", "4096", "--game", "v3",
                 "--runs-dir", str(tmp_path / "runs"), "--eval-modes", "greedy")
    assert r.returncode == 0, r.stdout + r.stderr
    e = entries(rec)
    assert e["basic_v3_4096_seed0"]["game"] == "v3" and e["basic_seed0"]["game"] == "v2"
    assert e["basic_v3_seed0"]["steps"] == 2000896  # v3's 2M run untouched
    assert "--name basic_v3_4096_seed0" in e["basic_v3_4096_seed0"]["command"]
    assert (tmp_path / "runs" / "basic_v3_4096_seed0" / "policy.pt").is_file()
    assert not (tmp_path / "runs" / "basic_v3_seed0").exists()
    calls.unlink()
    r = pipeline(w, rec, calls, "train", "basic", "--seed", "0", "--network", "gru", "--name", "basic_v3_seed0",
                 "--game", "v3", "--runs-dir", str(tmp_path / "runs"))
    assert r.returncode == 1 and "basic_v3_seed0 is recorded as a run of network ff" in r.stderr
    assert "this is network gru: name the run otherwise" in r.stderr
    assert not calls.exists() or "train.launch" not in calls.read_text()


def test_the_sweep_s_runs_and_a_recorded_run_s_seed_budget_and_role_are_not_taken_over(ws, tmp_path):
    """An unnamed run does not take the name of a sweep run, recorded (its note) or still to train
    (config/sweep.yaml); a named one does not train a recorded run under another training seed,
    budget or role. Each is refused before anything trains, and the records are left as they were."""
    w, rec, calls = ws
    subprocess.run(["cp", "-r", os.path.join(ROOT, "config"), str(rec / "config")], check=True)
    registry = ("basic_v3_seed0: {variant: basic, network: ff, game: v3, training_seed: 0, steps: 2000896, "
                "note: 'sweep run (config/sweep.yaml), phase v3_ff, pinned at 3a74733b91ed'}\n"
                "basic_seeker_v3_seed0: {variant: basic, network: ff, game: v3, training_seed: 0, steps: 2000896, "
                "role: seeker}\n")
    (rec / "policies" / "policies.yaml").write_text(registry)
    runs = str(tmp_path / "runs")
    for args, said in (
            ([], "basic_v3_seed0 is a run of the sweep (config/sweep.yaml), which trains and records it: give yours "
                 "a name of its own with --name"),
            (["--steps", "8000000"], "basic_v3_8m_seed0 is a run of the sweep"),  # v3_8m's, not yet trained
            (["--name", "basic_v3_seed0", "--steps", "8000000"],
             "basic_v3_seed0 is recorded with 2000896 steps trained (policies/policies.yaml); this run's budget is "
             "8000000 steps: name the run otherwise"),
            (["--name", "basic_v3_seed0", "--seed", "1"],
             "basic_v3_seed0 is recorded as a run of training seed 0 (policies/policies.yaml); this is training "
             "seed 1"),
            (["--name", "basic_seeker_v3_seed0"], "recorded as a run of role seeker (policies/policies.yaml); this "
                                                  "is role hider")):
        r = pipeline(w, rec, calls, "train", "basic", "--game", "v3", "--runs-dir", runs, *args)
        assert r.returncode == 1 and said in r.stderr, (args, r.stderr)
    assert not calls.exists() or "train.launch" not in calls.read_text()
    assert (rec / "policies" / "policies.yaml").read_text() == registry
    r = pipeline(w, rec, calls, "train", "basic", "--game", "v3", "--steps", "4096", "--name", "my_basic",
                 "--runs-dir", runs, "--eval-modes", "greedy")
    assert r.returncode == 0, r.stdout + r.stderr
    assert entries(rec)["my_basic"]["steps"] == 4096


def test_an_unnamed_run_takes_the_name_the_sweep_gives_the_same_run():
    sys.path.insert(0, PACKAGE)
    from hideseek_pipeline import sweep_config
    from hideseek_pipeline.train import TrainOptions
    for kw, game in ((dict(steps=8_000_000), "v3"), (dict(network="gru", seed=2), "v3"), (dict(role="seeker"), "v3"),
                     (dict(steps=500_000, network="gru", role="seeker", seed=1), "v2"), (dict(), "v2")):
        o = TrainOptions("basic", **kw)
        assert o.run_name(game) == sweep_config.run_name("basic", o.seed, game, o.network, o.steps, o.role)
    assert TrainOptions("basic", steps=8_000_000).run_name("v3") == "basic_v3_8m_seed0"
    assert TrainOptions("basic", name="mine", steps=8_000_000).run_name("v3") == "mine"


def test_analyze_plays_the_run_s_game_in_chunks_and_refuses_a_memoryless_feed_forward_run(ws, tmp_path):
    w, rec, calls = ws
    (rec / "policies" / "policies.yaml").write_text(
        "basic_v3_seed0: {variant: basic, network: ff, game: v3, training_seed: 0, steps: 2048}\n")
    weights = tmp_path / "policy.pt"
    weights.write_text("w")
    r = pipeline(w, rec, calls, "analyze", "basic_v3_seed0", str(weights), "--part", "behaviour", "--episodes", "120")
    assert r.returncode == 0, r.stderr
    plays = [line.split() for line in calls.read_text().splitlines() if line.startswith("play_episodes")]
    # 120 episodes in chunks of 50 from seed 10000, on game v3, greedy with memory
    assert [(p[2], p[5], p[6]) for p in plays] == [("v3", "10000", "50"), ("v3", "10050", "50"), ("v3", "10100", "20")]
    assert all(p[-2:] == ["greedy", "memory"] for p in plays)
    steps = [line for line in calls.read_text().splitlines() if line.startswith("behaviour.py")]
    assert steps and steps[0].split()[2] == str(rec / "docs" / "runs" / "basic_v3_seed0" / "analysis")
    r = pipeline(w, rec, calls, "analyze", "basic_v3_seed0", str(weights), "--part", "memoryless")
    assert r.returncode == 1 and "the memoryless ablation is a GRU's" in r.stderr


def test_a_seeker_s_run_trains_against_the_shipped_hider_and_is_evaluated_as_a_seeker(ws, tmp_path):
    w, rec, calls = ws
    r = pipeline(w, rec, calls, "train", "basic", "--role", "seeker", "--steps", "4096", "--runs-dir",
                 str(tmp_path / "runs"))
    # no hider of basic ships in the records: refused before anything trains
    assert r.returncode == 1 and "no hider of basic on game v2 ships" in r.stderr
    assert not calls.exists() or "train.launch" not in calls.read_text()
    (rec / "policies" / "basic.pt").write_text("hider weights")
    (rec / "policies" / "policies.yaml").write_text(
        "basic_seed2: {variant: basic, network: ff, game: v2, training_seed: 2, steps: 2048, weights: basic.pt}\n")
    r = pipeline(w, rec, calls, "train", "basic", "--role", "seeker", "--steps", "4096", "--runs-dir",
                 str(tmp_path / "runs"), "--port", "12345")
    assert r.returncode == 0, r.stdout + r.stderr
    e = entries(rec)["basic_seeker_4096_seed0"]
    assert (e["role"], e["variant"], e["game"], e["steps"]) == ("seeker", "basic", "v2", 4096)
    assert e["command"].startswith("hideseek_pipeline train basic --seed 0 --steps 4096 --network ff "
                                   "--name basic_seeker_4096_seed0 --role seeker")
    launched = [line for line in calls.read_text().splitlines() if line.startswith("roslaunch")]
    # the shipped hider as the records ship it (a pinned worktree's registry may ship another)
    assert "role:=seeker" in launched[0] and "opponent:=%s" % (rec / "policies" / "basic.pt") in launched[0]
    # then the learned and the scripted seeker against that hider and the four evaders, no hider evaluation
    evaluations = launched[1:]
    assert len(evaluations) == 10 and all("evaluate.launch" in line for line in evaluations)
    assert "seeker_policy:=%s" % (tmp_path / "runs" / "basic_seeker_4096_seed0" / "policy.pt") in evaluations[0]
    assert "seeker_mode:=scripted" in evaluations[1]
    table = (rec / "docs" / "runs" / "basic_seeker_4096_seed0" / "seeker_evaluation.csv").read_text().splitlines()
    assert [row.split(",")[:2] for row in table[1:3]] == [["basic", "learned"], ["basic", "scripted"]]
    assert [row.split(",")[0] for row in table[3::2]] == ["scripted/backpedal", "scripted/flee", "scripted/hide",
                                                          "scripted/lap"]
    summary = (rec / "docs" / "runs" / "basic_seeker_4096_seed0" / "seeker_evaluation.md").read_text()
    assert str(tmp_path) not in summary
    assert summary.startswith("# Seeker evaluation: basic_seeker_4096_seed0 (variant basic, game v2)")
    assert not (rec / "docs" / "runs" / "basic_seeker_4096_seed0" / "evaluation.csv").exists()
    r = pipeline(w, rec, calls, "train", "basic", "--role", "seeker", "--ship", "--runs-dir", str(tmp_path / "runs"))
    assert r.returncode == 1 and "a seeker's run is not shipped" in r.stderr


def test_an_opponent_that_is_not_the_role_s_is_refused_before_anything_trains(ws, tmp_path):
    w, rec, calls = ws
    for args, said in ((["--role", "seeker", "--opponent", "scripted/hyde"],
                        "a seeker's opponent is one of shipped, random, scripted/backpedal"),
                       (["--role", "seeker", "--opponent", "scripted"], "a seeker's opponent is one of"),
                       (["--opponent", "shipped"], "a hider's opponent is one of random, scripted, or a checkpoint"),
                       (["--opponent", str(tmp_path / "gone.pt")], "--opponent: no file %s" % (tmp_path / "gone.pt"))):
        r = pipeline(w, rec, calls, "train", "basic", "--steps", "4096", "--runs-dir", str(tmp_path / "runs"), *args)
        assert r.returncode == 1 and said in r.stderr, (args, r.stderr)
    assert not calls.exists() or "train.launch" not in calls.read_text()
    r = pipeline(w, rec, calls, "train", "basic", "--role", "seeker", "--opponent", "scripted/hide", "--steps", "4096",
                 "--runs-dir", str(tmp_path / "runs"), "--port", "12345")
    assert r.returncode == 0, r.stdout + r.stderr
    assert "opponent:=scripted/hide" in [line for line in calls.read_text().splitlines() if "train.launch" in line][0]


def test_a_trainer_writes_the_records_with_the_records_own_registry_reader(ws, tmp_path):
    """A trainer pinned at an older commit records into today's registry, whose entries may carry
    fields its own reader does not know: it reads and writes them with the records' reader."""
    w, rec, calls = ws
    module = rec / "src" / "hideseek_analysis" / "python" / "hideseek_analysis"
    module.mkdir(parents=True)
    today = open(os.path.join(ROOT, "src", "hideseek_analysis", "python", "hideseek_analysis", "registry.py")).read()
    assert today.count('"role")') == 1
    (module / "registry.py").write_text(today.replace('"role")', '"role", "field_of_tomorrow")'))
    subprocess.run(["cp", "-r", os.path.join(ROOT, "config"), str(rec / "config")], check=True)  # its variants
    (rec / "policies" / "policies.yaml").write_text(
        "basic_seed9: {variant: basic, network: ff, game: v2, training_seed: 9, steps: 2048, field_of_tomorrow: 1}\n")
    r = pipeline(w, rec, calls, "train", "basic", "--steps", "4096", "--runs-dir", str(tmp_path / "runs"))
    assert r.returncode == 0, r.stdout + r.stderr
    assert entries(rec)["basic_seed9"]["field_of_tomorrow"] == 1 and entries(rec)["basic_4096_seed0"]["steps"] == 4096


def test_a_seeker_evaluation_without_a_capture_shows_no_mean_time_to_capture(tmp_path):
    from hideseek_pipeline import seeker
    rows = [dict(hider="scripted/lap", seeker="learned", episodes=100, captures=0, capture_rate=0.0,
                 mean_time_to_capture=float("nan")),
            dict(hider="scripted/lap", seeker="scripted", episodes=100, captures=73, capture_rate=0.73,
                 mean_time_to_capture=484.5)]
    seeker.write_table(rows, str(tmp_path), "basic_seeker_v3_seed0")
    table = (tmp_path / "seeker_evaluation.md").read_text()
    assert "| scripted/lap | learned | 100 | 0 | 0.0 % | - |" in table and "nan" not in table
    assert "| scripted/lap | scripted | 100 | 73 | 73.0 % | 484.5 |" in table


@pytest.fixture
def own_files(tmp_path):
    """A variant file of one's own, `mine`, and its map (the stand-in resolver names it)."""
    variant, map_file = tmp_path / "mine.yaml", tmp_path / "mine_map.yaml"
    variant.write_text("variant: mine\nmap: %s\nseeker: {path_following: no_backtrack}\n" % map_file)
    map_file.write_text("walls: []\n")
    return variant, map_file


def test_a_variant_file_of_one_s_own_trains_evaluates_and_analyses_as_it_was_recorded(ws, tmp_path, own_files):
    """train --variant-config: every tool plays the file, and the registry records it and its map with
    their sha256; the run's evaluation and analysis play the same file again."""
    w, rec, calls = ws
    variant, map_file = own_files
    r = pipeline(w, rec, calls, "train", "mine", "--variant-config", str(variant), "--steps", "4096", "--runs-dir",
                 str(tmp_path / "runs"), "--eval-modes", "greedy", MAP_FILE=str(map_file))
    assert r.returncode == 0, r.stdout + r.stderr
    e = entries(rec)["mine_4096_seed0"]
    assert (e["variant"], e["variant_config"], e["map_file"]) == ("mine", str(variant), str(map_file))
    assert e["variant_sha256"] == hashlib.sha256(variant.read_bytes()).hexdigest()
    assert e["map_sha256"] == hashlib.sha256(map_file.read_bytes()).hexdigest()
    assert e["command"].endswith("--variant-config %s" % variant)
    lines = calls.read_text().splitlines()
    launched = [line for line in lines if line.startswith("roslaunch")]
    assert "train.launch variant:=mine" in launched[0] and "variant_config:=%s" % variant in launched[0]
    assert "evaluate.launch variant:=mine" in launched[1] and "variant_config:=%s" % variant in launched[1]
    resolved = [line for line in lines if line.startswith("resolve")]
    assert resolved and all("--variant-config %s mine" % variant in line for line in resolved)
    played = [line for line in lines if line.startswith("play_episodes")]
    assert played and all(line.endswith("--variant-config %s" % variant) for line in played)
    calls.unlink()
    weights = tmp_path / "runs" / "mine_4096_seed0" / "policy.pt"
    r = pipeline(w, rec, calls, "analyze", "mine_4096_seed0", str(weights), "--part", "behaviour", "--episodes", "60",
                 MAP_FILE=str(map_file))
    assert r.returncode == 0, r.stderr
    played = [line for line in calls.read_text().splitlines() if line.startswith("play_episodes")]
    assert len(played) == 2 and all(line.endswith("--variant-config %s" % variant) for line in played)


def test_a_variant_file_of_one_s_own_is_refused_where_it_is_misnamed_changed_or_shipped(ws, tmp_path, own_files):
    w, rec, calls = ws
    variant, map_file = own_files
    runs = str(tmp_path / "runs")
    own = ["--variant-config", str(variant), "--runs-dir", runs, "--steps", "4096"]
    for args, said in (
            (["yours"] + own, "is variant 'mine' (its variant field), not 'yours': give the variant on the command "
                              "line as the file names it, or change the file's variant field"),
            (["mine", "--variant-config", str(tmp_path / "gone.yaml"), "--runs-dir", runs], "no file"),
            (["mine", "--ship"] + own, "a run on a variant file of one's own is played from its weights")):
        r = pipeline(w, rec, calls, "train", *args, MAP_FILE=str(map_file))
        assert r.returncode == 1 and said in r.stderr, (args, r.stderr)
    basic = tmp_path / "basic.yaml"
    basic.write_text("variant: basic\n")
    r = pipeline(w, rec, calls, "train", "basic", "--variant-config", str(basic), "--runs-dir", runs,
                 MAP_FILE=str(map_file))
    assert r.returncode == 1 and "'basic' is a variant of the project" in r.stderr
    assert not calls.exists() or "train.launch" not in calls.read_text()
    # A run cut off with its checkpoint resumes on the files it started on, not on an edited one.
    r = pipeline(w, rec, calls, "train", "mine", *own, "--eval-modes", "greedy", MAP_FILE=str(map_file),
                 STOP_AT="2048")
    assert r.returncode == 1 and "the same command resumes it" in r.stderr
    saved = yaml.safe_load((tmp_path / "runs" / "mine_4096_seed0" / "variant_files.yaml").read_text())
    assert saved["variant_sha256"] == hashlib.sha256(variant.read_bytes()).hexdigest()
    map_file.write_text("walls: [{x: 1}]\n")
    calls.unlink()
    r = pipeline(w, rec, calls, "train", "mine", *own, MAP_FILE=str(map_file))
    assert r.returncode == 1 and "mine_4096_seed0's checkpoint in" in r.stderr and "name the run otherwise" in r.stderr
    assert "train.launch" not in calls.read_text()
    # Recorded, then its file edited: its evaluation and analysis are refused, naming the file.
    map_file.write_text("walls: []\n")
    r = pipeline(w, rec, calls, "train", "mine", *own, "--eval-modes", "greedy", MAP_FILE=str(map_file))
    assert r.returncode == 0, r.stdout + r.stderr
    variant.write_text(variant.read_text() + "episode: {max_steps: 100}\n")
    weights = str(tmp_path / "runs" / "mine_4096_seed0" / "policy.pt")
    for step in (["evaluate", "mine_4096_seed0", weights], ["analyze", "mine_4096_seed0", weights]):
        r = pipeline(w, rec, calls, *step, MAP_FILE=str(map_file))
        assert r.returncode == 1 and "mine_4096_seed0 trained on %s with sha256" % variant in r.stderr, r.stderr
        assert "it has changed since" in r.stderr
    # and the registry's check names it
    sys.path.insert(0, os.path.join(ROOT, "src", "hideseek_analysis", "python"))
    from hideseek_analysis import registry
    found = registry.problems(str(rec / "policies" / "policies.yaml"), os.path.join(ROOT, "config", "variants"))
    assert any("variant_config %s has changed since the run trained" % variant in p for p in found), found


def test_a_run_cut_off_before_its_first_checkpoint_starts_again_on_the_files_given_now(tmp_path, own_files):
    """variant_files.yaml binds a checkpoint to its files; with no checkpoint yet, a run started again
    on an edited file is a new start, and its checkpoint then resumes on the edited file."""
    sys.path.insert(0, PACKAGE)
    from hideseek_pipeline import own_variant
    from hideseek_pipeline.workspace import ToolError
    variant, map_file = own_files
    run = tmp_path / "run"
    run.mkdir()

    def fields():
        return {"variant_config": str(variant), "variant_sha256": own_variant.sha256(str(variant)),
                "map_file": str(map_file), "map_sha256": own_variant.sha256(str(map_file))}
    own_variant.check_resume(str(run), fields(), "mine", "train")  # first start: no checkpoint
    variant.write_text(variant.read_text() + "# edited before any checkpoint\n")
    own_variant.check_resume(str(run), fields(), "mine", "train")  # started again on the edited file
    (run / "checkpoint.pt").write_text("ckpt")
    own_variant.check_resume(str(run), fields(), "mine", "train")  # resumes on it
    with pytest.raises(ToolError, match="mine's checkpoint in .* trained on the variant file"):
        own_variant.check_resume(str(run), None, "mine", "train")  # not on the project's files
    map_file.write_text("walls: [{x: 2}]\n")
    with pytest.raises(ToolError, match="name the run otherwise, or restore the file"):
        own_variant.check_resume(str(run), fields(), "mine", "train")


def test_a_recorded_run_s_map_is_checked_by_content_where_this_workspace_resolves_it(tmp_path, own_files):
    """A relative map name resolves under the workspace's config/ (a worktree, devel or install space):
    the same content elsewhere plays; other content is refused, naming both files."""
    sys.path.insert(0, PACKAGE)
    from hideseek_pipeline import own_variant
    from hideseek_pipeline.workspace import ToolError
    variant, map_file = own_files
    elsewhere = tmp_path / "elsewhere_map.yaml"
    elsewhere.write_text(map_file.read_text())

    class Resolver:
        map_file = str(elsewhere)

        def resolve(self, name, key, game=None, variant_config=None):
            assert (name, key, game, variant_config) == ("mine", "map_file", "v3", str(variant))
            return self.map_file
    entry = {"variant": "mine", "game": "v3", "variant_config": str(variant),
             "variant_sha256": own_variant.sha256(str(variant)), "map_file": str(map_file),
             "map_sha256": own_variant.sha256(str(map_file))}
    assert own_variant.check_unchanged(Resolver(), "mine_seed0", entry, "evaluate") == str(variant)
    elsewhere.write_text("walls: [{x: 3}]\n")
    with pytest.raises(ToolError, match="mine_seed0 trained on %s with sha256 .*it has changed since \\(%s" % (
            map_file, elsewhere)):
        own_variant.check_unchanged(Resolver(), "mine_seed0", entry, "evaluate")
