"""The analysis across training seeds: the statistics (two-level bootstrap, probability of
improvement, rank correlation), Table 2 (table2.py), the claims (claims.py) and the figures
(seed_figures.py), on small made-up registries: no training, no ROS master. The sweep's queue has
its own tests (hideseek_pipeline)."""
import csv
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest
import yaml

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
ANALYSIS = os.path.join(ROOT, "src", "hideseek_analysis", "scripts")
sys.path.insert(0, os.path.join(ROOT, "src", "hideseek_analysis", "python"))
from hideseek_analysis import claims  # noqa: E402
from hideseek_analysis import stats as st  # noqa: E402


def make_records(tmp_path, runs):
    """A checkout-like folder: a registry with `runs` (name -> steps) and, for each, its greedy and
    sampled evaluations (episodes given as living-step lists)."""
    rec = tmp_path / "records"
    (rec / "policies").mkdir(parents=True)
    entries = {}
    for name, (variant, seed, steps, greedy, sampled) in runs.items():
        entries[name] = {"variant": variant, "network": "ff", "game": "v2", "training_seed": seed, "steps": steps,
                         "note": "sweep run (config/sweep.yaml), pinned at 0123456789ab"}
        for sub, living in (("", greedy), ("sampled", sampled)):
            if living is None:
                continue
            d = rec / "docs" / "runs" / name / sub
            d.mkdir(parents=True, exist_ok=True)
            with open(d / "episodes.csv", "w") as f:
                f.write("seed,living_steps,outcome\n")
                for i, x in enumerate(living):
                    f.write("%d,%d,%s\n" % (i, x, "survived" if x >= 1000 else "captured"))
            if not sub:
                (d / "trajectories.png").write_bytes(b"png")
            with open(d / "evaluation.csv", "w") as f:
                f.write("variant,policy,episodes,avg_living_steps,success_rate\n%s,%s,%d,%.2f,%.4f\n" % (
                    variant, name, len(living), np.mean(living), np.mean(np.array(living) >= 1000)))
    with open(rec / "policies" / "policies.yaml", "w") as f:
        yaml.safe_dump(entries, f, sort_keys=False)
    return rec


def drop_note(rec, name):
    path = rec / "policies" / "policies.yaml"
    entries = yaml.safe_load(path.read_text())
    del entries[name]["note"]
    path.write_text(yaml.safe_dump(entries, sort_keys=False))


# ---- statistics -------------------------------------------------------------------------------

def test_iqm_trims_a_quarter_at_each_end():
    assert st.iqm([0, 1, 2, 3, 4, 5, 6, 100]) == pytest.approx(np.mean([2, 3, 4, 5]))


def test_two_level_interval_covers_the_spread_between_runs():
    rng = np.random.default_rng(1)
    # Three runs that agree: a narrow interval. Three runs that differ by seed: a wide one.
    same = [rng.normal(300, 50, 100) for _ in range(3)]
    apart = [rng.normal(m, 50, 100) for m in (100, 300, 500)]
    _, (lo1, hi1) = st.pooled_statistic(same, st.mean, np.random.default_rng(0), 500)
    _, (lo2, hi2) = st.pooled_statistic(apart, st.mean, np.random.default_rng(0), 500)
    assert hi1 - lo1 < 40
    assert hi2 - lo2 > 150
    # an episode-level bootstrap alone would give about the narrow width for both
    assert lo2 < 250 and hi2 > 350


def test_probability_of_improvement():
    rng = np.random.default_rng(2)
    better = [np.full(100, 500.0), np.full(100, 600.0), np.full(100, 700.0)]
    worse = [np.full(100, 50.0), np.full(100, 60.0), np.full(100, 70.0)]
    poi = st.probability_of_improvement(better, worse, rng, 300)
    assert poi["runs"][0] == 1.0 and poi["runs"][1] == (1.0, 1.0)
    assert poi["episodes"][0] == 1.0
    same = st.probability_of_improvement(worse, worse, rng, 300)
    assert same["runs"][0] == pytest.approx(0.5)
    assert same["runs"][1][0] < 0.5 < same["runs"][1][1]


def test_rank_correlation_follows_the_reference_order():
    rng = np.random.default_rng(3)
    runs = [[np.full(50, float(m))] * 2 for m in (100, 200, 300, 400)]
    rho, (lo, hi) = st.rank_correlation(runs, [1, 2, 3, 4], rng, 200)
    assert rho == pytest.approx(1.0) and lo == pytest.approx(1.0)
    rho, _ = st.rank_correlation(runs, [4, 3, 2, 1], rng, 200)
    assert rho == pytest.approx(-1.0)


