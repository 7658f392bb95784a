"""The analysis as a library, used on evaluations of one's own (docs/analysis.md, The analysis as a
library): the statistics take one run as a plain array, refuse an empty run by name and take an
integer seed; episodes.csv files are checked; examples/compare_evaluations.py compares two
committed evaluations. No ROS master."""
import os
import subprocess
import sys

import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "src", "hideseek_analysis", "python"))

from hideseek_analysis import stats as st  # noqa: E402
from hideseek_analysis.runs import evaluation_by_seed, load_episodes  # noqa: E402

EXAMPLE = os.path.join(ROOT, "examples", "compare_evaluations.py")


def write(path, text):
    path.write_text(text)
    return str(path)


def test_one_run_may_be_a_plain_array_and_gives_what_a_list_of_one_run_gives():
    x = [3.0, 5.0, 8.0, 13.0]
    assert st.pooled_statistic(x, st.mean, st.keyed_rng(0, "a"), 300) == \
        st.pooled_statistic([x], st.mean, st.keyed_rng(0, "a"), 300)
    assert st.mean_difference(np.array(x), [1.0, 2.0], 7, 300) == st.mean_difference([x], [[1.0, 2.0]], 7, 300)


def test_a_run_without_episodes_and_a_bad_generator_are_refused_by_name():
    with pytest.raises(ValueError, match="runs_y: run 1 holds no episodes"):
        st.mean_difference([[1.0]], [[1.0], []], 0, 10)
    with pytest.raises(ValueError, match="runs: no runs"):
        st.pooled_statistic([], st.mean, 0, 10)
    with pytest.raises(TypeError, match="rng: a numpy Generator"):
        st.pooled_statistic([1.0, 2.0], st.mean, "0", 10)


def test_the_paired_difference_is_over_the_seeds_both_played():
    x = {0: 10.0, 1: 20.0, 2: 30.0, 5: 99.0}
    y = {0: 7.0, 1: 17.0, 2: 27.0, 9: 1.0}
    d, (lo, hi), n = st.paired_difference(x, y, 0, 200)
    assert (d, lo, hi, n) == (3.0, 3.0, 3.0, 3)  # every paired difference is 3
    with pytest.raises(ValueError, match="share no evaluation seed"):
        st.paired_difference({0: 1.0}, {1: 1.0}, 0, 10)


def test_an_episodes_file_is_checked_naming_the_file_and_the_line(tmp_path):
    with pytest.raises(FileNotFoundError, match="nosuch.csv: no such file"):
        load_episodes(str(tmp_path / "nosuch.csv"))
    wrong = write(tmp_path / "evaluation.csv", "variant,policy,episodes,avg_living_steps,success_rate\nb,p,1,2.0,0\n")
    with pytest.raises(ValueError, match="evaluation.csv: no column seed, living_steps, outcome"):
        load_episodes(wrong)
    caught = write(tmp_path / "caught.csv", "seed,living_steps,outcome\n0,12,captured\n1,40,caught\n")
    with pytest.raises(ValueError, match="caught.csv, line 3: outcome 'caught' is neither captured nor survived"):
        evaluation_by_seed(caught)
    good = write(tmp_path / "episodes.csv", "seed,living_steps,outcome\n4,12,captured\n5,1000,survived\n")
    living, success = load_episodes(good)
    assert living.tolist() == [12.0, 1000.0] and success.tolist() == [0.0, 1.0]
    assert evaluation_by_seed(good) == {4: 12.0, 5: 1000.0}


