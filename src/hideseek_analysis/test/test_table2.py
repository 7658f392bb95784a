"""Table 2 of the shipped policies (table2.py --evaluations), the same generator as Table 2 across
seeds: every shipped policy's episodes beside the random hider evaluated with them and the paper's
figures, a GRU hider and its memoryless ablation in rows of their own. No ROS master."""
import csv
import os
import shutil
import subprocess
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
TABLE2 = os.path.join(ROOT, "src", "hideseek_analysis", "scripts", "table2.py")


def write_episodes(folder, living):
    """One evaluation as evaluate.launch leaves it: episodes.csv and evaluation.csv."""
    os.makedirs(folder)
    with open(os.path.join(folder, "episodes.csv"), "w") as f:
        f.write("seed,living_steps,outcome\n")
        for i, x in enumerate(living):
            f.write("%d,%d,%s\n" % (i, x, "survived" if x >= 1000 else "captured"))
    with open(os.path.join(folder, "evaluation.csv"), "w") as f:
        f.write("variant,policy,episodes,avg_living_steps,success_rate\nx,y,%d,%.2f,%.4f\n" % (
            len(living), sum(living) / len(living), sum(x >= 1000 for x in living) / len(living)))


@pytest.fixture
def checkout(tmp_path):
    """A checkout's config/ and an evaluation of basic (feed-forward and GRU), slowerhider and
    stochasticseeker with their random hiders; fasterhider has only its random hider."""
    shutil.copytree(os.path.join(ROOT, "config"), tmp_path / "config")
    (tmp_path / "policies").mkdir()
    (tmp_path / "policies" / "policies.yaml").write_text("")
    ev = tmp_path / "report" / "evaluations"
    write_episodes(ev / "basic_trained", [100] * 10 + [1000] * 10)
    write_episodes(ev / "basic_gru_trained", [300] * 20)
    write_episodes(ev / "basic_gru_memoryless", [150] * 20)
    write_episodes(ev / "basic_random", [40] * 20)
    write_episodes(ev / "slowerhider_trained", [50] * 20)
    write_episodes(ev / "slowerhider_random", [45] * 20)
    write_episodes(ev / "stochasticseeker_trained", [200] * 20)
    write_episodes(ev / "fasterhider_random", [42] * 20)
    return tmp_path


def run(checkout):
    r = subprocess.run([sys.executable, TABLE2, "--root", str(checkout), "--evaluations",
                        str(checkout / "report" / "evaluations"), "--reps", "200"], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r.stderr
    return checkout / "report" / "table2_shipped"


def test_every_shipped_policy_is_a_row_beside_its_random_hider_and_the_paper(checkout):
    out = run(checkout)
    with open(out / "table2.csv") as f:
        rows = {(r["variant"], r["mode"]): r for r in csv.DictReader(f)}
    assert set(rows) == {("basic", "greedy"), ("basic", "GRU, greedy"), ("basic", "GRU memoryless, greedy"),
                         ("slowerhider", "greedy"), ("stochasticseeker", "greedy")}
    basic = rows[("basic", "greedy")]
    assert basic["runs"] == "1" and basic["episodes"] == "20" and basic["run_names"] == "basic"
    assert float(basic["living_mean"]) == pytest.approx(550.0) and float(basic["success_mean"]) == pytest.approx(0.5)
    # One run: the interval covers the spread between its episodes only, and holds the mean.
    assert float(basic["living_mean_lo"]) < 550.0 < float(basic["living_mean_hi"])
    assert float(rows[("basic", "GRU memoryless, greedy")]["living_mean"]) == pytest.approx(150.0)
    md = (out / "table2.md").read_text()
    assert md.startswith("# Table 2: the shipped policies")
    assert "| basic | random hider | | 40.0 | | 0 |" in md
    assert "| basic | paper, trained (8M steps) | 1 | 500 |" in md
    assert "No shipped policy evaluated: fasterhider" in md


def test_the_shipped_policies_are_ranked_against_the_paper_s_orderings(checkout):
    out = run(checkout)
    with open(out / "orderings.csv") as f:
        lines = f.read().splitlines()
    rows = {(r["better"], r["worse"]): r for r in csv.DictReader(x for x in lines if not x.startswith("#"))}
    assert set(rows) == {("basic", "stochasticseeker"), ("basic", "slowerhider"), ("stochasticseeker", "slowerhider")}
    # Every basic episode lives longer than every slowerhider one.
    assert float(rows[("basic", "slowerhider")]["poi_episodes"]) == pytest.approx(1.0)
    assert lines[-1].startswith("# spearman_rho_with_paper,3 variants,1.0000")


def test_an_evaluation_without_episodes_is_refused_by_name(checkout):
    (checkout / "report" / "evaluations" / "slowerhider_trained" / "episodes.csv").write_text(
        "seed,living_steps,outcome\n")
    r = subprocess.run([sys.executable, TABLE2, "--root", str(checkout), "--evaluations",
                        str(checkout / "report" / "evaluations"), "--reps", "50"], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode != 0
    assert "slowerhider_trained/episodes.csv: no episodes" in r.stderr


def test_a_folder_of_evaluations_named_otherwise_is_refused_naming_what_it_holds(checkout):
    # Evaluations of one's own under other names ("shipped", "flee") used to give a table of the
    # paper's rows alone and exit 0.
    ev = checkout / "mine"
    write_episodes(ev / "shipped", [100] * 4)
    write_episodes(ev / "flee", [50] * 4)
    r = subprocess.run([sys.executable, TABLE2, "--root", str(checkout), "--evaluations", str(ev), "--reps", "50"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2
    assert "holds no evaluation named VARIANT_trained" in r.stderr
    assert "it holds: flee, shipped" in r.stderr
    assert not (checkout / "table2_shipped").exists()
