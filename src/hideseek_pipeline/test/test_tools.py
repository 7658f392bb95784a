"""hideseek_pipeline test, bench and report, the parts that need no ROS: the one throughput
measurement, the tests' verdict from JUnit files, and report --from-scratch against stand-ins (fake
roslaunch and analysis scripts): what it evaluates and analyses, in which order, and what it refuses."""
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest
import yaml
from stand_ins import stand_in_workspace

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
PACKAGE = os.path.join(ROOT, "src", "hideseek_pipeline", "python")
sys.path.insert(0, PACKAGE)
from hideseek_pipeline import cli, measure, selfplay, tests, train  # noqa: E402


def test_samples_per_s_counts_from_the_end_of_the_warm_up_to_the_last_update(tmp_path):
    log = tmp_path / "training_log.csv"
    log.write_text("update,steps,wall_s\n1,1000,5\n2,2000,10\n3,3000,12\n4,4000,14\n")
    assert measure.samples_per_s(log) == pytest.approx(2000 / 4)   # updates 3-4 after the 2 warm-up ones
    assert measure.samples_per_s(log, 1, 3) == pytest.approx(2000 / 7)
    with pytest.raises(measure.MeasureError, match="no updates after update 4"):
        measure.samples_per_s(log, 4)


def test_loop_shares_are_each_part_of_the_loop_after_the_warm_up(tmp_path):
    profile = tmp_path / "loop_profile.csv"
    profile.write_text("update,x,wait,inference,update_s,other\n2,0,100,100,100,100\n3,0,1,2,6,1\n4,0,1,2,6,1\n")
    update, inference, wait, other = measure.loop_shares(profile)
    assert (update, inference, wait, other) == pytest.approx((0.6, 0.2, 0.1, 0.1))


