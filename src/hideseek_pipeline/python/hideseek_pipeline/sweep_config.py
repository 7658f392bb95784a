"""config/sweep.yaml: the sweep's settings and its phases.

A phase is one block of runs: its game, variants, training seeds, network and steps, and the commit
its runs train at. The queue trains the phases in their order, and within a phase seed-major (seed 0
of every variant, then seed 1, ...), so that it can be cut off anywhere. A key at the top level is
every phase's default; a phase may set any of them. Environment variables SWEEP_<KEY>
(SWEEP_SEEDS="0 1 2", SWEEP_VARIANTS="basic slowerhider", SWEEP_JOBS=2, ...) override a key in every
phase; SWEEP_PHASES="a b" keeps only the phases named.

A phase's `role` is who learns: hider (the default) or seeker. A seeker's phase trains seekers
against `opponent` (default: each variant's hider shipped on the phase's game), evaluates each as a
seeker and ships nothing; its runs are named <variant>_seeker[_<game>]..._seed<S>. A self-play
phase (role: selfplay) trains both sides in `generations` generations, `steps` per side in all (each
generation's opponent drawn with the latest generation's `latest_share`, unset: the pin's default), then
plays their cross-play and records it (hideseek_pipeline selfplay --record); it ships nothing, and
its runs are named <variant>_selfplay[_<game>][_latest<percent>]_seed<S>.

A phase's `start_within_min` keeps a long run for a session's beginning: its runs start only within
that many minutes of the queue's start (0, the default: any time); past it the queue goes on with
the phases after it, and the run waits for the queue's next start.
"""
import os
from dataclasses import dataclass, field
from typing import List, Optional

import yaml

TWO_MILLION = 2_000_000
PHASE_KEYS = ("commit", "game", "variants", "seeds", "network", "steps", "precision", "jobs", "hider_threads", "ship",
              "role", "opponent", "generations", "latest_share", "start_within_min")
TOP_KEYS = PHASE_KEYS + ("port", "phases", "retrain")
NETWORKS = ("ff", "gru")
ROLES = ("hider", "seeker", "selfplay")


class ConfigError(Exception):
    """A bad config/sweep.yaml or SWEEP_<KEY>, named in the message."""


@dataclass
class Phase:
    name: str
    commit: str
    game: str
    variants: List[str]
    seeds: List[int]
    network: str
    steps: int
    precision: str
    jobs: int
    hider_threads: int
    ship: bool = True  # ship each variant's median run of this phase as the variant's policy
    role: str = "hider"  # who learns: hider or seeker
    opponent: str = ""   # the fixed other side ('': the default, a seeker's: the shipped hider)
    generations: int = 4  # self-play: generations of each side (steps / generations each)
    latest_share: Optional[float] = None  # self-play: the draw's share of the latest opponent (None: the pin's default)
    start_within_min: float = 0  # a run of it starts only this soon after the queue's start (0: any time)


@dataclass
class Run:
    """One run of the queue: its name (what tells it apart from every other run), variant, seed and
    phase; `retrain` for a retrain of a done run whose weights are lost."""
    name: str
    variant: str
    seed: int
    phase: Phase
    retrain: bool = False


@dataclass
class SweepConfig:
    port: int
    path: str = ""
    phases: List[Phase] = field(default_factory=list)
    retrain: List[str] = field(default_factory=list)  # done runs whose weights are lost, to train again

    def runs(self):
        """Every run of every phase, in the queue's order."""
        return [run for phase in self.phases for run in phase_runs(phase)]


