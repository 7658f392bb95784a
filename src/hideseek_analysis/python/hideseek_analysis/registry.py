"""The project's two registries, read in one place by the tools, the report and CMake (its command
line: src/hideseek_analysis/scripts/hideseek_registry.py in a checkout, or rosrun hideseek_analysis hideseek_registry.py):

- the variants: config/variants/*.yaml (discovered, never listed; a file's `variant` is its name);
- the runs: policies/policies.yaml, one entry per training run (variant, network, game, training
  seed, steps, wall time, precision, the commit it trained with, its log and curve). The run whose
  exported weights are committed names them in `weights` (relative to policies/): the policy a
  variant's launch file plays by default (policy:=shipped). At most one run ships weights for a
  variant, network and game. A run trained on a variant file of its own records the file and its
  map with their sha256 (variant_config, variant_sha256, map_file, map_sha256).

The C++ nodes read the runs through hideseek_game/run_registry.h, under the same rules. Both
readers exist because a node resolves policy:=shipped at start-up in C++, without a Python
interpreter, while this file also writes the registry (record, ship, ship-median) for the scripts;
run_registry_test.cpp (TheCppAndPythonReadersAgree) runs both on the same files.

A policy's label is its variant's name, with _gru for a GRU hider (basic, basic_gru): the name
of its weights (policies/<label>.pt) and of its folders in an evaluation or a report.

usage:
  hideseek_registry.py variants [--paper-order]       the variant names, one per line (in name
                                                      order, or Table 2's: the paper's, then others)
  hideseek_registry.py runs [--variant V] [--game G] [--network N]
                                                      run names, one per line
  hideseek_registry.py shipped VARIANT [--network N] [--game G]
                                                      the shipped weights' path (exit 1: none)
  hideseek_registry.py shipped --all [--game G]       LABEL VARIANT NETWORK PATH of every shipped policy, in
                                                      Table 2's order
  hideseek_registry.py record RUN key=value ...       adds or updates a run's entry; key= (empty)
                                                      removes the key, so that a run trained again
                                                      keeps nothing of the old training (paused_s)
  hideseek_registry.py ship RUN WEIGHTS               copies WEIGHTS to policies/<variant>[_gru].pt
                                                      and makes RUN the shipped run of its key
  hideseek_registry.py ship-median VARIANT --weights-dir DIR [--note PREFIX]
                                                      ships the sweep run whose greedy evaluation is its
                                                      variant's median (the lower of the middle two for an
                                                      even count) from DIR/<run>/policy.pt; exit 1 where its
                                                      weights are not in DIR (the shipped run stays; the
                                                      sweep's ship step then looks in git history,
                                                      weights_in_history, and checks what it finds)
  hideseek_registry.py check                          exit 1, naming the problem, where the
                                                      registries disagree with each other or the tree
"""
import argparse
import contextlib
import csv
import fcntl
import glob
import hashlib
import io
import os
import shutil
import subprocess
import sys
import zipfile

import yaml



def _repository_root():
    """The checkout this file belongs to: the first folder above it with policies/policies.yaml
    (the file lives in src/hideseek_analysis/python/hideseek_analysis/).
    Elsewhere (an install space) the current folder: give --registry there."""
    here = os.path.dirname(os.path.realpath(__file__))
    while True:
        if os.path.isfile(os.path.join(here, "policies", "policies.yaml")):
            return here
        parent = os.path.dirname(here)
        if parent == here:
            return os.getcwd()
        here = parent


ROOT = _repository_root()
VARIANTS_DIR = os.path.join(ROOT, "config", "variants")
REGISTRY = os.path.join(ROOT, "policies", "policies.yaml")
PAPER = os.path.join(ROOT, "config", "paper_reference.yaml")
GAMES = os.path.join(ROOT, "config", "games.yaml")  # the default game: config/games.yaml's `default`
NETWORKS = ("ff", "gru")
# Keys a run may carry (the C++ loader refuses any other, so that a typo is found).
# A run trained on a variant file of its own (hideseek_pipeline train --variant-config): the file and
# its map, each with its sha256 when it trained; its evaluation and analysis replay them unchanged.
OWN_VARIANT_KEYS = ("variant_config", "variant_sha256", "map_file", "map_sha256")
RUN_KEYS = ("variant", "network", "game", "training_seed", "steps", "wall_s", "paused_s", "precision", "commit",
            "log", "curve", "command", "note", "weights", "draw", "retrain_of", "role") + OWN_VARIANT_KEYS
