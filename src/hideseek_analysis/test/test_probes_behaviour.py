"""probes.py (probes on the shared probe set) and behaviour.py (a run's states, transitions,
distance and behaviour) on synthetic data whose answers are known."""
import csv
import os
import sys

import numpy as np
import pytest

SCRIPTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts")
sys.path[:0] = [SCRIPTS, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python")]
import behaviour  # noqa: E402
import probes  # noqa: E402


def synthetic_labels(n_episodes=40, per_episode=30, seed=0):
    rng = np.random.default_rng(seed)
    n = n_episodes * per_episode
    episode = np.repeat(np.arange(n_episodes), per_episode)
    return {"S": rng.integers(0, 2, n), "H": rng.integers(0, 2, n), "episode": episode,
            "test": episode % 10 < 3, "variant": np.array(["basic"] * n)}


def test_a_feature_that_encodes_the_label_is_found_and_noise_is_not():
    labels = synthetic_labels()
    rng = np.random.default_rng(1)
    n = len(labels["S"])
    noise = rng.normal(size=(n, 20))
    informative = noise.copy()
    informative[:, 3] += 3.0 * labels["S"]
    informative[:, 7] += 3.0 * labels["H"]
    good = {r["target"]: r for r in probes.probe_all(informative, labels, "x")}
    bad = {r["target"]: r for r in probes.probe_all(noise, labels, "x")}
    for t in probes.TARGETS:
        assert good[t]["balanced_accuracy"] > 0.85, t
        assert abs(bad[t]["balanced_accuracy"] - 0.5) < 0.12, t
    # H where S = 1 uses only those images, scored on the test episodes alone
    assert good["H|S=1"]["test_images"] == int((labels["S"] == 1)[labels["test"]].sum())
    assert good["S"]["train_images"] + good["S"]["test_images"] == n


def test_regularisation_is_chosen_on_train_episodes():
    labels = synthetic_labels()
    rng = np.random.default_rng(2)
    x = rng.normal(size=(len(labels["S"]), 300))
    x[:, 0] += 0.8 * labels["S"]
    r = probes.probe(x, labels, "S")
    assert r["C"] in probes.CS
    # with 300 noisy features and one weak signal, strong regularisation wins
    assert r["C"] <= 0.1


def test_pixel_baseline_averages_4x4_blocks():
    images = np.zeros((2, 84, 84, 3), dtype=np.uint8)
    images[1, :4, :4, 0] = 255
    f = probes.pixel_features(images)
    assert f.shape == (2, 21 * 21 * 3)
    assert f[1, 0] == pytest.approx(1.0) and f[1, 1] == 0.0 and f[0].max() == 0.0


def write_steps(path, episodes):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["seed", "step", "hider_x", "hider_y", "hider_yaw", "seeker_x", "seeker_y", "seeker_yaw", "S", "H", "O",
                    "distance", "hider_action", "outcome"])
        for seed, steps in episodes:
            for k, (s, h, o, dist, action) in enumerate(steps):
                last = k == len(steps) - 1
                w.writerow([seed, k, 0, 0, 0, 1, 1, 0, s, h, o, dist, action,
                            ("survived" if len(steps) >= 1000 else "captured") if last else ""])


