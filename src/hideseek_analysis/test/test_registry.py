"""Tests of hideseek_analysis.registry, the one Python reader of the variants and the run registry,
and of its command line src/hideseek_analysis/scripts/hideseek_registry.py: run with python3 -m pytest."""
import hashlib
import os
import re
import subprocess
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "src", "hideseek_analysis", "python"))
from hideseek_analysis import registry as reg  # noqa: E402

SCRIPT = os.path.join(ROOT, "src", "hideseek_analysis", "scripts", "hideseek_registry.py")


def cli(*args):
    return subprocess.run([sys.executable, SCRIPT] + list(args), capture_output=True, text=True)


def test_the_tree_agrees_with_itself():
    """Every run names an existing variant, shipped weights exist, one per variant, network and
    game, and every .pt in policies/ is some run's shipped weights."""
    result = cli("check")
    assert result.returncode == 0, result.stderr


def test_every_relative_link_in_the_readme_and_docs_names_a_file_that_exists():
    """A reader follows the README's and docs' links, the generated report's among them (Table 3's
    link to docs/analysis.md once pointed one folder too high); code blocks are not links."""
    link = re.compile(r"\]\(([^)\s]+)\)")
    pages = [os.path.join(ROOT, "README.md")] + [
        os.path.join(d, f) for d, _, fs in os.walk(os.path.join(ROOT, "docs")) for f in fs if f.endswith(".md")]
    broken = []
    for page in pages:
        in_code = False
        with open(page) as f:
            for number, line in enumerate(f, 1):
                if line.lstrip().startswith("```"):
                    in_code = not in_code
                    continue
                for target in [] if in_code else link.findall(line):
                    path = target.split("#")[0]
                    if path and not re.match(r"[a-z]+:", path) and \
                            not os.path.exists(os.path.join(os.path.dirname(page), path)):
                        broken.append("%s:%d: %s" % (os.path.relpath(page, ROOT), number, target))
    assert len(pages) > 20
    assert not broken, "\n".join(broken)


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
    assert reg.shipped("basic", game="v2", registry=registry)[0] == "basic_seed0"
    reg.ship("basic_seed1", str(weights), registry)  # shipping another run takes the place of the first
    name, path = reg.shipped("basic", game="v2", registry=registry)
    assert name == "basic_seed1" and path.endswith("policies/basic.pt") and os.path.isfile(path)
    assert "weights" not in reg.runs(registry)["basic_seed0"]
    assert reg.problems(registry, variants) == []
    assert open(registry).read().startswith("# the registry\n")  # the header survives a rewrite
    assert reg.shipped("basic", game="v1", registry=registry) == (None, None)


def test_a_registry_elsewhere_finds_its_runs_logs_beside_it(tree, tmp_path):
    """`check --registry` of records kept outside the checkout (hideseek_pipeline train --record-root)
    reads each run's log and curve under that registry's own folder, not under the checkout's."""
    registry, variants = tree
    reg.record("scratch_seed0", {"variant": "basic", "network": "ff", "game": "v3", "training_seed": 0, "steps": 2048,
                                 "log": "docs/runs/scratch_seed0/training_log.csv"}, registry)
    assert reg.problems(registry, variants) == [
        "run scratch_seed0: log docs/runs/scratch_seed0/training_log.csv does not exist"]
    (tmp_path / "docs" / "runs" / "scratch_seed0").mkdir(parents=True)
    (tmp_path / "docs" / "runs" / "scratch_seed0" / "training_log.csv").write_text("update,steps\n1,1024\n")
    assert reg.problems(registry, variants) == []


def test_a_v3_policy_ships_beside_the_v2_one_of_its_variant(tree, tmp_path):
    """Shipping game v3's basic leaves v2's basic.pt as it is, so that v2 stays playable."""
    registry, variants = tree
    for game, content in (("v2", b"v2 weights"), ("v3", b"v3 weights")):
        weights = tmp_path / ("%s.pt" % game)
        weights.write_bytes(content)
        name = "basic_seed0" if game == "v2" else "basic_v3_seed0"
        reg.record(name, {"variant": "basic", "network": "ff", "game": game, "training_seed": 0, "steps": 2048},
                   registry)
        reg.ship(name, str(weights), registry)
    v2 = reg.shipped("basic", game="v2", registry=registry)[1]
    v3 = reg.shipped("basic", game="v3", registry=registry)[1]
    assert v2.endswith("policies/basic.pt") and open(v2, "rb").read() == b"v2 weights"
    assert v3.endswith("policies/basic_v3.pt") and open(v3, "rb").read() == b"v3 weights"
    assert reg.problems(registry, variants) == []