def run_analysis(script, rec, out, *extra):
    """One of the analysis scripts across training seeds on the made-up checkout `rec`, into `out`."""
    game = ["--game", "v2"] if script != "claims.py" and "--game" not in extra else []  # one game, into `out`
    r = subprocess.run([sys.executable, os.path.join(ANALYSIS, script), "--root", str(rec), "--out", str(out),
                        "--steps", "2048", "--reps", "200"] + game + list(extra), capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r.stderr
    return r


def test_table2_reads_the_sweep_runs_and_writes_the_tables(tmp_path):
    rec = make_records(tmp_path, {
        "basic_seed0": ("basic", 0, 2048, [100] * 10 + [1000] * 10, [50] * 20),
        "basic_seed1": ("basic", 1, 2048, [200] * 20, [60] * 20),
        "slowerhider_seed0": ("slowerhider", 0, 2048, [40] * 20, [40] * 20),
        # not a sweep run (another name) and a short one: both left out
        "basic_pilot_seed0": ("basic", 0, 2048, [5] * 20, None),
        "slowerhider_seed1": ("slowerhider", 1, 1024, [5] * 20, [5] * 20),
        # not trained by the sweep's queue (no sweep note): left out
        "stochasticmaps_seed0": ("stochasticmaps", 0, 2048, [5] * 20, [5] * 20),
    })
    drop_note(rec, "stochasticmaps_seed0")
    shutil.copytree(os.path.join(ROOT, "config"), rec / "config")
    out = tmp_path / "t2"
    run_analysis("table2.py", rec, out)
    with open(out / "table2.csv") as f:
        rows = {(x["variant"], x["mode"]): x for x in csv.DictReader(f)}
    b = rows[("basic", "greedy")]
    assert b["runs"] == "2" and b["run_names"] == "basic_seed0 basic_seed1"
    assert float(b["living_mean"]) == pytest.approx((100 * 10 + 1000 * 10 + 200 * 20) / 40)
    assert float(b["success_mean"]) == pytest.approx(0.25)
    assert float(b["living_mean_lo"]) <= float(b["living_mean"]) <= float(b["living_mean_hi"])
    assert rows[("slowerhider", "greedy")]["runs"] == "1"
    assert ("stochasticmaps", "greedy") not in rows
    assert rows[("basic", "sampled")]["per_run_living"] == "50.0 60.0"
    with open(out / "orderings.csv") as f:
        order = [x for x in csv.DictReader(f) if not x["better"].startswith("#")]
    assert [(x["better"], x["worse"]) for x in order] == [("basic", "slowerhider")]
    assert float(order[0]["poi_runs"]) == 1.0
    assert (out / "performance_profile.png").stat().st_size > 10000
    text = (out / "table2.md").read_text()
    assert "two-level bootstrap" in text and "| basic | paper, trained (8M steps) | 1 | 500 |" in text


def test_a_run_added_to_one_variant_leaves_the_other_variants_intervals_as_they_were(tmp_path):
    """Each estimate draws from its own generator: a new run of basic (the table's first row) must not
    move slowerhider's interval (it did while one generator served every row in turn)."""
    base = {"basic_seed0": ("basic", 0, 2048, [100] * 10 + [1000] * 10, [50] * 20),
            "basic_seed1": ("basic", 1, 2048, [200] * 15 + [700] * 5, [60] * 20),
            "slowerhider_seed0": ("slowerhider", 0, 2048, [40] * 10 + [90] * 10, [40] * 20),
            "slowerhider_seed1": ("slowerhider", 1, 2048, [60] * 10 + [30] * 10, [45] * 20)}
    rows = []
    for k, extra in enumerate(({}, {"basic_seed2": ("basic", 2, 2048, [300] * 20, [70] * 20)})):
        rec = make_records(tmp_path / str(k), dict(base, **extra))
        shutil.copytree(os.path.join(ROOT, "config"), rec / "config")
        run_analysis("table2.py", rec, tmp_path / str(k) / "t2")
        with open(tmp_path / str(k) / "t2" / "table2.csv") as f:
            rows.append({(x["variant"], x["mode"]): x for x in csv.DictReader(f)})
    assert rows[1][("basic", "greedy")]["runs"] == "3"
    for key in ("living_mean_lo", "living_mean_hi", "living_iqm_lo", "living_iqm_hi"):
        assert rows[0][("slowerhider", "greedy")][key] == rows[1][("slowerhider", "greedy")][key], key
    assert rows[0][("basic", "greedy")]["living_mean_hi"] != rows[1][("basic", "greedy")]["living_mean_hi"]


def test_mean_difference_interval_holds_zero_only_when_the_runs_overlap():
    rng = np.random.default_rng(4)
    far = st.mean_difference([np.full(50, 300.0), np.full(50, 320.0)], [np.full(50, 100.0), np.full(50, 110.0)], rng, 300)
    assert far[0] == pytest.approx(205.0) and far[1][0] > 0
    near = st.mean_difference([np.full(50, 100.0), np.full(50, 300.0)], [np.full(50, 150.0), np.full(50, 250.0)], rng, 300)
    assert near[0] == pytest.approx(0.0) and near[1][0] < 0 < near[1][1]


def test_the_two_readings_of_the_stochastic_seeker_are_compared_beside_the_table(tmp_path):
    """stochasticseeker (its seeker knows the spawn point) against stochasticseeker_explore: the
    difference with its interval, and which reading lands nearer the paper's 277 living steps."""
    rec = make_records(tmp_path, {
        "stochasticseeker_seed0": ("stochasticseeker", 0, 2048, [500] * 20, [500] * 20),
        "stochasticseeker_seed1": ("stochasticseeker", 1, 2048, [520] * 20, [520] * 20),
        "stochasticseeker_explore_seed0": ("stochasticseeker_explore", 0, 2048, [300] * 20, [300] * 20),
        "stochasticseeker_explore_seed1": ("stochasticseeker_explore", 1, 2048, [280] * 20, [280] * 20)})
    shutil.copytree(os.path.join(ROOT, "config"), rec / "config")
    out = tmp_path / "t2"
    run_analysis("table2.py", rec, out)
    with open(out / "readings.csv") as f:
        rows = {x["measure"]: x for x in csv.DictReader(f)}
    assert float(rows["living_mean"]["estimate"]) == pytest.approx(220.0)
    assert float(rows["living_mean"]["lo"]) > 0
    assert float(rows["poi_runs"]["estimate"]) == 1.0
    text = (out / "readings.md").read_text()
    assert "in living steps, stochasticseeker_explore (13.0 from the paper's 277, against 233.0)" in text
    assert "In living steps the interval of the difference excludes 0" in text
    assert "[readings.md](readings.md)" in (out / "table2.md").read_text()
    # Only one reading trained so far: no comparison is made up.
    rec2 = make_records(tmp_path / "one", {"stochasticseeker_seed0": ("stochasticseeker", 0, 2048, [500] * 20, None)})
    shutil.copytree(os.path.join(ROOT, "config"), rec2 / "config")
    run_analysis("table2.py", rec2, tmp_path / "one" / "t2")
    assert not (tmp_path / "one" / "t2" / "readings.csv").exists()
    assert "needs a run of each (stochasticseeker_explore has none)" in (tmp_path / "one" / "t2" / "readings.md").read_text()


def add_analysis(rec, name, gain_s, gain_h, s0h0o1=0.1):
    """A run's per-run analysis outputs as hideseek_pipeline analyze writes them (the parts the claims read)."""
    d = rec / "docs" / "runs" / name / "analysis"
    d.mkdir(parents=True, exist_ok=True)
    with open(d / "probes.csv", "w") as f:
        f.write("run,representation,target,C,train_images,test_images,test_positive_prior,accuracy,balanced_accuracy,"
                "random_init_mean,gain_over_random_init,pixels\n")
        for t, g in (("S", gain_s), ("H", gain_h), ("H|S=1", 0.0), ("H|S=0", 0.0)):
            f.write("%s,trained,%s,1,100,50,0.5,0.8,%.4f,0.7,%.4f,0.6\n" % (name, t, 0.7 + g, g))
    write_states(d / "states.csv", name, s0h0o1)


def write_states(path, name, s0h0o1):
    freq = [(1 - s0h0o1) / 7] * 8
    freq[1] = s0h0o1  # S0 H0 O1
    with open(path, "w") as f:
        f.write("run,state,S,H,O,steps,frequency\n")
        for i, x in enumerate(freq):
            f.write("%s,S%d H%d O%d,%d,%d,%d,0,%.5f\n" % (name, i >> 2 & 1, i >> 1 & 1, i & 1, i >> 2 & 1, i >> 1 & 1,
                                                         i & 1, x))


def run_claims(tmp_path, rec, *extra):
    shutil.copytree(os.path.join(ROOT, "config"), rec / "config", dirs_exist_ok=True)
    shutil.copy(os.path.join(ROOT, "docs", "calibration_table.csv"), rec / "docs" / "calibration_table.csv")
    out = tmp_path / "report"
    run_analysis("claims.py", rec, out, "--game", "v2", *extra)
    with open(out / "claims.csv") as f:
        return {x["claim"]: x for x in csv.DictReader(f)}


PAPER_VARIANTS = ("basic", "fasterhider", "visibilityreward_faster", "stochasticseeker", "stochasticmaps",
                  "visibilityreward", "slowerhider")


def test_claims_are_decided_only_with_two_runs_and_by_their_interval(tmp_path):
    runs = {"%s_seed%d" % (v, s): (v, s, 2048, [100 + 50 * k + 10 * s] * 20, [40] * 20)
            for k, v in enumerate(PAPER_VARIANTS) for s in range(3)}
    rec = make_records(tmp_path, runs)
    for v in PAPER_VARIANTS:
        for s, g in enumerate((0.10, 0.12, 0.08)):
            add_analysis(rec, "%s_seed%d" % (v, s), gain_s=g, gain_h=-g, s0h0o1=0.3)
    base = rec / "docs" / "analysis" / "baselines" / "slowerhider" / "random"
    base.mkdir(parents=True)
    write_states(base / "states.csv", "random", 0.1)
    c = run_claims(tmp_path, rec)
    assert c["Trained features beat random-init ones on S"]["result"] == "supported"
    assert float(c["Trained features beat random-init ones on S"]["effect"]) == pytest.approx(0.10, abs=1e-3)
    assert c["Trained features beat random-init ones on H"]["result"] == "contradicted"
    assert c["Trained features beat random-init ones on H"]["departure"] != ""
    assert c["slowerhider uses obstacles (not S, not H, O)"]["result"] == "supported"
    assert float(c["slowerhider uses obstacles (not S, not H, O)"]["effect"]) == pytest.approx(0.2, abs=1e-3)
    # living steps that rise along the paper's falling order (basic lowest here, highest there)
    assert c["Table 2's ordering of the variants"]["result"] == "contradicted"
    assert float(c["Table 2's ordering of the variants"]["effect"]) < -0.9
    assert c["Every variant's hider outlives the random hider"]["result"] == "supported"
    assert "not yet trained on game v2" in c["Failures come from a lack of memory"]["note"]
    assert c["Failures come from a lack of memory"]["result"] == "inconclusive"
    # one run of one variant is no interval over its training seeds: undecided, saying which
    for s in (1, 2):
        shutil.rmtree(rec / "docs" / "runs" / ("slowerhider_seed%d" % s) / "analysis")
    c = run_claims(tmp_path, rec)
    assert c["Trained features beat random-init ones on S"]["result"] == "inconclusive"
    assert "slowerhider" in c["Trained features beat random-init ones on S"]["note"]
    assert c["slowerhider uses obstacles (not S, not H, O)"]["result"] == "inconclusive"
    assert c["slowerhider uses obstacles (not S, not H, O)"]["ci_low"] == ""


def test_seed_figures_tsne_table3_and_behaviour_with_intervals_over_runs(tmp_path):
    rec = make_records(tmp_path, {"basic_seed%d" % s: ("basic", s, 2048, [100] * 20, [90] * 20) for s in range(3)})
    probe = rec / "docs" / "probe_set"
    probe.mkdir(parents=True)
    cells = [(i % 2, i // 2 % 2) for i in range(40)]
    with open(probe / "labels.csv", "w") as f:
        f.write("image,variant,S,H,episode,split\n")
        f.writelines("%d,basic,%d,%d,%d,test\n" % (i, s_, h, i) for i, (s_, h) in enumerate(cells))
    with open(probe / "tsne_baselines.csv", "w") as f:
        f.write("representation,target,images,neighbours,neighbour_balanced_accuracy\n"
                "random_init_0,S,40,10,0.6\nrandom_init_0,H,40,10,0.55\npixels,S,40,10,0.62\npixels,H,40,10,0.5\n")
    with open(probe / "tsne_random_init_0.csv", "w") as f:
        f.write("image,x,y\n" + "".join("%d,%d,%d\n" % (i, i, -i) for i in range(40)))
    for s, (score_s, score_h) in enumerate(((0.80, 0.70), (0.90, 0.72), (0.85, 0.74))):
        name = "basic_seed%d" % s
        add_analysis(rec, name, 0.08 + 0.02 * s, 0.1)
        d = rec / "docs" / "runs" / name / "analysis"
        with open(d / "tsne.csv", "w") as f:
            f.write("image,x,y\n" + "".join("%d,%.2f,%.2f\n" % (i, c[0] * 10 + s, c[1] * 10) for i, c in enumerate(cells)))
        with open(d / "behaviour.csv", "w") as f:
            f.write("run,episodes,steps,mean_living_steps,success_rate,backward_share,sees_seeker_share,seen_share,"
                    "line_of_sight_breaks_per_100,seeker_lost_per_100,distance_turns_per_100\n"
                    "%s,100,10000,100,0,%.2f,0.5,0.5,1,1,%d\n" % (name, 0.5 + 0.1 * s, 10 * s))
        with open(d / "tsne_neighbours.csv", "w") as f:
            f.write("run,target,images,neighbours,neighbour_balanced_accuracy,random_init_mean,pixels\n"
                    "%s,S,40,10,%.2f,0.6,0.62\n%s,H,40,10,%.2f,0.55,0.5\n" % (name, score_s, name, score_h))
    base = rec / "docs" / "analysis" / "baselines" / "basic" / "random"
    base.mkdir(parents=True)
    (base / "behaviour.csv").write_text((d / "behaviour.csv").read_text().replace("basic_seed2,", "random,")
                                        .replace(",0.70,", ",0.20,"))
    shutil.copytree(os.path.join(ROOT, "config"), rec / "config")
    out = tmp_path / "report"
    run_analysis("seed_figures.py", rec, out)
    # how each run behaves: the mean over runs with its interval, beside the random hider
    with open(out / "behaviour_seeds.csv") as f:
        b = {x["measure"]: x for x in csv.DictReader(f) if x["variant"] == "basic"}
    assert b["backward_share"]["runs"] == "3" and float(b["backward_share"]["trained"]) == pytest.approx(0.6)
    assert 0.5 <= float(b["backward_share"]["ci_low"]) < 0.6 < float(b["backward_share"]["ci_high"]) <= 0.7
    assert float(b["backward_share"]["random"]) == pytest.approx(0.2)
    assert float(b["distance_turns_per_100"]["trained"]) == pytest.approx(10)
    with open(out / "tsne_seeds.csv") as f:
        rows = {x["target"]: x for x in csv.DictReader(f) if x["variant"] == "basic"}
    assert rows["S"]["runs"] == "3" and float(rows["S"]["neighbour_balanced_accuracy"]) == pytest.approx(0.85)
    assert 0.8 <= float(rows["S"]["ci_low"]) < 0.85 < float(rows["S"]["ci_high"]) <= 0.9
    assert float(rows["H"]["random_init_mean"]) == pytest.approx(0.55) and float(rows["H"]["pixels"]) == 0.5
    assert (out / "tsne_seeds.png").stat().st_size > 20000
    # Table 3 across seeds, from the same runs' probes (add_analysis: gain 0.1, random init 0.7)
    with open(out / "table3_seeds.csv") as f:
        t3 = {x["target"]: x for x in csv.DictReader(f) if x["variant"] == "basic"}
    assert t3["S"]["runs"] == "3" and float(t3["S"]["gain"]) == pytest.approx(0.1)
    assert 0.08 <= float(t3["S"]["gain_ci_low"]) < 0.1 < float(t3["S"]["gain_ci_high"]) <= 0.12
    assert float(t3["S"]["trained"]) == pytest.approx(0.8) and float(t3["S"]["random_init_mean"]) == pytest.approx(0.7)
    assert float(t3["S"]["paper_trained"]) == pytest.approx(90.83)
    assert "| basic | H\\|S=1 | 3 |" in (out / "table3_seeds.md").read_text()  # a markdown row, not split at the |
    # a run without a t-SNE (analysed before it existed) is left out, not an error
    for name in ("basic_seed1", "basic_seed2"):
        os.remove(rec / "docs" / "runs" / name / "analysis" / "tsne_neighbours.csv")
    run_analysis("seed_figures.py", rec, out)
    with open(out / "tsne_seeds.csv") as f:
        rows = {x["target"]: x for x in csv.DictReader(f) if x["variant"] == "basic"}
    assert rows["S"]["runs"] == "1" and rows["S"]["ci_low"] == ""
    # two runs: a bootstrap over them returns their range, and the tables say so instead of "95 % CI"
    shutil.rmtree(rec / "docs" / "runs" / "basic_seed2" / "analysis")
    run_analysis("seed_figures.py", rec, out)
    assert "| basic | S | 2 | 79.0 (range of 2 runs: 78.0 to 80.0) |" in (out / "table3_seeds.md").read_text()


def add_gru_runs(rec, living, with_memory, without_memory, seeds=(0, 1, 2), variants=("basic", "slowerhider",
                                                                                       "stochasticmaps")):
    """GRU sweep runs <variant>_gru_seed<S> in the registry, with their greedy evaluation (`living`,
    episodes per seed) and the per-run analysis' living steps with memory and with the memoryless
    ablation (one value per seed each)."""
    path = rec / "policies" / "policies.yaml"
    entries = yaml.safe_load(path.read_text())
    for v in variants:
        for s in seeds:
            name = "%s_gru_seed%d" % (v, s)
            entries[name] = {"variant": v, "network": "gru", "game": "v2", "training_seed": s, "steps": 2048,
                             "note": "sweep run (config/sweep.yaml), pinned at 0123456789ab"}
            d = rec / "docs" / "runs" / name
            (d / "analysis" / "memoryless").mkdir(parents=True, exist_ok=True)
            with open(d / "episodes.csv", "w") as f:
                f.write("seed,living_steps,outcome\n" + "".join("%d,%d,captured\n" % (i, x)
                                                                 for i, x in enumerate(living[s])))
            for sub, x in (("", with_memory[s]), ("memoryless", without_memory[s])):
                with open(d / "analysis" / sub / "behaviour.csv", "w") as f:
                    f.write("run,episodes,steps,mean_living_steps,success_rate,backward_share,sees_seeker_share,"
                            "seen_share,line_of_sight_breaks_per_100,seeker_lost_per_100,distance_turns_per_100\n"
                            "%s,100,%d,%.2f,0,0.1,0.5,0.5,1,1,10\n" % (name, 100 * x, x))
    path.write_text(yaml.safe_dump(entries, sort_keys=False))


def test_the_memory_claim_pairs_each_gru_run_with_its_feed_forward_twin(tmp_path):
    memory_claim = "Failures come from a lack of memory"
    # Feed-forward runs of seed s live 100 + 100 s; a made-up pilot of basic, seed 0, lives 900.
    runs = {"%s_seed%d" % (v, s): (v, s, 2048, [100 + 100 * s] * 20, [90] * 20)
            for v in ("basic", "slowerhider", "stochasticmaps") for s in range(3)}
    runs["basic_v2r3pilot_seed0"] = ("basic", 0, 2048, [900] * 20, [900] * 20)
    rec = make_records(tmp_path, runs)
    # GRU runs of seed s live 150 + 101 s: 50, 51 and 52 more than their twins; their memory is worth +80.
    add_gru_runs(rec, {s: [150 + 101 * s] * 20 for s in range(3)}, [200] * 3, [120] * 3)
    # --extra brings the pilot into the feed-forward runs; the GRU's twin is still basic_seed0.
    c = run_claims(tmp_path, rec, "--extra", "basic_v2r3pilot_seed0")
    m = c[memory_claim]
    assert m["result"] == "supported", m
    assert float(m["effect"]) == pytest.approx(51.0)
    # Paired by seed the differences are 50-52; paired any other way they would be -50 or 250.
    assert 50 <= float(m["ci_low"]) < 51 < float(m["ci_high"]) <= 52
    assert "memory minus memoryless 80.0" in m["measure"] and m["note"] == ""
    assert m["runs"] == "basic 3, slowerhider 3, stochasticmaps 3"
    # the GRU runs are not counted as feed-forward runs of their variants
    assert "slowerhider 3" in c["Table 2's ordering of the variants"]["runs"]
    with open(tmp_path / "report" / "memory_seeds.csv") as f:
        t = {x["variant"]: x for x in csv.DictReader(f)}
    assert float(t["basic"]["gru"]) == pytest.approx(251.0) and float(t["basic"]["ff"]) == pytest.approx(200.0)
    assert 50 <= float(t["basic"]["difference_ci_low"]) <= float(t["basic"]["difference_ci_high"]) <= 52
    assert float(t["slowerhider"]["memory_gain"]) == pytest.approx(80.0) and t["slowerhider"]["runs"] == "3"
    row = [x for x in (tmp_path / "report" / "memory_seeds.md").read_text().splitlines() if x.startswith("| slowerhider")]
    assert len(row) == 1 and row[0].startswith("| slowerhider | 3 | 251.0 [") and "| 51.0 [5" in row[0]
    assert row[0].endswith("| 80.0 [80.0, 80.0] |")
    # It lives longer, but zeroing its state every step costs it nothing: not shown to be its memory.
    add_gru_runs(rec, {s: [150 + 101 * s] * 20 for s in range(3)}, [200, 201, 199], [201, 200, 200])
    m = run_claims(tmp_path, rec)[memory_claim]
    assert m["result"] == "inconclusive" and "not shown to be memory" in m["note"]
    # One GRU run not yet analysed: no ablation for every run, so not decided on the ablation.
    add_gru_runs(rec, {s: [150 + 101 * s] * 20 for s in range(3)}, [200] * 3, [120] * 3)
    shutil.rmtree(rec / "docs" / "runs" / "slowerhider_gru_seed2" / "analysis")
    m = run_claims(tmp_path, rec)[memory_claim]
    assert m["result"] == "inconclusive" and "no memoryless ablation for every GRU run of: slowerhider" in m["note"]
    # The GRU lives shorter than its twin: contradicted, with the rule that could cause it.
    add_gru_runs(rec, {s: [60 + 100 * s] * 20 for s in range(3)}, [200] * 3, [120] * 3)
    m = run_claims(tmp_path, rec)[memory_claim]
    assert m["result"] == "contradicted" and float(m["ci_high"]) < 0 and "8M" in m["departure"]
    # A twin not yet evaluated, and a GRU run with no twin at all (seed 7), are left unpaired, not an error.
    os.remove(rec / "docs" / "runs" / "stochasticmaps_seed1" / "episodes.csv")
    add_gru_runs(rec, {7: [150] * 20}, {7: 200}, {7: 120}, seeds=(7,), variants=("stochasticmaps",))
    m = run_claims(tmp_path, rec)[memory_claim]
    assert "stochasticmaps 2" in m["runs"] and m["result"] == "contradicted"
    # One GRU run of stochasticmaps is no interval over its seeds: undecided, naming the variant.
    os.remove(rec / "docs" / "runs" / "stochasticmaps_gru_seed2" / "episodes.csv")
    m = run_claims(tmp_path, rec)[memory_claim]
    assert m["result"] == "inconclusive" and "stochasticmaps" in m["note"] and "stochasticmaps 1" in m["runs"]
    assert m["ci_low"] == ""
    # GRU runs whose evaluation has not come back: the claim says so.
    path = rec / "policies" / "policies.yaml"
    for name in yaml.safe_load(path.read_text()):
        if "_gru_" in name and (rec / "docs" / "runs" / name / "episodes.csv").exists():
            os.remove(rec / "docs" / "runs" / name / "episodes.csv")
    m = run_claims(tmp_path, rec)[memory_claim]
    assert m["result"] == "inconclusive" and "have no evaluation or no evaluated feed-forward twin" in m["note"]
    # No GRU run at all: the claim says so.
    path.write_text(yaml.safe_dump({k: e for k, e in yaml.safe_load(path.read_text()).items() if "_gru_" not in k},
                                   sort_keys=False))
    m = run_claims(tmp_path, rec)[memory_claim]
    assert m["result"] == "inconclusive" and "not yet trained on game v2" in m["note"] and m["effect"] == ""


def test_a_claim_decided_on_two_runs_of_a_variant_is_marked_provisional():
    two = {"result": "contradicted", "runs": "fasterhider 2, visibilityreward_faster 3, basic 3", "note": ""}
    three = {"result": "supported", "runs": "basic 3, slowerhider 4", "note": ""}
    undecided = {"result": "inconclusive", "runs": "basic 2", "note": "needs more"}
    for r in (two, three, undecided):
        claims.mark_provisional(r)
    assert two["note"].startswith("provisional") and three["note"] == "" and undecided["note"] == "needs more"


def test_the_interval_decides_the_size_as_it_decides_the_direction():
    size = claims.PRACTICAL["share"][0]
    assert claims.verdict((0.004, 0.011), 3, 1.0, size) == "negligible"  # wholly under 0.02 of the steps
    assert claims.verdict((0.03, 0.05), 3, 1.0, size) == "supported"
    assert claims.verdict((-0.05, -0.03), 3, 1.0, size) == "contradicted"
    assert claims.verdict((-0.05, -0.03), 3, -1.0, size) == "supported"  # the paper's side is below zero
    assert claims.verdict((-0.01, 0.05), 3, 1.0, size) == "inconclusive"
    assert claims.verdict((0.03, 0.05), 1, 1.0, size) == "inconclusive"  # one run: no interval over seeds
    # An interval that excludes zero but crosses the size shows the direction, not the size, whichever
    # side of the size its point lies: v3's oscillation, 0.36 [0.21, 0.58] swings against 0.5, and
    # v2's transition 1, 0.289 [0.012, 0.573] per 100 steps against 0.2.
    swings, rate = claims.PRACTICAL["swings"][0], claims.PRACTICAL["rate"][0]
    assert claims.verdict((0.206, 0.580), 3, 1.0, swings) == "inconclusive"
    assert claims.verdict((-0.580, -0.206), 3, 1.0, swings) == "inconclusive"
    assert claims.verdict((0.012, 0.573), 3, 1.0, rate) == "inconclusive"
    assert claims.verdict((-0.573, -0.012), 3, 1.0, rate) == "inconclusive"
    assert claims.verdict((0.206, 0.45), 3, 1.0, swings) == "negligible"
    assert claims.verdict((0.2, 0.573), 3, 1.0, rate) == "supported"  # at the size counts


def test_the_concave_curve_is_decided_on_its_coefficient_s_interval_as_bends():
    """The practical size is a bend of balanced accuracy: the coefficient's interval is decided once
    turned into bends across the runs' range (here (0.7 / 2)^2 = 0.1225 of the coefficient)."""
    x = np.array([0.04, 0.3, 0.74])
    ci = (0.02, 0.07)  # a convex curve, but its bends, [0.0025, 0.0086], all under 0.01
    bends = tuple(np.multiply(ci, claims.bend_scale(x)))
    assert np.allclose(bends, (0.00245, 0.008575))
    assert claims.verdict(bends, 3, -1.0, claims.PRACTICAL["bend"][0]) == "negligible"
    assert claims.verdict(ci, 3, -1.0, claims.PRACTICAL["bend"][0]) == "contradicted"  # the coefficient as a bend


def write_behaviour(rec, name, turns, swings=None):
    d = rec / "docs" / "runs" / name / "analysis"
    d.mkdir(parents=True, exist_ok=True)
    cols = "run,episodes,steps,mean_living_steps,success_rate,backward_share,sees_seeker_share,seen_share," \
           "line_of_sight_breaks_per_100,seeker_lost_per_100,distance_turns_per_100"
    row = "%s,100,10000,100,0,0.5,0.5,0.5,1,1,%s" % (name, turns)
    if swings is None:
        (d / "swings.csv").unlink(missing_ok=True)
    else:
        cols, row = cols + ",distance_swings_per_100", row + ",%s" % swings
        (d / "swings.csv").write_text("run,threshold_m,swings_per_100\n" + "".join(
            "%s,%s,%s\n" % (name, t, swings * f) for t, f in ((0.25, 8), (0.5, 3), (1.0, 1), (2.0, 0.5))))
    (d / "behaviour.csv").write_text(cols + "\n" + row + "\n")


def test_oscillation_counts_swings_of_a_metre_and_names_runs_without_them(tmp_path):
    """basic wobbles (many turns, no swing of 1 m), the faster hiders swing: supported on swings,
    though the old measure (turns) says the opposite; a run analysed before the swings is named."""
    variants = ("basic", "fasterhider", "visibilityreward_faster")
    rec = make_records(tmp_path, {"%s_seed%d" % (v, s): (v, s, 2048, [100] * 20, [90] * 20)
                                  for v in variants for s in range(3)})
    for s in range(3):
        write_behaviour(rec, "basic_seed%d" % s, 30 + s, 0.01 * s)
        write_behaviour(rec, "fasterhider_seed%d" % s, 2, 1.5 + 0.1 * s)
        write_behaviour(rec, "visibilityreward_faster_seed%d" % s, 2, 1.2 + 0.1 * s)
    c = run_claims(tmp_path, rec)["The faster hiders' distance oscillates"]
    assert c["result"] == "supported", c
    assert float(c["effect"]) == pytest.approx(1.45 - 0.01, abs=1e-3)
    assert "the old measure" in c["measure"] and "-2" in c["measure"]  # turns: faster minus basic near -29
    table = (tmp_path / "report" / "oscillation_thresholds.md").read_text()
    assert "| basic | basic_seed1 | 31.00 | 0.08 | 0.03 | 0.01 | 0.01 |" in table
    write_behaviour(rec, "fasterhider_seed2", 2)  # analysed before the swings, weights lost
    c = run_claims(tmp_path, rec)["The faster hiders' distance oscillates"]
    assert "no swings measured for fasterhider_seed2" in c["note"]
    assert "| fasterhider | fasterhider_seed2 | 2.00 | - | - | - | - |" in (
        tmp_path / "report" / "oscillation_thresholds.md").read_text()


def write_state_tables(d, name, seq, episode_steps=100):
    """states.csv and transitions.csv of a run (or the random hider) whose every episode follows seq."""
    from hideseek_analysis import states as hs
    d.mkdir(parents=True, exist_ok=True)
    states = np.tile(seq, 10)
    _, tc = hs.transitions(states, np.repeat(np.arange(10), len(seq)))
    counts = np.bincount(states, minlength=8)
    with open(d / "states.csv", "w") as f:
        f.write("run,state,S,H,O,steps,frequency\n" + "".join(
            "%s,%s,%d,%d,%d,%d,%.5f\n" % (name, hs.STATE_NAMES[i], i >> 2 & 1, i >> 1 & 1, i & 1, counts[i],
                                          counts[i] / counts.sum()) for i in range(8)))
    with open(d / "transitions.csv", "w") as f:
        f.write("run,from,to,count,probability\n" + "".join(
            "%s,%s,%s,%d,\n" % (name, hs.STATE_NAMES[a], hs.STATE_NAMES[b], tc[a, b])
            for a in range(8) for b in range(8) if a != b))


def test_a_transition_missed_is_split_into_its_factors_and_the_claim_points_to_them(tmp_path):
    """Two runs of each variant that miss the random hider's turning away on opposite factors: one
    seldom in S1H1 but quick to leave it, one always there and slow to leave. Both turn away less
    often per step than a random hider that sits there half the time: the claim is contradicted and
    points to the factors, which the table gives run by run, each row multiplying out to its rate."""
    S1H1, S0H1, S0H0 = 6, 2, 0
    seldom = [S1H1] * 10 + [S0H1] * 10 + [S0H0] * 80  # in S1H1 0.1, leaves 10 per 100 there, to S0H1: 1 per 100
    stays = [S1H1] * 99 + [S0H1]  # in S1H1 0.99, leaves 1.01 per 100 there, to S0H1: 1 per 100
    random_hider = ([S1H1] * 25 + [S0H1] * 25) * 2  # in S1H1 0.5, leaves 4 per 100 there, to S0H1: 2 per 100
    rec = make_records(tmp_path, {"%s_seed%d" % (v, s): (v, s, 2048, [100] * 20, [90] * 20)
                                  for v in PAPER_VARIANTS for s in range(2)})
    for v in PAPER_VARIANTS:
        for s, seq in enumerate((seldom, stays)):
            write_state_tables(rec / "docs" / "runs" / ("%s_seed%d" % (v, s)) / "analysis", "%s_seed%d" % (v, s), seq)
        write_state_tables(rec / "docs" / "analysis" / "baselines" / v / "random", "random", random_hider)
    claims_of = run_claims(tmp_path, rec)
    c = claims_of["Transition 1: seen and seeing, the trained hider turns away (S1H1 -> S0H1)"]
    assert c["result"] == "contradicted" and float(c["effect"]) == pytest.approx(1.0 - 2.0)
    assert "[transitions_factors_seeds.md](transitions_factors_seeds.md)" in c["departure"]
    assert "transitions_factors_seeds.md" in claims_of["basic turns away, then runs"]["departure"]
    shutil.copytree(os.path.join(ROOT, "config"), rec / "config", dirs_exist_ok=True)
    out = tmp_path / "figures"
    run_analysis("seed_figures.py", rec, out)
    with open(out / "transitions_factors_seeds.csv") as f:
        rows = {x["run"]: x for x in csv.DictReader(f)
                if x["variant"] == "stochasticmaps" and x["transition"].startswith("turns away")}
    expected = {"stochasticmaps_seed0": (0.1, 10.0, 1.0, 1.0), "stochasticmaps_seed1": (0.99, 100 / 99, 1.0, 1.0),
                "random hider": (0.5, 4.0, 1.0, 2.0)}
    for run, values in expected.items():
        got = [float(rows[run][k]) for k in ("time_in", "leave_rate", "given", "rate")]
        assert got == pytest.approx(values, abs=1e-4), run
        assert got[0] * got[1] * got[2] == pytest.approx(got[3], abs=1e-3), run
    assert float(rows["mean of 2 runs"]["rate"]) == pytest.approx(1.0) and rows["mean of 2 runs"]["time_in"] == ""
    md = (out / "transitions_factors_seeds.md").read_text()
    assert "| turns away: S1H1 -> S0H1 | stochasticmaps | stochasticmaps_seed1 | 0.990 | 1.0 | 1.000 | 1.00 |" in md
    assert "| turns away: S1H1 -> S0H1 | stochasticmaps | random hider | 0.500 | 4.0 | 1.000 | 2.00 |" in md
    # a run that never leaves S0H1 for anywhere: rate 0, where it goes undefined, not 0
    assert "| leaves the view: S0H1 -> S0H0 | stochasticmaps | stochasticmaps_seed1 | 0.010 | 0.0 | - | 0.00 |" in md


def test_a_retrain_never_enters_table2_or_a_claim(tmp_path):
    runs = {"basic_seed%d" % s: ("basic", s, 2048, [100 + 10 * s] * 20, [90] * 20) for s in range(3)}
    runs["basic_seed0_retrain"] = ("basic", 0, 2048, [900] * 20, [900] * 20)
    rec = make_records(tmp_path, runs)
    path = rec / "policies" / "policies.yaml"
    entries = yaml.safe_load(path.read_text())
    entries["basic_seed0_retrain"].update(draw="retrain", retrain_of="basic_seed0")
    path.write_text(yaml.safe_dump(entries, sort_keys=False))
    shutil.copytree(os.path.join(ROOT, "config"), rec / "config")
    run_analysis("table2.py", rec, tmp_path / "t2")
    rows = list(csv.DictReader(open(tmp_path / "t2" / "table2.csv")))
    basic = next(r for r in rows if r["variant"] == "basic" and r["mode"] == "greedy")
    assert basic["run_names"] == "basic_seed0 basic_seed1 basic_seed2"
    r = subprocess.run([sys.executable, os.path.join(ANALYSIS, "table2.py"), "--root", str(rec), "--out",
                        str(tmp_path / "t3"), "--extra", "basic_seed0_retrain"], capture_output=True, text=True)
    assert r.returncode != 0 and "a retrain never enters Table 2 or a claim" in r.stderr


def test_the_claims_on_both_games_sit_side_by_side_with_the_budget_check_last(tmp_path):
    """Each game's claims into REPORT/<game>/, both in one table; basic's 8M runs against its 2M runs
    on v3, and which verdicts move with them; a run of one game never counts for the other."""
    runs = {"basic_seed%d" % s: ("basic", s, 2048, [100 + s] * 20, None) for s in range(3)}
    runs.update({"basic_v3_seed%d" % s: ("basic", s, 2048, [300 + 10 * s] * 20, None) for s in range(3)})
    runs.update({"basic_v3_8m_seed%d" % s: ("basic", s, 8000000, [600 + 10 * s] * 20, None) for s in range(3)})
    rec = make_records(tmp_path, runs)
    entries = yaml.safe_load((rec / "policies" / "policies.yaml").read_text())
    for name, e in entries.items():
        e["game"] = "v3" if "_v3" in name else "v2"
    (rec / "policies" / "policies.yaml").write_text(yaml.safe_dump(entries, sort_keys=False))
    shutil.copytree(os.path.join(ROOT, "config"), rec / "config")
    # a seeker's steps are no hider's budget: the budget check stays basic's 8M
    with open(rec / "config" / "sweep.yaml", "a") as f:
        f.write("  - {name: long_seeker, commit: 'x', game: v3, role: seeker, variants: [basic], seeds: [0], "
                "steps: 16000000}\n")
    for f in ("calibration_table.csv", "calibration_table_v3.csv"):
        shutil.copy(os.path.join(ROOT, "docs", f), rec / "docs" / f)
    out = tmp_path / "report"
    run_analysis("claims.py", rec, out)
    both = (out / "claims.md").read_text()
    assert "| claim | paper | v2: result | v2: effect [95 % CI] (runs) | v3: result |" in both
    for game in ("v2", "v3"):
        with open(out / game / "claims.csv") as f:
            rows = {x["claim"]: x for x in csv.DictReader(f)}
        assert "basic 3" in rows["Table 2's ordering of the variants"]["runs"]
    last = both.strip().splitlines()[-1]
    assert last.startswith("| Training longer: basic at 8M steps against 2M |")
    # 8M minus 2M on v3: (600 + 610 + 620) / 3 - (300 + 310 + 320) / 3 = 300 living steps
    assert "| **supported** | 300.000 [" in last and "(basic 8m 3, basic 2M 3)" in last
    assert "the A mode: v2 brakes on every turn, v3 keeps the hider's momentum" in both
    # the table has no measure column: the claim on every variant names the variant it was decided on
    outlives = next(line for line in both.splitlines() if line.startswith("| Every variant's hider outlives"))
    assert "(basic's, the lowest lower bound; basic 3)" in outlives, outlives


def test_a_miss_names_only_the_causes_its_game_still_has_and_says_when_none_is_left():
    """The "what could cause a miss" cell: v2 names its A mode and seeker motion; v3, which has
    neither, says that no tested cause is left rather than leaving the cell empty; a cause that both
    games share (the 2M budget, which the 8M check on basic tests) stays on both."""
    on_v2 = claims.Causes(("a_mode", "seeker_motion"), "v2")
    assert "A mode brakes on every turn" in on_v2 and "turns or moves, never both" in on_v2
    on_v3 = claims.Causes(("a_mode", "seeker_motion"), "v3")
    assert on_v3.startswith("no tested cause left on game v3: what could cause it on v2 is gone here")
    assert "v3 keeps the hider's momentum" in on_v3 and "v3 turns while it moves" in on_v3
    assert on_v3.keys == ("a_mode", "seeker_motion")  # the side-by-side table's "what changed" reads them
    basic = claims.Causes(("seeker_motion", "steps"), "v3")
    assert basic.startswith(claims.DEPARTURES["steps"]) and "8M budget check on basic" in basic
    assert basic.endswith("(gone on game v3, which could cause it on v2: the seeker: v2 turns or moves, v3 turns "
                          "while it moves)")
    assert claims.Causes(("seeker_motion", "steps"), "v2") == "; ".join(
        claims.DEPARTURES[k] for k in ("seeker_motion", "steps"))
    assert claims.Causes((), "v3") == ""
