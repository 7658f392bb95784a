"""probe_set (C++): the shared probe set is balanced on S x H within every variant, split by
episode, the same on every run, and a network's features come out one row per image. Small
arguments keep it to about a minute; PROBE_SET_BIN names the built tool."""
import csv
import hashlib
import os
import subprocess
from collections import Counter

import numpy as np
import pytest

BIN = os.environ.get("PROBE_SET_BIN", "")
ARGS = ["--episodes", "12", "--every", "2", "--per-cell", "4"]


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    assert os.path.isfile(BIN), "PROBE_SET_BIN (%r) does not name the built probe_set" % BIN
    out = tmp_path_factory.mktemp("probe_set")
    r = subprocess.run([BIN, "make", str(out)] + ARGS, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    return out


def rows(folder):
    with open(folder / "labels.csv") as f:
        return list(csv.DictReader(f))


def test_balanced_on_s_x_h_within_every_variant(made):
    labels = rows(made)
    cells = Counter((r["variant"], r["S"], r["H"]) for r in labels)
    variants = {r["variant"] for r in labels}
    assert len(variants) >= 7
    for v in variants:
        counts = [cells[(v, s, h)] for s in "01" for h in "01"]
        assert len(set(counts)) == 1 and counts[0] >= 1, (v, counts)
    assert "| basic |" in (made / "composition.md").read_text()


def test_split_by_episode(made):
    labels = rows(made)
    split_of = {}
    for r in labels:
        assert split_of.setdefault(r["episode"], r["split"]) == r["split"], "episode %s on both sides" % r["episode"]
    assert set(split_of.values()) == {"train", "test"}
    # no trajectory stands on both sides: variants that differ only in their reward (basic and
    # visibilityreward) play their own seeds, so no (hider, seed, poses) repeats across variants
    seen = {}
    for r in labels:
        key = (r["hider"], r["seed"], r["step"], r["hider_x"], r["hider_y"], r["seeker_x"], r["seeker_y"])
        assert seen.setdefault(key, r["split"]) == r["split"], key
    seeds = {}
    for r in labels:
        seeds.setdefault(r["seed"], set()).add(r["variant"])
    assert all(len(v) == 1 for v in seeds.values()), "a seed is played on two variants"
    # the evaluation seeds 0-99 are never used
    assert min(int(r["seed"]) for r in labels) >= 30000


def test_images_match_labels_and_are_the_same_every_time(made, tmp_path):
    images = np.load(made / "images.npy")
    assert images.dtype == np.uint8 and images.shape == (len(rows(made)), 84, 84, 3)
    assert images.std() > 10  # rendered scenes, not blank frames
    again = tmp_path / "again"
    r = subprocess.run([BIN, "make", str(again)] + ARGS, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    digest = [hashlib.sha256((d / "images.npy").read_bytes()).hexdigest() for d in (made, again)]
    assert digest[0] == digest[1]
    assert (made / "labels.csv").read_text() == (again / "labels.csv").read_text()


def test_features_of_a_random_init_network_one_row_per_image(made, tmp_path):
    out = tmp_path / "f.npy"
    r = subprocess.run([BIN, "features", str(made), str(out), "--random-init", "3"], capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stderr
    f = np.load(out)
    assert f.shape == (len(rows(made)), 512) and f.dtype == np.float32
    again = tmp_path / "g.npy"
    subprocess.run([BIN, "features", str(made), str(again), "--random-init", "3"], check=True, capture_output=True)
    assert np.array_equal(f, np.load(again))


def test_bad_input_is_refused_by_name(made, tmp_path):
    r = subprocess.run([BIN, "make", str(tmp_path / "x"), "--per-cell", "zero"], capture_output=True, text=True)
    assert r.returncode == 2 and "('zero') for option '--per-cell' is invalid" in r.stderr
    r = subprocess.run([BIN, "make", str(tmp_path / "x"), "--per-cell", "0"], capture_output=True, text=True)
    assert r.returncode == 2 and "--per-cell must be a whole number in [1, 100000], got 0" in r.stderr
    r = subprocess.run([BIN, "make", str(tmp_path / "x"), "--per-row", "5"], capture_output=True, text=True)
    assert r.returncode == 2 and "unrecognised option '--per-row'" in r.stderr and not (tmp_path / "x").exists()
    bad = tmp_path / "bad"
    bad.mkdir()
    (bad / "images.npy").write_bytes(b"\x93NUMPY\x01\x00" + b"\x10\x00" + b"{'descr': '<f4'}".ljust(16))
    r = subprocess.run([BIN, "features", str(bad), str(tmp_path / "o.npy"), "--random-init", "0"], capture_output=True,
                       text=True)
    assert r.returncode == 1 and "not a [N, H, W, 3] uint8 image array" in r.stderr
    r = subprocess.run([BIN, "features", str(made), str(tmp_path / "o.npy")], capture_output=True, text=True)
    assert r.returncode == 2 and "exactly one of --policy and --random-init" in r.stderr


def test_help_names_both_commands_and_an_unknown_command_is_refused():
    assert os.path.isfile(BIN), "PROBE_SET_BIN (%r) does not name the built probe_set" % BIN
    for flag in ("--help", "-h"):
        r = subprocess.run([BIN, flag], capture_output=True, text=True, timeout=60)
        assert r.returncode == 0, (flag, r.stderr)
        assert "probe_set make OUT_DIR" in r.stdout and "probe_set features PROBE_DIR" in r.stdout, r.stdout
    r = subprocess.run([BIN, "nosuch"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and "unknown command 'nosuch'" in r.stderr, (r.returncode, r.stderr)
