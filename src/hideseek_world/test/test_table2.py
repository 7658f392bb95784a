"""Tests of hideseek_analysis' table2.py (Table 2 beside the paper's): run with python3 -m pytest."""
import csv
import os
import subprocess
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
TABLE2 = os.path.join(ROOT, "src", "hideseek_analysis", "scripts", "table2.py")
PAPER = os.path.join(ROOT, "config", "paper_reference.yaml")


def write_evaluation(evaluations, folder, living, success):
    os.makedirs(os.path.join(evaluations, folder))
    with open(os.path.join(evaluations, folder, "evaluation.csv"), "w") as f:
        f.write("variant,policy,episodes,avg_living_steps,success_rate\n")
        f.write("x,y,100,%s,%s\n" % (living, success))


def run(tmp_path, policies_yaml):
    evaluations = tmp_path / "evaluations"
    policies = tmp_path / "policies"
    policies.mkdir()
    (policies / "policies.yaml").write_text(policies_yaml)
    stem = tmp_path / "table2"
    result = subprocess.run([sys.executable, TABLE2, PAPER, str(evaluations), str(stem), str(policies)],
                            capture_output=True, text=True)
    return result, stem


@pytest.fixture
def evaluations(tmp_path):
    e = str(tmp_path / "evaluations")
    os.makedirs(e)
    write_evaluation(e, "basic_random", 40.0, 0.0)
    write_evaluation(e, "basic_trained", 500.0, 0.45)        # shipped: seed 0, 1.2M steps
    write_evaluation(e, "basic_seed0_2m_trained", 600.0, 0.6)
    write_evaluation(e, "basic_seed1_trained", 300.0, 0.2)
    write_evaluation(e, "basic_seed2_trained", 450.0, 0.4)
    write_evaluation(e, "basic_gru_trained", 700.0, 0.7)
    write_evaluation(e, "slowerhider_random", 38.0, 0.0)
    return e


POLICIES = """
basic: {training_seed: 0, steps: 1200000, wall_s: 3600}
basic_seed0_2m: {variant: basic, network: ff, training_seed: 0, steps: 2000896, wall_s: 7200, precision: fp32}
basic_seed1: {variant: basic, network: ff, training_seed: 1, steps: 2000896, wall_s: 7200, precision: bf16}
basic_seed2: {variant: basic, network: ff, training_seed: 2, steps: 2000896, wall_s: 7200}
basic_gru: {variant: basic, network: gru, training_seed: 0, steps: 2000896, wall_s: 9000}
"""


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def test_every_run_of_a_variant_gets_a_row_beside_the_same_random_hider(tmp_path, evaluations):
    result, stem = run(tmp_path, POLICIES)
    assert result.returncode == 0, result.stderr
    table = rows(str(stem) + ".csv")
    basic = [r for r in table if r["base_variant"] == "basic"]
    # The shipped policy first, the GRU next, then the other runs by name.
    assert [r["variant"] for r in basic] == ["basic", "basic_gru", "basic_seed0_2m", "basic_seed1", "basic_seed2"]
    assert all(r["living_random"] == "40.0" for r in basic)
    assert [r["network"] for r in basic] == ["ff", "gru", "ff", "ff", "ff"]
    assert basic[3]["training_seed"] == "1" and basic[3]["living_trained"] == "300.0"
    assert basic[3]["success_trained"] == "20.00" and basic[3]["training_steps"] == "2000896"
    # A variant without a policy still has its row, with the random hider only.
    slower = [r for r in table if r["base_variant"] == "slowerhider"]
    assert [(r["variant"], r["living_trained"], r["living_random"]) for r in slower] == [("slowerhider", "", "38.0")]
    md = open(str(stem) + ".md").read()
    assert "| basic_seed1 | 1 | 300.0 / 40.0 |" in md
    # The precision a run trained in is shown where policies.yaml records it, "-" where it does not.
    assert [r["training_precision"] for r in basic] == ["", "", "fp32", "bf16", ""]
    assert "| 2000896 | bf16 | 2.0 |" in md and "| 2000896 | - | 2.0 |" in md