REQUIRED = ("variant", "network", "game")
# A run's draw: `first`, the first training of its variant and seed (the default, and the only
# draw that Table 2 and the claims count), or `retrain`, the same variant and seed trained again to
# recover weights to ship, named <run>_retrain and pointing at its first draw with `retrain_of`.
DRAWS = ("first", "retrain")
# Whose policy a run trained: a hider's (the default, every run before the seeker learned) or a
# seeker's. Table 2, the claims, shipping for the hider's launch files and every hider tool take
# hider runs only.
ROLES = ("hider", "seeker")
RETRAIN_SUFFIX = "_retrain"


class RegistryError(Exception):
    pass


class WeightsMissing(RegistryError):
    """The run to ship has no weights on this machine. `runs`: the runs whose weights would do (the
    median first draw, then its retrain where there is one), in that order."""

    def __init__(self, message, runs=()):
        super().__init__(message)
        self.runs = list(runs)


def variants(variants_dir=VARIANTS_DIR):
    """Variant names, sorted: every config/variants/*.yaml, named by its `variant` field."""
    names = []
    for path in sorted(glob.glob(os.path.join(variants_dir, "*.yaml"))):
        with open(path) as f:
            name = (yaml.safe_load(f) or {}).get("variant")
        stem = os.path.basename(path)[:-len(".yaml")]
        if name != stem:
            raise RegistryError("%s: field 'variant' is %r; it must be the file's name, %r" % (path, name, stem))
        names.append(name)
    return names


def paper_order(variants_dir=VARIANTS_DIR, paper=PAPER):
    """The variants in Table 2's order: the paper's (config/paper_reference.yaml), then the others by name."""
    names = variants(variants_dir)
    with open(paper) as f:
        listed = list((yaml.safe_load(f) or {}).get("variants") or {})
    return [n for n in listed if n in names] + [n for n in names if n not in listed]


def label(variant, network="ff"):
    """The name of a variant's policy of this network: basic, basic_gru."""
    return variant if network == "ff" else variant + "_" + network


def run_variant(name, entry, known):
    """The variant a run or policy label belongs to: its entry's `variant`, else read from the label."""
    if entry.get("variant"):
        return entry["variant"]
    for network in NETWORKS:
        for v in known:
            if label(v, network) == name:
                return v
    return None


def run_network(name, entry):
    """A run's network: its entry's `network`, else read from the label."""
    if entry.get("network"):
        return entry["network"]
    return next((n for n in NETWORKS if n != "ff" and name.endswith("_" + n)), "ff")


def _header(text):
    """The registry's leading comment block, kept when it is rewritten."""
    lines = []
    for line in text.splitlines(True):
        if not line.startswith("#"):
            break
        lines.append(line)
    return "".join(lines)


def runs(registry=REGISTRY):
    """Run name -> entry (a dict), in file order."""
    if not os.path.exists(registry):
        return {}
    with open(registry) as f:
        entries = yaml.safe_load(f) or {}
    return _checked(entries, registry)


def _checked(entries, registry):
    """The entries, once each is well formed; RegistryError naming the run and field otherwise."""
    if not isinstance(entries, dict):
        raise RegistryError("%s: must map run names to runs" % registry)
    for name, entry in entries.items():
        if not isinstance(entry, dict):
            raise RegistryError("%s: run %s: must be a mapping of the run's fields" % (registry, name))
        for key in entry:
            if key not in RUN_KEYS:
                raise RegistryError("%s: run %s: unknown field %r" % (registry, name, key))
        for key in REQUIRED:
            if not entry.get(key):
                raise RegistryError("%s: run %s: field %r is required" % (registry, name, key))
        if entry["network"] not in NETWORKS:
            raise RegistryError("%s: run %s: field 'network' is %r, not one of %s" % (registry, name, entry["network"],
                                                                                      ", ".join(NETWORKS)))
        if role(entry) not in ROLES:
            raise RegistryError("%s: run %s: field 'role' is %r, not one of %s" % (registry, name, entry["role"],
                                                                                   ", ".join(ROLES)))
        if draw(entry) not in DRAWS:
            raise RegistryError("%s: run %s: field 'draw' is %r, not one of %s" % (registry, name, entry["draw"],
                                                                                   ", ".join(DRAWS)))
        if (draw(entry) == "retrain") != bool(entry.get("retrain_of")):
            raise RegistryError("%s: run %s: %s" % (registry, name, "a retrain needs 'retrain_of', the run it trains again"
                                                    if draw(entry) == "retrain" else "'retrain_of' is only for a retrain"))
        own = [key for key in OWN_VARIANT_KEYS if entry.get(key)]
        if own and len(own) != len(OWN_VARIANT_KEYS):
            raise RegistryError("%s: run %s: a run on a variant file of its own records %s together; it has only %s"
                                % (registry, name, ", ".join(OWN_VARIANT_KEYS), ", ".join(own)))
        if own and entry.get("weights"):
            raise RegistryError("%s: run %s: a run on a variant file of its own ships no weights (a variant's shipped "
                                "policy is played under its name, whatever file that name then reads)"
                                % (registry, name))
    return entries