def test_the_example_compares_two_evaluations_as_their_files_say(tmp_path):
    a = os.path.join(ROOT, "docs", "runs", "basic_v3_seed0")
    b = os.path.join(ROOT, "docs", "runs", "slowerhider_v3_seed0")
    r = subprocess.run([sys.executable, EXAMPLE, a, b, "--out", str(tmp_path), "--reps", "200"],
                       capture_output=True, text=True, timeout=120, env=dict(os.environ, MPLBACKEND="Agg"))
    assert r.returncode == 0, r.stderr
    la, lb = load_episodes(os.path.join(a, "episodes.csv"))[0], load_episodes(os.path.join(b, "episodes.csv"))[0]
    assert "basic_v3_seed0: 100 episodes, mean living steps %.1f" % la.mean() in r.stdout
    assert "slowerhider_v3_seed0: 100 episodes, mean living steps %.1f" % lb.mean() in r.stdout
    assert "minus slowerhider_v3_seed0: %.1f" % (la.mean() - lb.mean()) in r.stdout
    assert "paired over the 100 seeds both played" in r.stdout
    assert (tmp_path / "performance_profile.png").stat().st_size > 10000
    r = subprocess.run([sys.executable, EXAMPLE, str(tmp_path / "nosuch"), a], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 2 and "nosuch: no such file" in r.stderr


def test_every_estimate_takes_an_integer_seed_and_draws_each_variant_on_its_own():
    assert st.mean_over_runs([1.0, 2.0, 4.0], 0, 100)[0] == pytest.approx(7 / 3)
    assert st.boot_runs({"a": [1.0, 2.0, 6.0]}, lambda d: d["a"].mean(), 0, 100)[0] == pytest.approx(3.0)
    # Three variants of the same shape, shifted: had each its own generator from the same integer,
    # every resample would keep their order and the interval would be [1, 1].
    runs = [[np.arange(10.0) + shift] for shift in (0.0, 0.5, 1.0)]
    rho, (lo, hi) = st.rank_correlation(runs, [1, 2, 3], 0, 300)
    assert rho == pytest.approx(1.0) and lo < 1.0


def test_the_example_refuses_two_evaluations_of_one_name(tmp_path):
    for side in ("a", "b"):
        (tmp_path / side / "eval").mkdir(parents=True)
        write(tmp_path / side / "eval" / "episodes.csv", "seed,living_steps,outcome\n0,12,captured\n")
    r = subprocess.run([sys.executable, EXAMPLE, str(tmp_path / "a" / "eval"), str(tmp_path / "b" / "eval")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2 and "both are named eval: give them names with --labels" in r.stderr
    # Two folders that do not exist: that is said first, whatever their names.
    r = subprocess.run([sys.executable, EXAMPLE, str(tmp_path / "c" / "shipped"), str(tmp_path / "c" / "flee")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2 and "shipped: no such file" in r.stderr
    r = subprocess.run([sys.executable, EXAMPLE, str(tmp_path / "a" / "eval"), str(tmp_path / "b" / "eval"),
                        "--labels", "a", "b", "--reps", "50"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and "a minus b: 0.0" in r.stdout and "pairs nothing" not in r.stdout
    # Evaluations that name their game (from 2026-12-02): one seed on two games pairs nothing, and
    # the example says so; one written before has no game column and is taken as it is.
    header = "variant,policy,episodes,avg_living_steps,success_rate,game\n"
    write(tmp_path / "a" / "eval" / "evaluation.csv", header + "basic,p,1,12.00,0.0000,v2\n")
    write(tmp_path / "b" / "eval" / "evaluation.csv", header + "basic,p,1,12.00,0.0000,v3\n")
    r = subprocess.run([sys.executable, EXAMPLE, str(tmp_path / "a" / "eval"), str(tmp_path / "b" / "eval"),
                        "--labels", "a", "b", "--reps", "50"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and "(games v2 and v3: each plays its own maps and rules" in r.stdout
    write(tmp_path / "b" / "eval" / "evaluation.csv",
          "variant,policy,episodes,avg_living_steps,success_rate\nbasic,p,1,12.00,0.0000\n")
    r = subprocess.run([sys.executable, EXAMPLE, str(tmp_path / "a" / "eval"), str(tmp_path / "b" / "eval"),
                        "--labels", "a", "b", "--reps", "50"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and "pairs nothing" not in r.stdout