def test_a_seeker_run_ships_beside_the_hider_and_never_as_it(tree, tmp_path):
    """A learning seeker's run records its role: it ships to its own file, the hider's shipped policy
    and median stay the hider's, and a role other than hider or seeker is refused by name."""
    registry, variants = tree
    for name, role, content in (("basic_seed0", None, b"hider"), ("basic_seeker_seed0", "seeker", b"seeker")):
        weights = tmp_path / (name + ".pt")
        weights.write_bytes(content)
        fields = {"variant": "basic", "network": "ff", "game": "v2", "training_seed": 0, "steps": 2048,
                  "note": "sweep run (config/sweep.yaml)"}
        if role:
            fields["role"] = role
        reg.record(name, fields, registry)
        reg.ship(name, str(weights), registry)
    hider = reg.shipped("basic", game="v2", registry=registry)
    seeker = reg.shipped("basic", game="v2", registry=registry, of="seeker")
    assert hider[0] == "basic_seed0" and open(hider[1], "rb").read() == b"hider"
    assert seeker[1].endswith("policies/basic_seeker.pt") and open(seeker[1], "rb").read() == b"seeker"
    assert reg.problems(registry, variants) == []
    for name in ("basic_seed0", "basic_seeker_seed0"):
        docs = tmp_path / "docs" / "runs" / name
        docs.mkdir(parents=True)
        (docs / "evaluation.csv").write_text("variant,policy,episodes,avg_living_steps,success_rate\nb,p,100,50,0\n")
    assert reg.median_run("basic", game="v2", registry=registry, root=str(tmp_path)) == "basic_seed0"
    with pytest.raises(reg.RegistryError, match="field 'role' is 'referee', not one of hider, seeker"):
        reg.record("basic_seed1", {"variant": "basic", "network": "ff", "game": "v2", "role": "referee"}, registry)


def test_the_median_of_a_budget_leaves_out_the_runs_of_another(tree, tmp_path):
    """The 8M budget check's runs never become the 2M median that a variant ships, nor the reverse."""
    registry, _ = tree
    scores = {"basic_v3_seed0": (2000896, 100.0), "basic_v3_seed1": (2000896, 300.0),
              "basic_v3_8m_seed0": (8000512, 200.0)}
    for name, (steps, living) in scores.items():
        reg.record(name, {"variant": "basic", "network": "ff", "game": "v3", "steps": steps,
                          "note": "sweep run (config/sweep.yaml), phase x, pinned at abc"}, registry)
        folder = tmp_path / "docs" / "runs" / name
        folder.mkdir(parents=True)
        (folder / "evaluation.csv").write_text("variant,policy,episodes,avg_living_steps,success_rate\n"
                                               "basic,%s,100,%.2f,0.1\n" % (name, living))
    root = str(tmp_path)
    assert reg.median_run("basic", game="v3", registry=registry, root=root) == "basic_v3_8m_seed0"  # all three
    assert reg.median_run("basic", game="v3", registry=registry, root=root, steps=2_000_000) == "basic_v3_seed0"
    assert reg.median_run("basic", game="v3", registry=registry, root=root, steps=8_000_000) == "basic_v3_8m_seed0"


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


def test_a_run_on_a_variant_file_of_its_own_is_checked_against_its_files(tree, tmp_path):
    """Such a run names no variant of the tree: the check looks at its files instead, and names one
    that is gone or has changed since; its four fields come together or not at all."""
    registry, variants = tree
    mine, map_file = tmp_path / "mine.yaml", tmp_path / "map.yaml"
    mine.write_text("variant: mine\n")
    map_file.write_text("walls: []\n")
    sha = {p: hashlib.sha256(p.read_bytes()).hexdigest() for p in (mine, map_file)}
    open(registry, "a").write(
        "mine_seed0: {variant: mine, network: ff, game: v3, variant_config: %s, variant_sha256: %s, map_file: %s, "
        "map_sha256: %s}\n" % (mine, sha[mine], map_file, sha[map_file]))
    assert reg.problems(registry, variants) == []
    mine.write_text("variant: mine\nepisode: {max_steps: 100}\n")
    map_file.unlink()
    found = "\n".join(reg.problems(registry, variants))
    assert "run mine_seed0: variant_config %s has changed since the run trained" % mine in found
    assert "run mine_seed0: map_file %s does not exist" % map_file in found
    assert "has no file in" not in found
    open(registry, "a").write("half_seed0: {variant: half, network: ff, game: v3, variant_config: %s}\n" % mine)
    result = cli("--registry", registry, "--variants-dir", variants, "runs")
    assert result.returncode == 2 and "run half_seed0: a run on a variant file of its own records" in result.stderr
    shipped = tmp_path / "shipped.yaml"
    shipped.write_text("mine_seed0: {variant: mine, network: ff, game: v3, variant_config: %s, variant_sha256: a, "
                       "map_file: %s, map_sha256: b, weights: mine.pt}\n" % (mine, map_file))
    result = cli("--registry", str(shipped), "--variants-dir", variants, "runs")
    assert result.returncode == 2
    assert "run mine_seed0: a run on a variant file of its own ships no weights" in result.stderr