def budget_label(steps):
    """'' for the 2M steps of every run so far, else the budget: 8000000 -> '8m', 500000 -> '500k'."""
    if steps == TWO_MILLION:
        return ""
    if steps % 1_000_000 == 0:
        return "%dm" % (steps // 1_000_000)
    if steps % 1000 == 0:
        return "%dk" % (steps // 1000)
    return str(steps)


def probability(value):
    """`value` as a number from 0 to 1, or None where it is not one (the config's and the command
    line's check of a share)."""
    try:
        value = float(value)
    except (TypeError, ValueError):
        return None
    return value if 0.0 <= value <= 1.0 else None


def start_window(phase):
    """What the phase's start_within_min means, for a person ('' where it has none)."""
    if not phase.start_within_min:
        return ""
    return "starts a run only within %g min of the queue's start" % phase.start_within_min


def run_name(variant, seed, game, network, steps, role="hider", latest_share=None):
    """The run's name: what tells it apart. v2's feed-forward 2M runs keep their names
    (basic_seed0, basic_gru_seed1); a seeker, another game, network or budget adds itself:
    basic_v3_seed0, basic_v3_gru_seed0, basic_v3_8m_seed0, basic_seeker_v3_seed0, basic_selfplay_v3_seed0;
    a self-play that draws its latest opponent with a share adds it in percent (basic_selfplay_v3_latest50_seed0;
    the uniform draw, share 0 or unset, adds nothing)."""
    parts = [variant]
    if role != "hider":
        parts.append(role)
    if game != "v2":
        parts.append(game)
    if role == "selfplay" and latest_share:
        parts.append("latest%g" % round(100 * latest_share, 1))
    if network != "ff":
        parts.append(network)
    if budget_label(steps):
        parts.append(budget_label(steps))
    return "_".join(parts) + "_seed%d" % seed


def phase_runs(phase):
    return [Run(run_name(v, s, phase.game, phase.network, phase.steps, phase.role, phase.latest_share), v, s, phase)
            for s in phase.seeds for v in phase.variants]


def _whole(value, key, where, minimum=0):
    text = str(value).strip()
    if not text.lstrip("-").isdigit() or int(text) < minimum:
        raise ConfigError("%s: %s: '%s' is not a whole number%s" % (
            where, key, value, "" if minimum == 0 else " >= %d" % minimum))
    return int(text)


def _words(value):
    if isinstance(value, list):
        return [str(x) for x in value]
    return str(value).split()


def _env_overrides(environ):
    out = {}
    for key in PHASE_KEYS + ("port",):
        text = environ.get("SWEEP_" + key.upper())
        if text:
            out[key] = text
    return out


def load(path, known_variants, paper_order, default_game, environ=None):
    """Reads the sweep's config; `known_variants` are config/variants' names, `paper_order` what
    `variants: all` means, `default_game` the game a phase without one plays."""
    environ = os.environ if environ is None else environ
    try:
        with open(path) as f:
            raw = yaml.safe_load(f) or {}
    except (OSError, yaml.YAMLError) as e:
        raise ConfigError("cannot read %s: %s" % (path, e))
    if not isinstance(raw, dict):
        raise ConfigError("%s: not a mapping of keys" % path)
    unknown = sorted(set(raw) - set(TOP_KEYS))
    if unknown:
        raise ConfigError("%s: unknown key %s (keys: %s)" % (path, unknown[0], ", ".join(TOP_KEYS)))
    where = os.path.basename(path)
    overrides = _env_overrides(environ)
    top = {k: v for k, v in raw.items() if k not in ("phases", "retrain")}
    raw_phases = raw.get("phases") or [{"name": "sweep"}]
    if not isinstance(raw_phases, list):
        raise ConfigError("%s: phases: a list of phases" % where)
    phases, names = [], set()
    wanted = environ.get("SWEEP_PHASES", "").split()
    for i, rp in enumerate(raw_phases):
        if not isinstance(rp, dict) or not rp.get("name"):
            raise ConfigError("%s: phases[%d]: a mapping with a name" % (where, i))
        bad = sorted(set(rp) - set(PHASE_KEYS) - {"name"})
        if bad:
            raise ConfigError("%s: phase %s: unknown key %s" % (where, rp["name"], bad[0]))
        merged = dict(top, **rp)
        merged.update(overrides)
        phases.append(_phase(merged, "%s: phase %s" % (where, rp["name"]), known_variants, paper_order,
                             default_game))
        if phases[-1].name in names:
            raise ConfigError("%s: two phases are named %s" % (where, phases[-1].name))
        names.add(phases[-1].name)
    missing = [w for w in wanted if w not in names]
    if missing:
        raise ConfigError("SWEEP_PHASES: no phase %s in %s" % (missing[0], where))
    if wanted:
        phases = [p for p in phases if p.name in wanted]
    port = _whole(overrides.get("port", raw.get("port", 12100)), "port", where, 1)
    config = SweepConfig(port=port, path=os.path.abspath(path), phases=phases)
    seen = {}
    for run in config.runs():
        if run.name in seen:
            raise ConfigError("%s: phases %s and %s both hold the run %s" % (
                where, seen[run.name], run.phase.name, run.name))
        seen[run.name] = run.phase.name
    config.retrain = _retrain(raw.get("retrain"), where, {r.name: r for r in config.runs()}, bool(wanted))
    return config


def _retrain(value, where, runs, some_phases):
    """The `retrain` list: runs of the queue, each a hider's (a retrain recovers weights a variant
    ships). With SWEEP_PHASES, the runs of the phases left out are dropped, not refused."""
    names = _words(value) if value is not None else []
    for name in names:
        run = runs.get(name)
        if run is None and some_phases:
            continue
        if run is None:
            raise ConfigError("%s: retrain: '%s' is not a run of the queue (hideseek_pipeline sweep status lists them)"
                              % (where, name))
        if run.phase.role != "hider":
            raise ConfigError("%s: retrain: '%s' is a %s phase's run, which ships no weights to recover"
                              % (where, name, run.phase.role))
    return [n for n in dict.fromkeys(names) if n in runs]


def _phase(m, where, known_variants, paper_order, default_game):
    for key in ("commit", "steps", "seeds", "network", "precision", "jobs", "hider_threads", "variants"):
        if key not in m:
            raise ConfigError("%s: no %s (set it in the phase or at the top)" % (where, key))
    variants = _words(m["variants"])
    if variants == ["all"]:
        variants = list(paper_order)
    for v in variants:
        if v not in known_variants:
            raise ConfigError("%s: variants: no variant '%s' in config/variants" % (where, v))
    network = str(m["network"])
    if network not in NETWORKS:
        raise ConfigError("%s: network: '%s' is not one of %s" % (where, network, ", ".join(NETWORKS)))
    commit = str(m["commit"])
    if not commit or commit == "PIN":
        raise ConfigError("%s: commit is not set (pin a commit of main)" % where)
    role = str(m.get("role") or "hider")
    if role not in ROLES:
        raise ConfigError("%s: role: '%s' is not one of %s" % (where, role, ", ".join(ROLES)))
    ship = _flag(m.get("ship", role == "hider"), "ship", where)
    if ship and role != "hider":
        raise ConfigError("%s: ship: a %s phase ships nothing (set ship: false)"
                          % (where, "seeker's" if role == "seeker" else "self-play"))
    generations = _whole(m.get("generations", 4), "generations", where, 1)
    latest_share = m.get("latest_share")
    if latest_share is not None:
        if role != "selfplay":
            raise ConfigError("%s: latest_share: only a self-play phase draws its opponents" % where)
        latest_share = probability(latest_share)
        if latest_share is None:
            raise ConfigError("%s: latest_share: '%s' is not a number from 0 to 1" % (where, m["latest_share"]))
    try:
        start_within_min = float(m.get("start_within_min", 0))
    except (TypeError, ValueError):
        start_within_min = -1.0
    if not start_within_min >= 0:
        raise ConfigError("%s: start_within_min: '%s' is not a number of minutes >= 0 (0: any time)"
                          % (where, m["start_within_min"]))
    if role == "selfplay":
        if network != "ff" or m.get("opponent"):
            raise ConfigError("%s: a self-play phase trains feed-forward learners against each other's pools "
                              "(no network other than ff, no opponent)" % where)
        if _whole(m["steps"], "steps", where, 1) % generations:
            raise ConfigError("%s: steps: %s is not a whole number of generations (%d): a generation trains "
                              "steps / generations a side" % (where, m["steps"], generations))
    return Phase(name=str(m["name"]), commit=commit, game=str(m.get("game") or default_game), variants=variants,
                 seeds=[_whole(s, "seeds", where) for s in _words(m["seeds"])], network=network,
                 steps=_whole(m["steps"], "steps", where, 1), precision=str(m["precision"]),
                 jobs=_whole(m["jobs"], "jobs", where, 1),
                 hider_threads=_whole(m["hider_threads"], "hider_threads", where, 1), ship=ship, role=role,
                 opponent=str(m.get("opponent") or ""), generations=generations, latest_share=latest_share,
                 start_within_min=start_within_min)


def _flag(value, key, where):
    if isinstance(value, bool):
        return value
    if str(value).lower() in ("true", "false"):
        return str(value).lower() == "true"
    raise ConfigError("%s: %s: '%s' is not true or false" % (where, key, value))