def test_behaviour_counts_states_transitions_and_behaviour(tmp_path):
    # episode 0: seen and seeing, turns away (S 1 -> 0), then breaks the line of sight (H 1 -> 0)
    e0 = [(1, 1, 0, 5.0, 3), (0, 1, 0, 5.5, 2), (0, 0, 1, 6.0, 2), (0, 0, 1, 6.5, 1)]
    e1 = [(1, 1, 0, 2.0, 0), (1, 1, 0, 1.0, 0)]
    steps = tmp_path / "steps.csv"
    write_steps(steps, [(10000, e0), (10001, e1)])
    # as play_episodes writes it: the arenas' steps interleaved, step by step
    with open(steps) as f:
        header, *body = f.read().splitlines()
    body.sort(key=lambda line: (int(line.split(",")[1]), int(line.split(",")[0])))
    steps.write_text("\n".join([header] + body) + "\n")
    out = tmp_path / "out"
    behaviour.write(str(out), behaviour.summarise(behaviour.read_steps(str(steps))), "r")
    with open(out / "behaviour.csv") as f:
        row = next(csv.DictReader(f))
    assert row["episodes"] == "2" and row["steps"] == "6"
    assert float(row["mean_living_steps"]) == 3.0 and float(row["success_rate"]) == 0.0
    assert float(row["backward_share"]) == pytest.approx(2 / 6, abs=1e-4)
    assert float(row["line_of_sight_breaks_per_100"]) == pytest.approx(100 / 6, abs=1e-2)
    with open(out / "transitions.csv") as f:
        t = {(r["from"], r["to"]): r for r in csv.DictReader(f)}
    assert len(t) == 56
    assert t[("S1 H1 O0", "S0 H1 O0")]["count"] == "1" and t[("S1 H1 O0", "S0 H1 O0")]["probability"] == "1.0"
    assert t[("S0 H1 O0", "S0 H0 O1")]["count"] == "1"
    # no transition across the episode boundary (e0's last state to e1's first)
    assert t[("S0 H0 O1", "S1 H1 O0")]["count"] == "0"
    with open(out / "states.csv") as f:
        s = {r["state"]: r for r in csv.DictReader(f)}
    assert s["S1 H1 O0"]["steps"] == "3"
    with open(out / "distance.csv") as f:
        d = list(csv.DictReader(f))
    assert float(d[0]["mean_distance"]) == pytest.approx((5 + 5.5 + 6 + 6.5 + 2 + 1) / 6, abs=1e-3)
    assert d[0]["episodes_running"] == "2" and d[1]["mean_distance"] == ""


def test_swings_count_reversals_of_at_least_the_threshold_and_never_a_wobble():
    # an orbit's wobble: 0.3 m up and down, 40 times: no swing of 1 m, many turns
    wobble = [2.0 + 0.3 * (k % 2) for k in range(80)]
    assert behaviour.swings(wobble, 1.0) == 0
    assert behaviour.swings(wobble, 0.25) == 78  # every reversal is at least 0.25 m
    # waits while the seeker comes 3 m closer, runs 4 m away, waits again, runs: 3 reversals of >= 1 m
    wait_run = [5, 4, 3, 2, 4, 6, 5, 4, 3, 6.5, 6.4]
    assert behaviour.swings(wait_run, 1.0) == 3
    assert behaviour.swings(wait_run, 2.0) == 3
    assert behaviour.swings(wait_run, 3.5) == 0  # no reversal reaches 3.5 m
    assert behaviour.swings([1.0, 1.5, 1.9], 1.0) == 0  # one way only


def test_behaviour_reports_swings_at_each_threshold(tmp_path):
    # comes 3 m closer, runs 4 m away, then wobbles by 0.3 m at 6 m for 30 steps
    dists = [5, 4.5, 4, 3.5, 3, 2.5, 2, 3, 4, 5, 6] + [6 - 0.3 * (k % 2) for k in range(30)]
    e0 = [(1, 1, 0, dist, 2) for dist in dists]
    steps = tmp_path / "steps.csv"
    write_steps(steps, [(10000, e0)])
    out = tmp_path / "out"
    behaviour.write(str(out), behaviour.summarise(behaviour.read_steps(str(steps))), "r")
    with open(out / "behaviour.csv") as f:
        row = next(csv.DictReader(f))
    assert float(row["distance_swings_per_100"]) == pytest.approx(100 / 41, abs=1e-2)  # one swing of >= 1 m
    assert float(row["distance_turns_per_100"]) > float(row["distance_swings_per_100"])  # the wobble at 6 m counts there
    with open(out / "swings.csv") as f:
        per = {float(r["threshold_m"]): float(r["swings_per_100"]) for r in csv.DictReader(f)}
    assert sorted(per) == list(behaviour.SWING_THRESHOLDS)
    assert per[2.0] == pytest.approx(100 / 41, abs=1e-2) and per[0.25] > per[1.0]


def test_neighbour_score_is_one_for_separated_labels_and_a_half_for_mixed_ones():
    rng = np.random.default_rng(3)
    y = np.repeat([0, 1], 100)
    apart = np.c_[rng.normal(size=200) + 20 * y, rng.normal(size=200)]
    mixed = rng.normal(size=(200, 2))
    assert probes.neighbour_score(apart, y) == pytest.approx(1.0)
    assert abs(probes.neighbour_score(mixed, y) - 0.5) < 0.12
    with pytest.raises(ValueError):
        probes.neighbour_score(mixed, np.zeros(200, dtype=int))