def draw(entry):
    """first or retrain (see DRAWS)."""
    return entry.get("draw", "first")


def role(entry):
    """hider or seeker (see ROLES)."""
    return entry.get("role", "hider")


def weights_path(entry, registry=REGISTRY):
    return os.path.join(os.path.dirname(registry), entry["weights"]) if entry.get("weights") else None


def default_game(games=GAMES):
    """The game played where none is named: config/games.yaml's `default` (as the C++ resolver reads it)."""
    try:
        with open(games) as f:
            game = (yaml.safe_load(f) or {}).get("default")
    except OSError as e:
        raise RegistryError("%s: cannot be read (%s)" % (games, e.strerror))
    if not game:
        raise RegistryError("%s: the key 'default' (the default game) is missing" % games)
    return str(game)


def shipped(variant, network="ff", game=None, registry=REGISTRY, of="hider"):
    """(run name, absolute weights path) of the shipped run of a game (None: the default game) and
    role (`of`: a hider's unless said), or (None, None)."""
    game = game or default_game()
    for name, entry in runs(registry).items():
        if (entry["variant"], entry["network"], entry["game"], role(entry)) == (variant, network, game, of) and \
                entry.get("weights"):
            return name, weights_path(entry, registry)
    return None, None


def select(variant=None, game=None, network=None, registry=REGISTRY):
    return [n for n, e in runs(registry).items()
            if (variant is None or e["variant"] == variant) and (game is None or e["game"] == game)
            and (network is None or e["network"] == network)]


def _write(entries, registry=REGISTRY):
    header = ""
    if os.path.exists(registry):
        with open(registry) as f:
            header = _header(f.read())
    tmp = registry + ".tmp"
    with open(tmp, "w") as f:
        f.write(header + (yaml.safe_dump(entries, sort_keys=False) if entries else ""))
    os.replace(tmp, registry)


def _value(text):
    """key=value on the command line: numbers as numbers, the rest as text."""
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