def test_recording_a_run_again_replaces_its_training_and_an_empty_value_removes_a_field(tree):
    """A retrained run is recorded over its first training: the new wall time replaces the old, and
    paused_s= (what hideseek_pipeline train and the sweep pass when the new training was never paused)
    removes the old training's paused time rather than leaving it beside the new wall time."""
    registry, variants = tree
    first = ["variant=basic", "network=ff", "game=v2", "training_seed=0", "wall_s=4394", "paused_s=1030"]
    assert cli("--registry", registry, "--variants-dir", variants, "record", "basic_seed0", *first).returncode == 0
    assert reg.runs(registry)["basic_seed0"]["paused_s"] == 1030
    again = cli("--registry", registry, "--variants-dir", variants, "record", "basic_seed0", "wall_s=2504", "paused_s=")
    assert again.returncode == 0, again.stderr
    entry = reg.runs(registry)["basic_seed0"]
    assert entry["wall_s"] == 2504 and "paused_s" not in entry
    assert entry["variant"] == "basic" and entry["training_seed"] == 0


def test_a_malformed_run_is_refused_naming_it(tree):
    registry, variants = tree
    open(registry, "a").write("basic_seed0: {variant: basic, network: ff, game: v2, stpes: 3}\n")
    result = cli("--registry", registry, "--variants-dir", variants, "runs")
    assert result.returncode == 2
    assert "run basic_seed0: unknown field 'stpes'" in result.stderr


def test_shipped_exits_1_where_nothing_is_shipped(tree):
    registry, variants = tree
    result = cli("--registry", registry, "--variants-dir", variants, "shipped", "slowerhider")  # the default game
    assert result.returncode == 1
    assert "no ff policy is shipped for variant slowerhider on game %s" % reg.default_game() in result.stderr


def test_a_listing_whose_reader_has_gone_ends_without_a_traceback():
    """`hideseek_registry.py runs | head -n 1`: the reader closes the pipe before the listing ends;
    the tool ends quietly by SIGPIPE, as ls does, not with a Python traceback. (Here the reader is
    gone before the first write, so every run sees it, whatever the timing.)"""
    read, write = os.pipe()
    os.close(read)
    r = subprocess.run([sys.executable, SCRIPT, "runs"], stdout=write, stderr=subprocess.PIPE, text=True)
    os.close(write)
    assert r.returncode == -13 and r.stderr == "", (r.returncode, r.stderr)