def test_neighbour_score_leaves_out_the_images_own_episode():
    # 40 episodes of 10 nearly identical frames; the label is one per episode and says nothing
    # about where the episode lies: only the frames of its own episode would predict it
    rng = np.random.default_rng(5)
    episode = np.repeat(np.arange(40), 10)
    y = np.repeat(rng.permutation(np.repeat([0, 1], 20)), 10)
    x = rng.normal(size=(40, 2))[episode] + 0.001 * rng.normal(size=(400, 2))
    assert probes.neighbour_score(x, y) > 0.95  # each frame's own episode answers for it
    assert abs(probes.neighbour_score(x, y, groups=episode) - 0.5) < 0.15


def write_probe_labels(path, labels):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["image", "variant", "S", "H", "episode", "split"])
        for i in range(len(labels["S"])):
            w.writerow([i, labels["variant"][i], labels["S"][i], labels["H"][i], labels["episode"][i],
                        "test" if labels["test"][i] else "train"])


def test_tsne_of_a_run_embeds_the_test_images_and_scores_what_the_features_encode(tmp_path):
    labels = synthetic_labels(n_episodes=40, per_episode=20)
    write_probe_labels(tmp_path / "labels.csv", labels)
    rng = np.random.default_rng(4)
    n = len(labels["S"])
    f = rng.normal(size=(n, 64)).astype(np.float32)
    f[:, :8] += 6.0 * labels["S"][:, None]  # S written large in the features, H not at all
    np.save(tmp_path / "trained.npy", f)
    with open(tmp_path / "tsne_baselines.csv", "w") as fh:
        fh.write("representation,target,images,neighbours,neighbour_balanced_accuracy\n"
                 "random_init_0,S,240,10,0.60\nrandom_init_1,S,240,10,0.62\nrandom_init_0,H,240,10,0.5\n"
                 "random_init_1,H,240,10,0.5\npixels,S,240,10,0.55\npixels,H,240,10,0.51\n")
    out = tmp_path / "out"
    assert probes.main(["tsne", str(tmp_path), str(tmp_path / "trained.npy"), str(out), "--run", "r",
                        "--baselines", str(tmp_path / "tsne_baselines.csv")]) == 0
    with open(out / "tsne.csv") as fh:
        coords = list(csv.DictReader(fh))
    # exactly the held-out test images, in order, each with finite coordinates
    assert [int(r["image"]) for r in coords] == list(np.flatnonzero(labels["test"]))
    assert all(np.isfinite(float(r["x"])) and np.isfinite(float(r["y"])) for r in coords)
    with open(out / "tsne_neighbours.csv") as fh:
        scores = {r["target"]: r for r in csv.DictReader(fh)}
    assert float(scores["S"]["neighbour_balanced_accuracy"]) > 0.9
    assert abs(float(scores["H"]["neighbour_balanced_accuracy"]) - 0.5) < 0.12
    assert float(scores["S"]["random_init_mean"]) == pytest.approx(0.61) and scores["S"]["pixels"] == "0.55"
    # the embedding is the same on a second call: the committed coordinates can be made again
    assert probes.main(["tsne", str(tmp_path), str(tmp_path / "trained.npy"), str(tmp_path / "again")]) == 0
    assert (tmp_path / "again" / "tsne.csv").read_text() == (out / "tsne.csv").read_text()


def test_occlusion_counts_the_pairs_a_box_hides_from_each_other():
    import occlusion
    empty = {"type": "fixed", "half_extent": 3.0, "obstacles": []}
    n, pairs, share = occlusion.occluded_share(empty, grid=0.5)
    assert pairs == n * (n - 1) // 2 and share == 0.0
    # A wall across the whole arena: every pair with one point on each side is occluded, about half.
    split = {"type": "fixed", "half_extent": 3.0, "obstacles": [{"center": [0.0, 0.0], "size": [0.2, 6.0]}]}
    n, pairs, share = occlusion.occluded_share(split, grid=0.5)
    side = n // 2
    assert share == pytest.approx(side * side / pairs, abs=1e-9)
    # The same wall turned a quarter, by yaw: the same share.
    turned = {"type": "fixed", "half_extent": 3.0,
              "obstacles": [{"center": [0.0, 0.0], "size": [6.0, 0.2], "yaw": 1.5707963267948966}]}
    assert occlusion.occluded_share(turned, grid=0.5)[2] == pytest.approx(share, abs=1e-9)