def test_the_measure_command_line_prints_what_the_throughput_studies_read(tmp_path):
    log = tmp_path / "training_log.csv"
    log.write_text("update,steps,wall_s\n2,2000,10\n3,3001,12\n")
    env = dict(os.environ, PYTHONPATH=PACKAGE)
    run = [sys.executable, "-m", "hideseek_pipeline.measure"]
    r = subprocess.run(run + ["samples-per-s", str(log)], env=env, capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout == "500\n"   # 1001 samples in 2 s, to the whole sample
    r = subprocess.run(run + ["rollout-steps", os.path.join(ROOT, "config", "ppo.yaml")], env=env, capture_output=True,
                       text=True)
    assert r.returncode == 0 and int(r.stdout) > 0
    r = subprocess.run(run + ["samples-per-s", str(tmp_path / "missing.csv")], env=env, capture_output=True, text=True)
    assert r.returncode == 1 and "missing.csv" in r.stderr


def test_the_verdict_counts_cases_failures_errors_and_an_unreadable_file(tmp_path):
    (tmp_path / "a").mkdir()
    (tmp_path / "a" / "one.xml").write_text(
        '<testsuite><testcase name="p1"/><testcase name="p2"/><testcase name="f"><failure/></testcase>'
        '<testcase name="e"><error/></testcase><testcase name="s"><skipped/></testcase></testsuite>')
    (tmp_path / "broken.xml").write_text("<testsuite><testcase")
    assert tests.tally(str(tmp_path)) == (2, 3, ["s"])
    # a skipped case is named with its reason (pytest's message attribute; gtest's text)
    (tmp_path / "a" / "two.xml").write_text(
        '<testsuite><testcase name="veth"><skipped message="needs CAP_SYS_ADMIN">long text</skipped></testcase>'
        '<testcase name="bare"><skipped/></testcase></testsuite>')
    assert tests.tally(str(tmp_path)) == (2, 3, ["s", "veth (needs CAP_SYS_ADMIN)", "bare"])
    # a case marked skipped that also failed (a teardown error after the skip) is a failure, not named skipped
    (tmp_path / "a" / "three.xml").write_text(
        '<testsuite><testcase name="torn"><skipped message="x"/><error message="teardown"/></testcase></testsuite>')
    assert tests.tally(str(tmp_path)) == (2, 4, ["s", "veth (needs CAP_SYS_ADMIN)", "bare"])


def test_a_run_that_stops_on_a_build_error_fails_even_where_every_result_passed(tmp_path):
    """catkin_make run_tests stopped by a target that does not link: the tests that ran passed, the
    rest never ran, and the verdict is a failure that says why (stand-in catkin tools)."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "catkin_make").write_text(
        "#!/bin/bash\nmkdir -p build/test_results/pkg\n"
        "echo '<testsuite><testcase name=\"ran\"/></testsuite>' > build/test_results/pkg/gtest-ran.xml\n"
        "echo 'collect2: error: ld returned 1 exit status'\nexit 2\n")
    (bin_dir / "catkin_test_results").write_text("#!/bin/bash\necho 'Summary: 1 tests, 0 errors, 0 failures'\n")
    for tool in bin_dir.iterdir():
        tool.chmod(0o755)
    root = tmp_path / "ws"
    (root / "scripts").mkdir(parents=True)
    (root / "scripts" / "env.sh").write_text("export PATH=%s:$PATH\n" % bin_dir)
    said = []
    assert tests.run_tests(str(root), say=said.append) == 1
    assert "collect2: error: ld returned 1 exit status" in said
    assert any("stopped with exit status 2 before every test ran" in line for line in said)
    assert said[-1] == "1 passed, 1 failed"


@pytest.fixture
def checkout(tmp_path):
    """Stand-ins in a checkout with basic (a feed-forward and a GRU policy shipped) and slowerhider
    (nothing shipped), and the real registry module."""
    w = stand_in_workspace(tmp_path / "ws")
    lib = w / "src" / "hideseek_analysis" / "python" / "hideseek_analysis"
    lib.mkdir(parents=True)
    shutil.copy(os.path.join(ROOT, "src", "hideseek_analysis", "python", "hideseek_analysis", "registry.py"), lib)
    (w / "config" / "variants").mkdir(parents=True)
    for v in ("basic", "slowerhider"):
        (w / "config" / "variants" / (v + ".yaml")).write_text("variant: %s\n" % v)
    (w / "config" / "paper_reference.yaml").write_text("variants:\n  basic: {}\n  slowerhider: {}\n")
    (w / "config" / "games.yaml").write_text("default: v2\n")
    # A sweep none of whose runs is done: report --from-scratch's sweep analysis finds nothing to do.
    (w / "config" / "sweep.yaml").write_text("precision: fp32\njobs: 1\nhider_threads: 1\nsteps: 2048\nnetwork: ff\n"
                                             "port: 12900\nphases:\n  - {name: p, commit: '0123456789ab', game: v2, "
                                             "variants: [basic], seeds: [5]}\n")
    (w / "policies").mkdir()
    (w / "policies" / "policies.yaml").write_text(
        "basic_seed0: {variant: basic, network: ff, game: v2, weights: basic.pt}\n"
        "basic_gru_seed0: {variant: basic, network: gru, game: v2, weights: basic_gru.pt}\n")
    return w


def report(w, tmp_path, *args, **env):
    e = dict(os.environ, PYTHONPATH=PACKAGE, CALLS=str(tmp_path / "calls.txt"), HIDESEEK_ROOT=str(w),
             SWEEP_DIR=str(tmp_path / "sweep"),
             PATH="/usr/bin:" + os.environ["PATH"])
    e.update(env)
    work = ["--work-dir", str(tmp_path / "work")] if "--from-scratch" in args else []
    return subprocess.run([sys.executable, "-m", "hideseek_pipeline", "report", str(tmp_path / "report")] + work +
                          list(args), env=e, capture_output=True, text=True, timeout=120)


def test_report_from_scratch_evaluates_every_shipped_policy_then_analyses_it(checkout, tmp_path):
    r = report(checkout, tmp_path, "--from-scratch", "--steps", "500")
    assert r.returncode == 0, r.stdout + r.stderr
    calls = (tmp_path / "calls.txt").read_text().splitlines()
    evaluations = [c.split("output_dir:=")[1].split()[0].rsplit("/", 1)[1] for c in calls if "evaluate.launch" in c]
    assert evaluations == ["basic_random", "basic_trained", "basic_gru_trained", "basic_gru_memoryless",
                           "slowerhider_random"]
    assert all("game:=v2" in c for c in calls if ".launch" in c)  # the default game (config/games.yaml)
    assert "memoryless:=true" in [c for c in calls if "basic_gru_memoryless" in c][0]
    analyses = [c for c in calls if "analyze.launch" in c]
    assert len(analyses) == 2 and "report_dir:=%s/v2/basic " % (tmp_path / "report") in analyses[0] + " "
    assert "steps:=500" in analyses[0] and "policy:=%s/policies/basic_gru.pt" % checkout in analyses[1]
    ran = [c.split()[0] for c in calls if c.endswith(".py") or ".py " in c]
    assert ran == ["table2.py", "reproduce_report.py", "table2.py", "seed_figures.py", "claims.py"]
    assert "slowerhider: no shipped policy on game v2" in r.stdout
    assert (tmp_path / "report" / "v2" / "evaluations" / "basic_trained" / "evaluation.csv").is_file()
    assert not (tmp_path / "report" / "v2" / "evaluations" / "basic_trained" / "launch.log").exists()


def test_report_from_scratch_plays_the_game_it_is_given(checkout, tmp_path):
    """--game v3: that game's shipped policies (none here: the random hiders only), into v3/."""
    r = report(checkout, tmp_path, "--from-scratch", "--game", "v3")
    assert r.returncode == 0, r.stdout + r.stderr
    launched = [c for c in (tmp_path / "calls.txt").read_text().splitlines() if ".launch" in c]
    assert [c.split("output_dir:=")[1].split()[0] for c in launched] == [
        "%s/v3/evaluations/%s_random" % (tmp_path / "report", v) for v in ("basic", "slowerhider")]
    assert all("game:=v3" in c for c in launched) and "basic: no shipped policy on game v3" in r.stdout


def test_report_names_a_failed_evaluation_and_an_unknown_variant(checkout, tmp_path):
    r = report(checkout, tmp_path, "--from-scratch", FAIL_VARIANT="slowerhider")
    assert r.returncode == 1
    assert "the evaluation of slowerhider (random) failed, see" in r.stderr and "launch.log" in r.stderr
    r = report(checkout, tmp_path, "--from-scratch", "--variants", "basic", "fastest")
    assert r.returncode == 1 and "--variants names fastest, not among: basic slowerhider" in r.stderr


def test_report_without_from_scratch_only_remakes_the_tables_across_seeds(checkout, tmp_path):
    r = report(checkout, tmp_path)
    assert r.returncode == 0, r.stderr
    calls = (tmp_path / "calls.txt").read_text().splitlines()
    assert [c.split()[0] for c in calls] == ["table2.py", "seed_figures.py", "claims.py"]


def test_report_takes_its_from_scratch_options_only_with_from_scratch(checkout, tmp_path):
    r = report(checkout, tmp_path, "--steps", "500")
    assert r.returncode == 1 and "--steps only with --from-scratch" in r.stderr


def test_a_malformed_log_is_named_not_a_traceback(tmp_path):
    log = tmp_path / "training_log.csv"
    log.write_text("update,steps,wall_s\n2,2000,10\n3,x,12\n")
    with pytest.raises(measure.MeasureError, match="training_log.csv: a malformed row"):
        measure.samples_per_s(log)


def _test_port_ranges():
    """The ranges of docs/testing.md's "Ports" table (every row of it), and the port `make test` sets."""
    text = open(os.path.join(ROOT, "docs", "testing.md")).read().split("## Ports", 1)[1].split("\n## ", 1)[0]
    rows = [line for line in text.splitlines() if line.startswith("| ") and not line.startswith(("| range", "| ---"))]
    ranges = [re.match(r"\| (\d+)-(\d+) \|", row) for row in rows]
    assert len(rows) >= 10 and all(ranges), "docs/testing.md's Ports table: a row without a range: %s" % rows
    return [(int(m.group(1)), int(m.group(2))) for m in ranges] + [(tests.PORT, tests.PORT)]


def test_pipeline_ports_by_default_stay_out_of_every_tests_range():
    """A training, self-play, evaluation or report started by hand beside `make test`, and the sweep,
    never land on a test's ROS master: every default port lies outside the ranges the tests draw from."""
    parse = cli.parser().parse_args
    launch = ET.parse(os.path.join(ROOT, "src", "hideseek_pipeline", "launch", "selfplay.launch")).getroot()
    launch_port = [int(a.get("default")) for a in launch.iter("arg") if a.get("name") == "port"]
    assert launch_port == [parse(["selfplay", "out"]).port] == [selfplay.SelfPlayOptions(out="o").port]
    sweep_port = yaml.safe_load(open(os.path.join(ROOT, "config", "sweep.yaml")))["port"]
    defaults = {"report": parse(["report"]).port,
                "selfplay": parse(["selfplay", "out"]).port,
                "evaluate": parse(["evaluate", "run", "w.pt"]).port,
                "evaluate-seeker": parse(["evaluate-seeker", "s.pt", "--output", "o"]).port,
                "sweep slot 0": sweep_port, "sweep slot 1": sweep_port + 10, "sweep recovery": sweep_port + 90}
    ports = {"%s %d" % (name, port + k): port + k for name, port in defaults.items() for k in (0, 1, 2)}
    for seed in range(10):
        for network in ("ff", "gru"):
            for role in ("hider", "seeker"):
                port = train.default_port(seed, network, role)
                for k in (0, 1000, 1001):
                    ports["train seed %d %s %s %d" % (seed, network, role, port + k)] = port + k
    ranges = _test_port_ranges()
    clashes = [name for name, port in ports.items() if any(a <= port <= b for a, b in ranges)]
    assert not clashes, "default ports inside a test's range (docs/testing.md, Ports): %s" % clashes