def test_ship_median_ships_the_median_sweep_run_and_keeps_the_shipped_one_without_its_weights(tree, tmp_path):
    """The sweep ships the run whose greedy evaluation is its variant's median; a pilot run (no sweep
    note) does not count; where the median run's weights are gone, the shipped run stays and the
    command says which run to retrain (exit 1)."""
    registry, _ = tree
    root = str(tmp_path)
    weights_dir = tmp_path / "runs"
    scores = {"basic_seed0": 400.0, "basic_seed1": 100.0, "basic_seed2": 250.0, "basic_pilot": 300.0}
    for name, steps in scores.items():
        note = "exploration" if name == "basic_pilot" else "sweep run (config/sweep.yaml), pinned at abc"
        reg.record(name, {"variant": "basic", "network": "ff", "game": "v2", "note": note}, registry)
        folder = tmp_path / "docs" / "runs" / name
        folder.mkdir(parents=True)
        (folder / "evaluation.csv").write_text("variant,policy,episodes,avg_living_steps,success_rate\n"
                                               "basic,%s (greedy),100,%.2f,0.1\n" % (name, steps))
    (weights_dir / "basic_pilot").mkdir(parents=True)
    (weights_dir / "basic_pilot" / "policy.pt").write_bytes(b"pilot")
    reg.ship("basic_pilot", str(weights_dir / "basic_pilot" / "policy.pt"), registry)
    assert reg.median_run("basic", game="v2", registry=registry, root=root) == "basic_seed2"
    # seed 2's weights are gone: the pilot stays shipped, and the CLI says so with exit 1
    result = cli("--registry", registry, "--variants-dir", str(tmp_path / "variants"), "ship-median", "basic",
                 "--game", "v2", "--weights-dir", str(weights_dir))
    assert result.returncode == 1 and "basic_seed2" in result.stderr and "basic_pilot stays shipped" in result.stderr
    assert reg.shipped("basic", game="v2", registry=registry)[0] == "basic_pilot"
    (weights_dir / "basic_seed2").mkdir()
    (weights_dir / "basic_seed2" / "policy.pt").write_bytes(b"seed2")
    result = cli("--registry", registry, "--variants-dir", str(tmp_path / "variants"), "ship-median", "basic",
                 "--game", "v2", "--weights-dir", str(weights_dir))
    assert result.returncode == 0, result.stderr
    name, path = reg.shipped("basic", game="v2", registry=registry)
    assert name == "basic_seed2" and open(path, "rb").read() == b"seed2"
    assert "already shipped" in reg.ship_median("basic", str(weights_dir), game="v2", registry=registry, root=root)
    # an even count ships the lower of the middle two
    (tmp_path / "docs" / "runs" / "basic_seed2" / "evaluation.csv").unlink()
    assert reg.median_run("basic", game="v2", registry=registry, root=root) == "basic_seed1"


def test_the_median_counts_first_draws_and_ships_a_retrain_where_the_first_draws_weights_are_lost(tree, tmp_path):
    """A retrain (<run>_retrain, draw: retrain) never counts toward the median, however it scored;
    where the median first draw's weights are gone and its retrain's are here, the retrain ships,
    named as the retrain it is. A retrain must name a first draw of the same variant and seed."""
    registry, variants = tree
    root = str(tmp_path)
    weights_dir = tmp_path / "runs"
    sweep = {"note": "sweep run (config/sweep.yaml), pinned at abc", "variant": "basic", "network": "ff", "game": "v2"}
    scores = {"basic_seed0": 400.0, "basic_seed1": 100.0, "basic_seed2": 250.0, "basic_seed2_retrain": 900.0}
    for name, living in scores.items():
        fields = dict(sweep, training_seed=int(name[10]))
        if name.endswith("_retrain"):
            fields.update(draw="retrain", retrain_of="basic_seed2")
        reg.record(name, fields, registry)
        folder = tmp_path / "docs" / "runs" / name
        folder.mkdir(parents=True)
        (folder / "evaluation.csv").write_text("variant,policy,episodes,avg_living_steps,success_rate\n"
                                               "basic,%s (greedy),100,%.2f,0.1\n" % (name, living))
    assert reg.median_run("basic", game="v2", registry=registry, root=root) == "basic_seed2"  # 900 is not a first draw
    (weights_dir / "basic_seed2_retrain").mkdir(parents=True)
    (weights_dir / "basic_seed2_retrain" / "policy.pt").write_bytes(b"retrain")
    said = reg.ship_median("basic", str(weights_dir), game="v2", registry=registry, root=root)
    assert "shipped basic_seed2_retrain as the median run of basic (its retrain)" in said
    assert reg.shipped("basic", game="v2", registry=registry)[0] == "basic_seed2_retrain"
    assert "already shipped" in reg.ship_median("basic", str(weights_dir), game="v2", registry=registry, root=root)
    assert reg.problems(registry, variants) == []
    reg.record("basic_seed1_retrain", dict(sweep, training_seed=0, draw="retrain", retrain_of="basic_seed1"), registry)
    assert "not a retrain of basic_seed1" in "\n".join(reg.problems(registry, variants))
    with pytest.raises(reg.RegistryError, match="a retrain needs 'retrain_of'"):
        reg.record("basic_seed0_retrain", dict(sweep, training_seed=0, draw="retrain"), registry)
    assert "basic_seed0_retrain" not in reg.runs(registry)  # refused before it was written