def test_spread_over_training_seeds_takes_runs_of_equal_steps_and_network_only(tmp_path, evaluations):
    result, stem = run(tmp_path, POLICIES)
    assert result.returncode == 0, result.stderr
    spread = rows(str(stem) + "_seeds.csv")
    # The shipped 1.2M-step policy and the GRU are not pooled with the three 2M feed-forward runs.
    assert len(spread) == 1
    g = spread[0]
    assert (g["variant"], g["network"], g["training_steps"]) == ("basic", "ff", "2000896")
    assert g["training_seeds"] == "0 1 2"
    assert g["runs"] == "basic_seed0_2m basic_seed1 basic_seed2"
    # Pooled runs of different precisions say so, seed by seed ("?" where a run's is not recorded).
    assert g["precisions"] == "fp32 bf16 ?"
    assert g["living_mean"] == "450.0" and g["living_std"] == "150.0"   # 600, 300, 450
    assert (g["living_min"], g["living_max"]) == ("300.0", "600.0")
    assert g["success_mean"] == "40.00" and g["success_std"] == "20.00"
    assert "| basic | ff | 2000896 | 0 1 2 (basic_seed0_2m basic_seed1 basic_seed2) | fp32 bf16 ? | 450.0 ± 150.0" in \
        open(str(stem) + ".md").read()


def test_no_spread_table_with_one_seed_and_a_stale_one_is_removed(tmp_path, evaluations):
    (tmp_path / "table2_seeds.csv").write_text("stale\n")
    result, stem = run(tmp_path, "basic: {training_seed: 0, steps: 1200000, wall_s: 3600}\n")
    assert result.returncode == 0, result.stderr
    assert not os.path.exists(str(stem) + "_seeds.csv")
    assert "Spread over training seeds" not in open(str(stem) + ".md").read()
    assert [r["variant"] for r in rows(str(stem) + ".csv") if r["base_variant"] == "basic"] == ["basic", "basic_gru"]


def test_an_entry_that_names_no_variant_is_refused_by_name(tmp_path, evaluations):
    result, _ = run(tmp_path, POLICIES + "mystery_run: {training_seed: 3, steps: 10}\n")
    assert result.returncode != 0
    assert "mystery_run" in result.stderr and "variant" in result.stderr


def test_a_misspelt_variant_is_refused_not_dropped(tmp_path, evaluations):
    result, _ = run(tmp_path, POLICIES + "vr_run: {variant: visibilityreward-faster, training_seed: 0, steps: 10}\n")
    assert result.returncode != 0
    assert "vr_run" in result.stderr and "visibilityreward-faster" in result.stderr


def test_runs_go_to_their_own_variant_not_one_whose_name_is_a_prefix(tmp_path, evaluations):
    write_evaluation(evaluations, "visibilityreward_random", 39.0, 0.0)
    write_evaluation(evaluations, "visibilityreward_faster_random", 38.0, 0.0)
    write_evaluation(evaluations, "visibilityreward_faster_gru_trained", 200.0, 0.1)
    write_evaluation(evaluations, "visibilityreward_faster_seed1_trained", 150.0, 0.05)
    result, stem = run(tmp_path, POLICIES + "visibilityreward_faster_seed1: {variant: visibilityreward_faster, "
                                            "training_seed: 1, steps: 10}\n")
    assert result.returncode == 0, result.stderr
    table = rows(str(stem) + ".csv")
    assert [r["variant"] for r in table if r["base_variant"] == "visibilityreward"] == ["visibilityreward"]
    faster = [r for r in table if r["base_variant"] == "visibilityreward_faster"]
    assert [(r["variant"], r["living_trained"], r["living_random"]) for r in faster] == [
        ("visibilityreward_faster", "", "38.0"), ("visibilityreward_faster_gru", "200.0", "38.0"),
        ("visibilityreward_faster_seed1", "150.0", "38.0")]


def test_a_listed_run_without_an_evaluation_gets_no_row(tmp_path, evaluations):
    result, stem = run(tmp_path, POLICIES + "basic_seed3: {variant: basic, training_seed: 3, steps: 2000896}\n")
    assert result.returncode == 0, result.stderr
    assert "basic_seed3" not in [r["variant"] for r in rows(str(stem) + ".csv")]
    assert rows(str(stem) + "_seeds.csv")[0]["training_seeds"] == "0 1 2"


def test_the_spread_takes_one_run_per_seed_the_shipped_policy_first(tmp_path, evaluations):
    # The shipped basic policy has the same steps as basic_seed0_2m: seed 0 counts once, as the shipped one.
    policies = POLICIES.replace("basic: {training_seed: 0, steps: 1200000", "basic: {training_seed: 0, steps: 2000896")
    result, stem = run(tmp_path, policies)
    assert result.returncode == 0, result.stderr
    g = rows(str(stem) + "_seeds.csv")[0]
    assert g["training_seeds"] == "0 1 2" and g["runs"] == "basic basic_seed1 basic_seed2"
    assert g["living_mean"] == "416.7"   # 500, 300, 450