@contextlib.contextmanager
def _locked(registry):
    """Holds an exclusive lock beside the registry, so that two runs recording at once (the sweep's
    concurrent runs) do not lose each other's entries."""
    with open(registry + ".lock", "a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)


def record(name, fields, registry=REGISTRY):
    """Adds or updates a run's entry. A field whose value is None is removed from the entry."""
    with _locked(registry):
        entries = runs(registry)
        entry = dict(entries.get(name, {}))
        entry.update(fields)
        entry = {k: v for k, v in entry.items() if v is not None}
        entries[name] = {k: entry[k] for k in RUN_KEYS if k in entry}
        _write(_checked(entries, registry), registry)  # a malformed entry is refused before it is written


def ship(name, weights, registry=REGISTRY):
    entries = runs(registry)
    if name not in entries:
        raise RegistryError("%s: no run %s to ship" % (registry, name))
    entry = entries[name]
    # One file per variant, network, game and role: game v2's hiders keep their names (basic.pt), another
    # game's carry it (basic_v3.pt), so that shipping v3 leaves v2 playable under game:=v2; a seeker's
    # carries its role (basic_seeker_v3.pt).
    file_name = (label(entry["variant"], entry["network"]) + ("" if role(entry) == "hider" else "_" + role(entry)) +
                 ("" if entry["game"] == "v2" else "_" + entry["game"]) + ".pt")
    target = os.path.join(os.path.dirname(registry), file_name)
    if os.path.abspath(weights) != os.path.abspath(target):
        shutil.copyfile(weights, target)
    for other, e in entries.items():
        if other != name and (e["variant"], e["network"], e["game"], role(e)) == (
                entry["variant"], entry["network"], entry["game"], role(entry)):
            e.pop("weights", None)
    entry["weights"] = file_name
    _write(entries, registry)


# The note the sweep's queue starts each of its runs' entries with (a same-named run from elsewhere
# is not one of its runs): Table 2, the claims and the median to ship count those runs only.
SWEEP_NOTE = "sweep run"


def greedy_living_steps(name, root=ROOT):
    """The mean living steps of a run's greedy evaluation (docs/runs/<run>/evaluation.csv), or None."""
    path = os.path.join(root, "docs", "runs", name, "evaluation.csv")
    if not os.path.isfile(path):
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if len(rows) != 1 or "avg_living_steps" not in rows[0]:
        raise RegistryError("%s: expected one row with avg_living_steps" % path)
    return float(rows[0]["avg_living_steps"])


def of_budget(trained, budget):
    """Whether a run that trained `trained` steps was a run of `budget` steps: a run ends at the
    first whole rollout past its budget, so its recorded steps lie in [budget, 2 x budget)."""
    return budget <= int(trained or 0) < 2 * budget


def first_draws(variant, network="ff", game=None, registry=REGISTRY, root=ROOT, note=SWEEP_NOTE, steps=None):
    """{run: greedy mean living steps} of a variant's first-draw hider runs on a game (None: the
    default game) whose note starts with `note` and that have a greedy evaluation. With `steps`,
    only runs of that budget (recorded steps from `steps` to under twice it: a run ends at the
    first whole rollout past its budget)."""
    found, game = {}, game or default_game()
    for name, e in runs(registry).items():
        if (e["variant"], e["network"], e["game"], role(e)) != (variant, network, game, "hider"):
            continue
        if steps is not None and not of_budget(e.get("steps", 0), steps):
            continue
        if not str(e.get("note", "")).startswith(note) or draw(e) != "first":
            continue
        living = greedy_living_steps(name, root)
        if living is not None:
            found[name] = living
    return found


def median_run(variant, network="ff", game=None, registry=REGISTRY, root=ROOT, note=SWEEP_NOTE, steps=None):
    """The hider run to ship for a variant on a game (None: the default game): among its first
    draws (first_draws), the one whose mean living steps is the median (the lower of the middle two
    for an even count; ties broken by name). None when there is no such run."""
    scored = sorted((living, name) for name, living in
                    first_draws(variant, network, game, registry, root, note, steps).items())
    if not scored:
        return None
    return scored[(len(scored) - 1) // 2][1]


def ship_median(variant, weights_dir, network="ff", game=None, registry=REGISTRY, root=ROOT, note=SWEEP_NOTE,
                steps=None):
    """Ships the median run of a variant (median_run, by first draws) from weights_dir/<run>/policy.pt,
    or, where those weights are lost, its retrain <run>_retrain from weights_dir/<run>_retrain/.
    Returns a sentence saying what it did; raises WeightsMissing when neither's weights are there."""
    game = game or default_game()
    name = median_run(variant, network, game, registry, root, note, steps)
    if name is None:
        return "variant %s has no evaluated run whose note starts with %r; nothing shipped" % (variant, note)
    current, _ = shipped(variant, network, game, registry)
    retrain = name + RETRAIN_SUFFIX
    if current in (name, retrain):
        return "%s, the median run of %s%s, is already shipped" % (current, variant,
                                                                  " (its retrain)" if current == retrain else "")
    candidates = [name] + ([retrain] if retrain in runs(registry) else [])
    for run in candidates:
        weights = os.path.join(weights_dir, run, "policy.pt")
        if os.path.isfile(weights):
            with _locked(registry):
                ship(run, weights, registry)
            return "shipped %s as the median run of %s%s (was %s)" % (run, variant, " (its retrain)" if run == retrain
                                                                     else "", current or "nothing")
    raise WeightsMissing("the median run of %s is %s, but its weights %s are not on this machine; %s "
                         "(hideseek_pipeline sweep retrain %s to ship it)" % (
                             variant, name, " or ".join(os.path.join(weights_dir, r, "policy.pt") for r in candidates),
                             "%s stays shipped" % current if current else "no run is shipped", name), candidates)


def _git(folder, *args):
    return subprocess.run(["git", "-C", folder] + list(args), capture_output=True)


def is_torch_archive(data):
    """Whether `data` is an exported policy's file as torch.jit.save writes it: a zip archive with
    its pickled data and its code."""
    try:
        with zipfile.ZipFile(io.BytesIO(data)) as z:
            names = z.namelist()
    except zipfile.BadZipFile:
        return False
    return any(n.endswith("/data.pkl") for n in names) and any("/code/" in n for n in names)


def weights_in_history(name, registry=REGISTRY):
    """The weights a run shipped with once, from the git history of the registry's checkout:
    (commit, the file's bytes) at the newest commit whose registry names the run's `weights` and
    holds that file as an exported policy; None where the checkout is no git repository or the run
    never shipped. A run whose weights left the machine (a sweep's run folder on another machine)
    keeps them there while it ships, since its weights are committed with the registry."""
    folder = os.path.dirname(os.path.realpath(registry))
    top = _git(folder, "rev-parse", "--show-toplevel")
    if top.returncode != 0:
        return None
    folder = top.stdout.decode().strip()  # paths below are the repository's
    rel = os.path.relpath(os.path.realpath(registry), folder)
    log = _git(folder, "log", "--format=%H", "--", rel)
    loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    for commit in log.stdout.decode().split():
        shown = _git(folder, "show", "%s:%s" % (commit, rel))
        if shown.returncode != 0 or (name + ":").encode() not in shown.stdout:
            continue
        try:
            entry = (yaml.load(shown.stdout, Loader=loader) or {}).get(name)
        except yaml.YAMLError:
            continue
        if not isinstance(entry, dict) or not entry.get("weights"):
            continue
        blob = _git(folder, "show", "%s:%s" % (commit, os.path.join(os.path.dirname(rel), str(entry["weights"]))))
        if blob.returncode == 0 and is_torch_archive(blob.stdout):
            return commit, blob.stdout
    return None


def _sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def problems(registry=REGISTRY, variants_dir=VARIANTS_DIR):
    """Where the registries disagree with each other or with the tree."""
    found = []
    try:
        names = set(variants(variants_dir))
        entries = runs(registry)
    except RegistryError as e:
        return [str(e)]
    keys = {}
    root = os.path.dirname(os.path.dirname(os.path.abspath(registry)))  # the records' checkout: log paths are its
    for name, e in entries.items():
        if e.get("variant_config"):
            if e["variant"] in names:
                found.append("run %s: trained on a variant file of its own, %s, under a name of the project's, %r"
                             % (name, e["variant_config"], e["variant"]))
            for field, sha in (("variant_config", "variant_sha256"), ("map_file", "map_sha256")):
                if not os.path.isfile(e[field]):
                    found.append("run %s: %s %s does not exist" % (name, field, e[field]))
                elif _sha256(e[field]) != e[sha]:
                    found.append("run %s: %s %s has changed since the run trained (its sha256 is not %s)"
                                 % (name, field, e[field], e[sha]))
        elif e["variant"] not in names:
            found.append("run %s: variant %r has no file in %s" % (name, e["variant"], variants_dir))
        path = weights_path(e, registry)
        if path:
            if not os.path.isfile(path):
                found.append("run %s: weights %s do not exist" % (name, path))
            key = (e["variant"], e["network"], e["game"], role(e))
            if key in keys:
                found.append("runs %s and %s both ship weights for variant %s, network %s, game %s, role %s"
                             % (keys[key], name, *key))
            keys[key] = name
        for field in ("log", "curve"):
            if e.get(field) and not os.path.isfile(os.path.join(root, e[field])):
                found.append("run %s: %s %s does not exist" % (name, field, e[field]))
        if draw(e) == "retrain":
            first = entries.get(e["retrain_of"])
            if first is None:
                found.append("run %s: retrain_of names %s, which is not a run" % (name, e["retrain_of"]))
            elif draw(first) != "first" or any(first.get(k) != e.get(k) for k in ("variant", "network", "game",
                                                                                   "training_seed")):
                found.append("run %s: not a retrain of %s (another draw, variant, network, game or training seed)"
                             % (name, e["retrain_of"]))
            elif name != e["retrain_of"] + RETRAIN_SUFFIX:
                found.append("run %s: a retrain of %s is named %s" % (name, e["retrain_of"],
                                                                    e["retrain_of"] + RETRAIN_SUFFIX))
    listed = {os.path.realpath(weights_path(e, registry)) for e in entries.values() if e.get("weights")}
    for path in sorted(glob.glob(os.path.join(os.path.dirname(registry), "*.pt"))):
        if os.path.realpath(path) not in listed:
            found.append("%s is shipped by no run of %s (one set of weights per variant: remove it or "
                         "record its run)" % (path, registry))
    return found


def _parser():
    parser = argparse.ArgumentParser(prog="hideseek_registry.py", description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--registry", default=REGISTRY, help="the run registry (default: policies/policies.yaml)")
    parser.add_argument("--variants-dir", default=VARIANTS_DIR, help="the variants (default: config/variants)")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("variants", help="the variant names, one per line")
    p.add_argument("--paper-order", action="store_true", help="Table 2's order: the paper's, then the others")
    p = sub.add_parser("runs", help="run names, one per line")
    p.add_argument("--variant")
    p.add_argument("--game")
    p.add_argument("--network", choices=NETWORKS)
    p = sub.add_parser("shipped", help="the shipped weights' path (exit 1: none), or with --all every shipped policy")
    p.add_argument("variant", nargs="?")
    p.add_argument("--all", action="store_true")
    p.add_argument("--network", default="ff", choices=NETWORKS)
    p.add_argument("--game", default=None, help="default: config/games.yaml's")
    p = sub.add_parser("record", help="adds or updates a run's entry (key= removes the key)")
    p.add_argument("run")
    p.add_argument("fields", nargs="+", metavar="key=value")
    p = sub.add_parser("ship", help="copies WEIGHTS to policies/ and makes RUN the shipped run of its key")
    p.add_argument("run")
    p.add_argument("weights")
    p = sub.add_parser("ship-median", help="ships the sweep run whose greedy evaluation is its variant's median")
    p.add_argument("variant")
    p.add_argument("--weights-dir", required=True, help="the folder of the runs' folders (<run>/policy.pt)")
    p.add_argument("--network", default="ff", choices=NETWORKS)
    p.add_argument("--game", default=None, help="default: config/games.yaml's")
    p.add_argument("--note", default=SWEEP_NOTE, help="the runs considered: those whose note starts with this")
    sub.add_parser("check", help="exit 1, naming the problem, where the registries disagree with each other or the tree")
    return parser


def _print_variants(args):
    print("\n".join(paper_order(args.variants_dir) if args.paper_order else variants(args.variants_dir)))


def _print_shipped(args):
    if args.all:
        for v in paper_order(args.variants_dir):
            for network in NETWORKS:
                _, path = shipped(v, network, args.game, args.registry)
                if path:
                    print(label(v, network), v, network, path)
        return 0
    if not args.variant:
        raise RegistryError("shipped: name a VARIANT, or --all")
    _, path = shipped(args.variant, args.network, args.game, args.registry)
    if not path:
        print("hideseek_registry: no %s policy is shipped for variant %s on game %s"
              % (args.network, args.variant, args.game or default_game()), file=sys.stderr)
        return 1
    print(path)
    return 0


def _record(args):
    fields = {}
    for item in args.fields:
        key, sep, value = item.partition("=")
        if not sep or key not in RUN_KEYS:
            raise RegistryError("record: %r is not key=value with a key among %s" % (item, ", ".join(RUN_KEYS)))
        if value == "":
            fields[key] = None
        else:
            fields[key] = _value(value) if key not in ("commit", "game", "log", "curve") else value
    record(args.run, fields, args.registry)


def _ship_median(args):
    root = os.path.dirname(os.path.dirname(os.path.abspath(args.registry)))
    print("hideseek_registry: " + ship_median(args.variant, args.weights_dir, args.network, args.game, args.registry,
                                              root, args.note))


def _check(args):
    found = problems(args.registry, args.variants_dir)
    for problem in found:
        print("hideseek_registry: " + problem, file=sys.stderr)
    return 1 if found else 0


COMMANDS = {
    "variants": _print_variants,
    "runs": lambda args: print("\n".join(select(args.variant, args.game, args.network, args.registry))),
    "shipped": _print_shipped,
    "record": _record,
    "ship": lambda args: ship(args.run, args.weights, args.registry),
    "ship-median": _ship_median,
    "check": _check,
}


def main(argv=None):
    """The command line (the module's docstring); exit 1 where nothing is shipped or the check finds a
    problem, 2 where a registry cannot be read."""
    args = _parser().parse_args(argv)
    try:
        return COMMANDS[args.command](args) or 0
    except WeightsMissing as e:
        print("hideseek_registry: %s" % e, file=sys.stderr)
        return 1
    except RegistryError as e:
        print("hideseek_registry: %s" % e, file=sys.stderr)
        return 2
