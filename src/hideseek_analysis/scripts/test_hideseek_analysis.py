"""Tests of the analysis statistics: run with python3 -m pytest."""
import numpy as np
import pytest

import hideseek_analysis as ha


def synthetic(n_episodes=60, steps=50, dims=64, separable=True, seed=0):
    rng = np.random.default_rng(seed)
    groups = np.repeat(np.arange(n_episodes), steps)
    labels = rng.random(len(groups)) < 0.3
    features = rng.normal(size=(len(groups), dims))
    if separable:
        features[:, 5] += np.where(labels, 3.0, -3.0)  # one direction carries the label
    return features, labels, groups


def test_probe_reaches_about_100_percent_where_the_label_is_linearly_separable():
    features, labels, groups = synthetic(separable=True)
    r = ha.probe(features, labels, groups)
    assert r["accuracy"] > 0.98
    assert r["balanced_accuracy"] > 0.98


def test_probe_is_at_chance_on_random_features_and_says_so():
    features, labels, groups = synthetic(separable=False)
    r = ha.probe(features, labels, groups)
    # A probe on noise cannot beat predicting the majority class by much, and its balanced
    # accuracy stays near 0.5 even though plain accuracy sits near the 70 % prior.
    assert abs(r["balanced_accuracy"] - 0.5) < 0.06
    assert r["accuracy"] < r["majority_accuracy"] + 0.03
    assert 0.2 < r["positive_prior"] < 0.4


def test_probe_splits_by_episode():
    features, labels, groups = synthetic()
    r = ha.probe(features, labels, groups, test_size=0.25)
    assert r["test_episodes"] == 15
    assert r["train_samples"] + r["test_samples"] == len(labels)


def test_state_index_and_frequencies():
    assert list(ha.state_index([0, 0, 1, 1], [0, 1, 0, 1], [1, 0, 0, 1])) == [1, 2, 4, 7]
    f = ha.state_frequencies([0, 0, 7, 3])
    assert f.sum() == pytest.approx(1.0)
    assert f[0] == pytest.approx(0.5)
    assert ha.STATE_NAMES[6] == "S1 H1 O0"


def test_transition_probabilities_out_of_each_source_state_sum_to_one():
    # From state 0: to 1 twice and to 2 once; from 1: to 0 once; from 2: to 0 once. Repeats of a
    # state (0 0) are no transition.
    p, counts = ha.transitions([0, 0, 1, 0, 1, 0, 2, 0], [0] * 8)
    assert counts[0, 1] == 2 and counts[0, 2] == 1 and counts[1, 0] == 2 and counts[2, 0] == 1
    assert p[0, 1] == pytest.approx(2 / 3) and p[0, 2] == pytest.approx(1 / 3)
    assert p[1, 0] == pytest.approx(1.0)
    visited = ~np.isnan(p).all(axis=1)
    assert list(np.nonzero(visited)[0]) == [0, 1, 2]
    assert np.allclose(p[visited].sum(axis=1), 1.0)


def test_transitions_do_not_cross_episodes_and_unvisited_states_are_nan():
    # Episode 0: 0 -> 1 -> 1 -> 2; episode 1 starts in 5: the 2 -> 5 boundary is no transition.
    p, counts = ha.transitions([0, 1, 1, 2, 5, 5], [0, 0, 0, 0, 1, 1])
    assert counts[0, 1] == 1 and counts[1, 2] == 1 and counts[2, 5] == 0
    assert counts.sum() == 2
    assert np.isnan(p[3]).all()


def test_report_writes_every_file_from_synthetic_inputs(tmp_path):
    rows = run_report_on_synthetic_inputs(tmp_path, with_memory=False)
    trained_s = [r for r in rows if r["label"] == "S" and r["network"] == "trained"][0]
    assert float(trained_s["balanced_accuracy"]) > 0.9
    assert {r["representation"] for r in rows} == {"features"}


def test_report_probes_the_gru_state_of_a_recurrent_policy(tmp_path):
    rows = run_report_on_synthetic_inputs(tmp_path, with_memory=True)
    got = {(r["representation"], r["label"], r["network"]): float(r["balanced_accuracy"]) for r in rows}
    assert len(got) == 8 and len(rows) == 8
    # The synthetic GRU state carries H, the features do not: each probe reads its own array.
    assert got["gru_state", "H", "trained"] > 0.9
    assert got["features", "H", "trained"] < 0.7
    assert got["gru_state", "H", "random_init"] < 0.7


def run_report_on_synthetic_inputs(tmp_path, with_memory):
    import subprocess
    import sys
    import os
    rng = np.random.default_rng(2)
    inp, out = tmp_path / "in", tmp_path / "out"
    inp.mkdir()
    episodes = np.repeat(np.arange(20), 30)
    s, h, o = (rng.random((3, len(episodes))) < 0.4).astype(int)
    for name in ("trained", "random"):
        with open(inp / ("steps_%s.csv" % name), "w") as f:
            f.write("arena,episode,step,S,H,O,distance,hider_x,hider_y,hider_yaw,seeker_x,seeker_y,seeker_yaw,"
                    "hider_action,reward,outcome\n")
            for i, e in enumerate(episodes):
                f.write("0,%d,%d,%d,%d,%d,%.2f,%.2f,1.0,0.0,-2.0,-1.0,0.0,1,0.001,%d\n"
                        % (e, i % 30, s[i], h[i], o[i], 3.0 - 0.05 * (i % 30), 0.1 * (i % 30), int(i % 30 == 29)))
    with open(inp / "layouts.csv", "w") as f:
        f.write("episode,half_extent,x,y,size_x,size_y,yaw\n0,7,0,0,2,0.6,0\n0,7,0,0,0.6,2,0\n3,7,5,5,8,1,0.785\n")
    with open(inp / "features.csv", "w") as f:
        f.write("episode,step,S,H\n")
        for i, e in enumerate(episodes):
            f.write("%d,%d,%d,%d\n" % (e, i % 30, s[i], h[i]))
    features = rng.normal(size=(len(episodes), 512)).astype(np.float32)
    features[:, :8] += 3.0 * s[:, None]  # the label shows in a few directions
    np.save(inp / "features_trained.npy", features)
    np.save(inp / "features_random.npy", rng.normal(size=(len(episodes), 512)).astype(np.float32))
    if with_memory:
        memory = rng.normal(size=(len(episodes), 512)).astype(np.float32)
        memory[:, :8] += 3.0 * h[:, None]
        np.save(inp / "memory_trained.npy", memory)
        np.save(inp / "memory_random.npy", rng.normal(size=(len(episodes), 512)).astype(np.float32))
    here = os.path.dirname(os.path.abspath(__file__))
    subprocess.run([sys.executable, os.path.join(here, "report.py"), str(inp), str(out), "--variant", "basic",
                    "--policy", "synthetic", "--steps", "0", "--tsne-samples", "200"], check=True, cwd=here)
    for name in ("probes.csv", "probes.md", "tsne_S.png", "tsne_H.png", "state_frequencies.csv",
                 "state_frequencies.md", "state_frequencies.png", "transitions.csv", "transitions.png",
                 "distance_time.png"):
        assert (out / name).stat().st_size > 0, name
    with open(out / "probes.csv") as f:
        return list(csv_rows(f))


def csv_rows(f):
    import csv
    return csv.DictReader(f)
