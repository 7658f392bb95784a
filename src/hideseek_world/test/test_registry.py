"""Tests of scripts/hideseek_registry.py, the one Python reader of the variants and the run
registry: run with python3 -m pytest."""
import os
import subprocess
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import hideseek_registry as reg  # noqa: E402

SCRIPT = os.path.join(ROOT, "scripts", "hideseek_registry.py")


def cli(*args):
    return subprocess.run([sys.executable, SCRIPT] + list(args), capture_output=True, text=True)


def test_the_tree_agrees_with_itself():
    """Every run names an existing variant, shipped weights exist, one per variant, network and
    game, and every .pt in policies/ is some run's shipped weights."""
    result = cli("check")
    assert result.returncode == 0, result.stderr


def test_variants_are_discovered_from_config_variants():
    names = reg.variants()
    files = sorted(f[:-len(".yaml")] for f in os.listdir(os.path.join(ROOT, "config", "variants")) if f.endswith(".yaml"))
    assert names == files
    assert "basic" in names and len(names) >= 7


def test_every_variant_has_its_launch_file():
    """roslaunch hideseek_world <variant>.launch is how a user starts a variant."""
    for name in reg.variants():
        assert os.path.isfile(os.path.join(ROOT, "launch", name + ".launch")), name


@pytest.fixture
def tree(tmp_path):
    variants = tmp_path / "variants"
    variants.mkdir()
    for v in ("basic", "slowerhider"):
        (variants / (v + ".yaml")).write_text("variant: %s\nmap: deterministic.yaml\n" % v)
    policies = tmp_path / "policies"
    policies.mkdir()
    registry = policies / "policies.yaml"
    registry.write_text("# the registry\n")
    return str(registry), str(variants)


def test_record_then_ship_makes_one_run_the_shipped_one(tree, tmp_path):
    registry, variants = tree
    weights = tmp_path / "policy.pt"
    weights.write_bytes(b"w0")
    for seed in (0, 1):
        reg.record("basic_seed%d" % seed, {"variant": "basic", "network": "ff", "game": "v2",
                                           "training_seed": seed, "steps": 2000896}, registry)
    reg.ship("basic_seed0", str(weights), registry)
    assert reg.shipped("basic", registry=registry)[0] == "basic_seed0"
    reg.ship("basic_seed1", str(weights), registry)  # shipping another run takes the place of the first
    name, path = reg.shipped("basic", registry=registry)
    assert name == "basic_seed1" and path.endswith("policies/basic.pt") and os.path.isfile(path)
    assert "weights" not in reg.runs(registry)["basic_seed0"]
    assert reg.problems(registry, variants) == []
    assert open(registry).read().startswith("# the registry\n")  # the header survives a rewrite
    assert reg.shipped("basic", game="v1", registry=registry) == (None, None)


def test_problems_name_what_disagrees(tree):
    registry, variants = tree
    policies = os.path.dirname(registry)
    open(os.path.join(policies, "stray.pt"), "w").write("w")
    open(registry, "a").write("ghost_seed0: {variant: ghost, network: ff, game: v2}\n"
                              "basic_seed0: {variant: basic, network: ff, game: v2, weights: basic.pt}\n")
    found = "\n".join(reg.problems(registry, variants))
    assert "variant 'ghost' has no file" in found
    assert "basic.pt do not exist" in found
    assert "stray.pt is shipped by no run" in found


def test_a_malformed_run_is_refused_naming_it(tree):
    registry, variants = tree
    open(registry, "a").write("basic_seed0: {variant: basic, network: ff, game: v2, stpes: 3}\n")
    result = cli("--registry", registry, "--variants-dir", variants, "runs")
    assert result.returncode == 2
    assert "run basic_seed0: unknown field 'stpes'" in result.stderr


def test_shipped_exits_1_where_nothing_is_shipped(tree):
    registry, variants = tree
    result = cli("--registry", registry, "--variants-dir", variants, "shipped", "slowerhider")
    assert result.returncode == 1
    assert "no ff policy is shipped for variant slowerhider on game v2" in result.stderr
