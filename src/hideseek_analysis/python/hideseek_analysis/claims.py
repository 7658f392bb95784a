"""The claims table: every claim of the paper decided on the sweep's runs, with the effect size and
the 95 % interval that decide it, on each game the sweep trains and side by side.

Reads each game's sweep runs (runs.py selects them: registry entries <variant>[_<game>][_<budget>]_seed<S>,
plus --extra of that game), each run's evaluation (docs/runs/<run>/episodes.csv) and per-run
analysis (docs/runs/<run>/analysis/: probes.csv, states.csv, transitions.csv, behaviour.csv,
written by hideseek_pipeline analyze), the random hider's behaviour per variant
(docs/analysis/baselines/[<game>/]<variant>/random/) and its living steps (the game's calibration
table), and for the memory claim the sweep's GRU runs (of the variants config/sweep.yaml trains GRU
hiders of) with their memoryless ablations (docs/runs/<run>/analysis/memoryless/behaviour.csv).
Writes each game's claims.md/.csv, memory_seeds.md/.csv (the GRU runs against their feed-forward
twins) and oscillation_thresholds.md/.csv into OUT/<game>/, and the claims on both games side by
side into OUT/claims.md (default OUT ROOT/docs/report); the budget check (basic at the longer
budget config/sweep.yaml trains, against 2M) is the last row of that game's table.

Every interval is a 95 % percentile bootstrap over the runs (training seeds) of each variant
involved, resampled within each variant; living steps use the two-level bootstrap (runs, then
episodes). The interval decides the size as it decides the direction: a claim is **supported**
when its interval lies wholly on the paper's side of zero and at or beyond the measure's practical
size (PRACTICAL), **contradicted** when the same holds on the other side, **negligible** when the
interval excludes zero and lies wholly under the practical size, and **inconclusive** otherwise (an
interval across zero, or one that excludes zero but crosses the practical size: the direction is
shown, the size is not), or when a variant it needs has fewer than MIN_RUNS runs (an
interval over one training seed says nothing about seeds). Only each seed's first training counts:
a retrain (<run>_retrain) never does. Where a claim is not supported, the table names the rules of
this game that depart from the paper, were tested, and could cause it, each with the experiment
that tests it (DEPARTURES; docs/game_rules.md). A transition is decided on its rate per 100 steps,
with the conditional probability beside it; the oscillation on swings of the distance of at least
1 m, with the old measure beside it and the threshold's effect in oscillation_thresholds.md.
"""
import os
import re

import numpy as np

from . import stats as st
from .config import Config
from .runs import (Runs, calibration, calibration_file, evaluation_by_seed, load_episodes, outputs, parse_selection,
                   read_csv, run_name, sweep_runs)
from .states import state_freq, transition_prob, transition_rate
from .tables import probe_value, write_rows

MIN_RUNS = 2
SOUND_RUNS = 3
# What could cause a miss: only rules of this game that depart from the paper (docs/game_rules.md)
# and were tested, or that the experiment named with them tests. Named where a claim is not supported.
DEPARTURES = {
    "a_mode": "game v2's A mode brakes on every turn and stay, so the accelerating hiders barely move "
              "(the random one averages 0.13 m/s against 0.8; every accelerating sweep run stays at 44-58 "
              "living steps; docs/calibration.md): game v3's momentum model is the experiment",
    "seeker_motion": "game v2's seeker turns or moves, never both, so a hider circling it is never caught "
                     "(measured: a 1.9 m circle at the seeker's speed survives 11 of 24 start angles on v2, none on v3; "
                     "docs/calibration.md): game v3's seeker, which turns while it moves, is the experiment",
    "spawn": "the seeker starts knowing the hider's spawn point (the paper's, read literally, explores): "
             "stochasticseeker_explore against stochasticseeker tests it (table2_seeds/readings.md)",
    "steps": "2M training steps per run against the paper's 8M: the 8M budget check on basic is the experiment",
    "colours": "each agent's front has its own colour, so S and H are partly readable from colour (the pixels "
               "baseline of Table 3): a probe set rendered with one colour is the experiment",
}


# The departures a game no longer has: game v3 reads the paper's motion as its engine would run it.
FIXED_ON = {"v3": ("a_mode", "seeker_motion")}
# What changed from game v2 to v3 that bears on a claim whose miss a departure could cause.
CHANGED = {"a_mode": "the A mode: v2 brakes on every turn, v3 keeps the hider's momentum",
           "seeker_motion": "the seeker: v2 turns or moves, v3 turns while it moves"}


class Causes(str):
    """The departures that could cause a miss, in words, with their DEPARTURES keys (`keys`)."""

    def __new__(cls, keys, game="v2"):
        gone = [CHANGED.get(k, k) for k in keys if k in FIXED_ON.get(game, ())]
        text = "; ".join(DEPARTURES[k] for k in keys if k not in FIXED_ON.get(game, ()))
        if gone and not text:  # every departure named is one this game no longer has: say so, not nothing
            text = "no tested cause left on game %s: what could cause it on v2 is gone here (%s)" % (
                game, "; ".join(gone))
        elif gone:
            text += " (gone on game %s, which could cause it on v2: %s)" % (game, "; ".join(gone))
        made = super().__new__(cls, text)
        made.keys = tuple(keys)
        return made


# The smallest effect that counts, per measure (in the measure's own units): an interval must lie
# wholly at or beyond it to support or contradict a claim; one that excludes zero but lies wholly
# under it is "negligible".
PRACTICAL = {
    "rho": (0.3, "a rho of 0.3 either way"),
    "living": (25.0, "25 living steps (2.5 % of an episode)"),
    "accuracy": (0.02, "0.02 balanced accuracy"),
    "bend": (0.01, "a bend of 0.01 balanced accuracy across the runs' range"),
    "share": (0.02, "0.02 of the steps"),
    "rate": (0.2, "0.2 transitions per 100 steps"),
    "swings": (0.5, "0.5 swings per 100 steps"),
}



def verdict(ci, n_min, sign=1.0, practical=0.0):
    """The verdict on an effect whose paper side is sign * effect > 0, from its interval alone, which
    decides the size as it decides the direction: supported where the interval lies wholly on the
    paper's side and at or beyond the practical size; contradicted, the same on the other side;
    negligible where it excludes zero and lies wholly under the size; inconclusive otherwise: an
    interval across zero, or one that excludes zero but crosses the size (the direction is shown,
    the size is not), or fewer than MIN_RUNS runs of a variant."""
    if n_min < MIN_RUNS or not np.all(np.isfinite(ci)):
        return "inconclusive"
    lo, hi = sorted((sign * ci[0], sign * ci[1]))
    if lo <= 0 <= hi:
        return "inconclusive"
    near, far = (lo, hi) if lo > 0 else (-hi, -lo)  # the interval's ends, by their distance from zero
    if far < practical:
        return "negligible"
    if near >= practical:
        return "supported" if lo > 0 else "contradicted"
    return "inconclusive"


def claim(name, paper, measure, point=None, ci=None, runs="", result="inconclusive", note="", departure="",
          practical=""):
    return {"claim": name, "paper": paper, "measure": measure,
            "effect": "" if point is None else round(point, 4),
            "ci_low": "" if ci is None or not np.isfinite(ci[0]) else round(ci[0], 4),
            "ci_high": "" if ci is None or not np.isfinite(ci[1]) else round(ci[1], 4),
            "practical": practical, "runs": runs, "result": result, "note": note,
            "departure": "" if result == "supported" else departure, "causes": getattr(departure, "keys", ())}


def decide(ci, n_min, kind, sign=1.0):
    """verdict() with the practical size of a measure of PRACTICAL's kind; (result, its text)."""
    size, text = PRACTICAL[kind]
    return verdict(ci, n_min, sign, size), text


def runs_text(per_variant):
    return ", ".join("%s %d" % (v, len(x)) for v, x in per_variant.items()) or "none"


def missing(per_variant, needed):
    short = [v for v in needed if len(per_variant.get(v, [])) < MIN_RUNS]
    return ("needs at least %d runs of: %s" % (MIN_RUNS, ", ".join(short))) if short else ""


def fewest(per_variant, needed):
    """The fewest runs of a variant among `needed`; 0 while one of them has none."""
    return min(len(x) for x in per_variant.values()) if len(per_variant) == len(needed) else 0


def mean_of_means(sample):
    return np.mean([x.mean() for x in sample.values()])


def effect_text(r):
    """A claim's effect with its interval, where it has one: 0.123 [0.100, 0.150]."""
    if r["effect"] == "":
        return "-"
    return "%.3f" % r["effect"] + ("" if r["ci_low"] == "" else " [%.3f, %.3f]" % (r["ci_low"], r["ci_high"]))


class Context:
    """What every claim reads: the runs, the lists from config/, and the bootstrap's seed and size.
    Each claim bootstraps with its own generator (stats.keyed_rng)."""

    def __init__(self, root, found, cfg, seed, reps, game="v2", gru_found=None, twins=None):
        self.root, self.R, self.seed, self.reps, self.game = root, Runs(root, found, game), seed, reps, game
        self.cfg = cfg
        self.paper = cfg.paper
        self.variants = tuple(cfg.paper_variants)
        self.faster = cfg.faster_hiders
        self.gru_variants = cfg.gru_variants(game)
        self.calib = calibration(root, game)
        self.gru_found = gru_found or {}
        # The feed-forward runs the GRU runs are paired with (the budget check swaps basic's runs
        # for its longer ones, not the GRU's twins).
        self.twins = Runs(root, twins if twins is not None else found, game)

    def rng(self, *key):
        return st.keyed_rng(self.seed, *key)

    def causes(self, *keys):
        """The departures of this game that could cause a miss (those it no longer has left out)."""
        return Causes(keys, self.game)


ORDERING = ("Table 2's ordering of the variants", "the order of Table 2's living steps")


def ordering_claim(c, living):
    """1. Table 2's ordering: Spearman's rho with the paper's living steps (the key Table 2 uses, so
    the same interval in both)."""
    if len(living) < 3:
        return claim(*ORDERING, "Spearman's rho with the paper's living steps", runs=runs_text(living),
                     note="needs at least three of the paper's variants evaluated")
    vs = list(living)
    rho, ci = st.rank_correlation([living[v] for v in vs], [c.paper[v]["living_trained"] for v in vs], c.rng("rho"),
                                  c.reps)
    res, size = decide(ci, fewest(living, c.variants), "rho")
    return claim(*ORDERING, "Spearman's rho with the paper's living steps (%d variants)" % len(vs), rho, ci,
                 runs_text(living), res, missing(living, c.variants), c.causes("a_mode", "seeker_motion"), size)


BEATS_RANDOM = ("Every variant's hider outlives the random hider", "Table 2: trained > random on every variant")


def beats_random_claim(c, living):
    """2. Every variant beats the random hider: the variant whose difference has the lowest lower bound."""
    diffs = {}
    for v, runs in living.items():
        rnd = [float(r["avg_living_steps"]) for r in c.calib.get(v, []) if r["evader"] == "random"]
        if rnd:
            # The key of Table 2's greedy mean: the same interval in both.
            point, ci = st.pooled_statistic(runs, st.mean, c.rng(v, "greedy", "living_mean"), c.reps)
            diffs[v] = (point - rnd[0], (ci[0] - rnd[0], ci[1] - rnd[0]), len(runs))
    if not diffs:
        return claim(*BEATS_RANDOM, "living steps, trained minus random", runs=runs_text(living),
                     note="needs evaluated runs and the random hider's row of docs/%s" % calibration_file(c.game))
    n_min = min(x[2] for x in diffs.values()) if len(diffs) == len(c.variants) else 0
    # Decided on the variant with the lowest lower bound, unless a variant's whole interval lies at
    # or beyond the practical size under the random hider: that one contradicts the claim, and the
    # row shows it (the lowest upper bound among them).
    below = [v for v, x in diffs.items() if x[1][1] <= -PRACTICAL["living"][0]]
    if below and n_min >= MIN_RUNS:
        v_worst, why = min(below, key=lambda v: diffs[v][1][1]), "wholly below the random hider"
    else:
        v_worst, why = min(diffs, key=lambda v: diffs[v][1][0]), "the lowest lower bound"
    d = diffs[v_worst]
    res, size = decide(d[1], n_min, "living")
    made = claim(*BEATS_RANDOM, "living steps, trained minus random; the variant with %s (%s)" % (why, v_worst), d[0],
                 d[1], runs_text(living), res, missing(living, c.variants), c.causes("a_mode", "steps"), size)
    made["focus"] = "%s's, %s" % (v_worst, why)  # the table on both games has no measure column
    return made


def features_claims(c):
    """3. Trained features beat random-init ones, on S and on H."""
    out = []
    for target, label in (("S", "S (the hider sees the seeker)"), ("H", "H (the seeker sees the hider)")):
        gains = {v: [probe_value(rows, target) for _, rows in c.R.analysed(v, "probes")] for v in c.variants}
        gains = {v: x for v, x in gains.items() if x}
        if not gains:
            out.append(claim("Trained features beat random-init ones on %s" % target, "Table 3: trained > random init",
                             "balanced accuracy gain on %s, on the shared probe set" % label, note="no run analysed yet"))
            continue
        point, ci = st.boot_runs(gains, mean_of_means, c.rng("features", target), c.reps)
        res, size = decide(ci, fewest(gains, c.variants), "accuracy")
        out.append(claim("Trained features beat random-init ones on %s" % target, "Table 3: trained > random init",
                         "balanced accuracy on the shared probe set, trained minus the mean of 5 random-init "
                         "networks, mean over variants", point, ci, runs_text(gains), res,
                         missing(gains, c.variants), c.causes("colours", "steps"), size))
    return out


WORST = "visibilityreward_faster"
PERCEPTION = ("%s is worst at perception" % WORST, "Table 3: lowest trained probe accuracy")


def perception_claim(c):
    """4. visibilityreward_faster is worst at perception: its mean S and H accuracy minus the lowest other's."""
    acc = {v: [(probe_value(rows, "S", "balanced_accuracy") + probe_value(rows, "H", "balanced_accuracy")) / 2
               for _, rows in c.R.analysed(v, "probes")] for v in c.variants}
    acc = {v: x for v, x in acc.items() if x}
    if WORST not in acc or len(acc) < 2:
        return claim(*PERCEPTION, "mean of S and H balanced accuracy against the other variants", runs=runs_text(acc),
                     note="needs %s and another variant analysed" % WORST)

    def margin(s):
        return s[WORST].mean() - min(x.mean() for v, x in s.items() if v != WORST)
    point, ci = st.boot_runs(acc, margin, c.rng("worst at perception"), c.reps)
    res, size = decide(ci, fewest(acc, c.variants), "accuracy", -1.0)
    return claim(*PERCEPTION, "mean of S and H balanced accuracy, %s minus the lowest other variant" % WORST,
                 point, ci, runs_text(acc), res, missing(acc, c.variants), c.causes("colours", "a_mode"), size)


CONCAVE = ("Survival and representation follow a concave curve", "Figure 7: an inverted U")


def _concave_fit(x, y, groups, rng, reps):
    """The quadratic coefficient of y against x with its bootstrap interval over points, and the
    leave-one-variant-out RMSE of the linear and the quadratic fit {1: e1, 2: e2}."""
    quad = float(np.polyfit(x, y, 2)[0])
    boot = []
    for _ in range(reps):
        i = rng.integers(0, len(x), len(x))
        if len(np.unique(x[i])) >= 3:
            boot.append(np.polyfit(x[i], y[i], 2)[0])
    err = {}
    for deg in (1, 2):
        e = []
        for g in sorted(set(groups)):
            train, test = groups != g, groups == g
            if len(np.unique(x[train])) > deg:
                e.extend((np.polyval(np.polyfit(x[train], y[train], deg), x[test]) - y[test]) ** 2)
        err[deg] = float(np.sqrt(np.mean(e)))
    return quad, st.interval(boot), err


def bend_scale(x):
    """(range of x / 2)^2: a quadratic coefficient a times it is the curve's bend across that range,
    its largest distance from its chord there (PRACTICAL["bend"]'s units)."""
    return ((np.max(x) - np.min(x)) / 2) ** 2


def concave_claim(c):
    """5. Survival and representation: a concave curve over one point per run (living steps, probe gain)."""
    pts = []
    for v in c.variants:
        for name, rows in c.R.analysed(v, "probes"):
            if os.path.exists(c.R.path(name, "episodes.csv")):
                living = load_episodes(c.R.path(name, "episodes.csv"))[0].mean()
                pts.append((v, living, (probe_value(rows, "S") + probe_value(rows, "H")) / 2))
    variants_in = sorted({p[0] for p in pts})
    if not (len(pts) >= 6 and len(variants_in) >= 3 and len({round(p[1], 6) for p in pts}) >= 3):
        return claim(*CONCAVE, "quadratic coefficient of probe gain against living steps, one point per run",
                     runs="%d runs of %d variants" % (len(pts), len(variants_in)),
                     note="needs at least 6 analysed runs of 3 variants")
    x = np.array([p[1] for p in pts]) / 1000.0
    groups = np.array([p[0] for p in pts])
    quad, ci, err = _concave_fit(x, np.array([p[2] for p in pts]), groups, c.rng("concave curve"), c.reps)
    per_variant = min(int((groups == g).sum()) for g in variants_in)
    # The practical size is a bend: the quadratic's largest distance from its chord across the
    # runs' range of x, |a| (range / 2)^2, of at least PRACTICAL["bend"] balanced accuracy.
    bend = abs(quad) * bend_scale(x)
    res = verdict(tuple(np.multiply(ci, bend_scale(x))), per_variant if len(variants_in) == len(c.variants) else 0,
                  -1.0, PRACTICAL["bend"][0])
    if res == "supported" and err[2] >= err[1]:
        res = "inconclusive"
    return claim(*CONCAVE, "quadratic coefficient of probe gain (mean of S, H) against living steps / 1000, one point "
                 "per run; its bend across the runs' range %.4f; leave-one-variant-out RMSE linear %.4f, quadratic "
                 "%.4f (%s predicts better)" % (bend, err[1], err[2], "the quadratic" if err[2] < err[1] else "the linear"),
                 quad, ci, "%d runs of %d variants" % (len(pts), len(variants_in)), res, "", c.causes("steps", "a_mode"),
                 PRACTICAL["bend"][1])


def relative(c, variants, tables, fn, label, paper_text, departure, kind):
    """A behaviour of the trained hider against the random hider of the same variant: fn(get) reads a
    run's tables through get(table) (the run's analysis, or the random hider's baseline)."""
    per = {}
    for v in variants:
        if not all(c.R.baseline(v, t) for t in tables):
            continue
        base = fn(lambda t: c.R.baseline(v, t))
        vals = [fn(lambda t, n=n: c.R.analysis(n, t)) - base for n in c.R.names(v)
                if all(c.R.analysis(n, t) for t in tables)]
        vals = [x for x in vals if np.isfinite(x)]
        if vals:
            per[v] = vals
    if not per:
        return claim(label, paper_text, "trained minus the random hider", runs="none",
                     note="no analysed run (or no random-hider baseline) of %s" % ", ".join(variants),
                     practical=PRACTICAL[kind][1])
    point, ci = st.boot_runs(per, mean_of_means, c.rng(label), c.reps)
    res, size = decide(ci, fewest(per, variants), kind)
    return claim(label, paper_text, "trained minus the random hider of the same variant", point, ci,
                 runs_text(per), res, missing(per, variants), departure, size)


TURN_AWAY, RUN_OFF = ((1, 1), (0, 1)), ((0, 1), (0, 0))


def transition_claim(c, variants, label, paper_text, move, what):
    """A transition decided on its rate per 100 steps; the conditional form beside it."""
    motion = c.causes("seeker_motion")
    by_rate = relative(c, variants, ("transitions", "states"),
                       lambda get: transition_rate(get("transitions"), get("states"), *move), label, paper_text,
                       motion, "rate")
    cond = relative(c, variants, ("transitions",), lambda get: transition_prob(get("transitions"), *move),
                    label + " (given)", paper_text, motion, "rate")
    by_rate["measure"] = ("%s per 100 steps, trained minus the random hider of the same variant (beside it, "
                          "P(it | the hider leaves %s), trained minus random: %s)" % (what, what.split(" -> ")[0],
                                                                                  effect_text(cond)))
    if by_rate["departure"]:
        by_rate["departure"] += factors_pointer(what.split(" -> ")[0])
    return by_rate


def factors_pointer(state):
    """Where a missed transition's rate is split into its factors, run by run (tables.transition_factors_table)."""
    return ("; measured: the rate's three factors run by run beside the random hider's (time in the from-state, %s; "
            "how often the hider leaves it; where it goes) in "
            "[transitions_factors_seeds.md](transitions_factors_seeds.md)" % state)


def turn_then_run_claim(c):
    """6. basic turns away, then runs: both transitions must hold."""
    c6a = transition_claim(c, ("basic",), "basic turns away ...", "Figure 5: basic turns away from the seeker",
                           TURN_AWAY, "S1H1 -> S0H1")
    c6b = transition_claim(c, ("basic",), "... then runs", "Figure 5: then runs out of sight", RUN_OFF, "S0H1 -> S0H0")
    both = [c6a["result"], c6b["result"]]
    res = "supported" if both == ["supported"] * 2 else ("contradicted" if "contradicted" in both else
                                                         "negligible" if "negligible" in both and "inconclusive" not in both
                                                         else "inconclusive")
    made = claim("basic turns away, then runs", "Figure 5 and section 5: turn away from the seeker, then run",
                 "S1H1 -> S0H1 and S0H1 -> S0H0 per 100 steps, trained minus random: turn away %s; run %s "
                 "(both must hold)" % (effect_text(c6a), effect_text(c6b)),
                 runs=c6a["runs"], result=res, note=c6a["note"] or c6b["note"],
                 departure=c.causes("seeker_motion", "steps"),
                 practical=PRACTICAL["rate"][1])
    if made["departure"]:
        made["departure"] += factors_pointer("S1H1 and S0H1")
    return made


def behaviour_claims(c):
    """6-8: the behaviours of Figures 4 and 5, each against the random hider of its variant."""
    return [
        turn_then_run_claim(c),
        relative(c, ("slowerhider",), ("states",),
                 lambda get: state_freq(get("states"), lambda s, h, o: s == 0 and h == 0 and o == 1),
                 "slowerhider uses obstacles (not S, not H, O)", "Figure 4: slowerhider's state S0 H0 O1 above random",
                 c.causes("seeker_motion"), "share"),
        relative(c, (WORST,), ("states",), lambda get: state_freq(get("states"), lambda s, h, o: s == 1 and h == 0),
                 "%s watches while hidden (S, not H)" % WORST, "Figure 4: %s's states S1 H0 above random" % WORST,
                 c.causes("a_mode"), "share"),
        transition_claim(c, c.variants, "Transition 1: seen and seeing, the trained hider turns away (S1H1 -> S0H1)",
                         "Figure 5's first highlighted transition (this project's reading)", TURN_AWAY, "S1H1 -> S0H1"),
        transition_claim(c, c.variants, "Transition 2: seen and not seeing, it leaves the seeker's view (S0H1 -> S0H0)",
                         "Figure 5's second highlighted transition (this project's reading)", RUN_OFF, "S0H1 -> S0H0"),
    ]


def swings_of(rows):
    """A run's swings of the distance of at least 1 m per 100 steps, or None where its analysis
    predates the measure."""
    value = rows[0].get("distance_swings_per_100", "") if rows else ""
    return float(value) if value != "" else None


OSCILLATES = ("The faster hiders' distance oscillates", "Figure 6: the faster hiders' distance oscillates")


def oscillation_claim(c):
    """The faster hiders' distance oscillates: swings of at least 1 m per 100 steps, faster hiders
    minus basic. The old measure (turns of the 5-step average, every wobble of an orbit counted) is
    given beside it. Runs analysed before the swings existed, whose weights are lost, are named."""
    needed = c.faster + ("basic",)
    osc, turns, lacking = {}, {}, []
    for v in needed:
        for n, rows in c.R.analysed(v, "behaviour"):
            turns.setdefault(v, []).append(float(rows[0]["distance_turns_per_100"]))
            if swings_of(rows) is None:
                lacking.append(n)
            else:
                osc.setdefault(v, []).append(swings_of(rows))

    def excess(s):
        return np.mean([s[v].mean() for v in c.faster if v in s]) - s["basic"].mean()
    old = "-"
    if "basic" in turns and any(v in turns for v in c.faster):
        p, ci = st.boot_runs(turns, excess, c.rng("oscillates", "turns"), c.reps)
        old = "%.2f" % p + (" [%.2f, %.2f]" % ci if np.all(np.isfinite(ci)) else "")
    measure = ("swings of the distance of at least 1 m per 100 steps, faster hiders minus basic (the old measure, "
               "turns of its 5-step average, where an orbit's wobble counts: %s; the threshold's effect in "
               "oscillation_thresholds.md)" % old)
    note = ("no swings measured for %s (analysed before the measure existed, weights lost)" % ", ".join(lacking)
            if lacking else "")
    departure = c.causes("a_mode", "seeker_motion")
    if "basic" not in osc or not any(v in osc for v in c.faster):
        return claim(*OSCILLATES, measure, runs=runs_text(osc), note=note or "needs basic and a faster hider analysed",
                     departure=departure, practical=PRACTICAL["swings"][1])
    point, ci = st.boot_runs(osc, excess, c.rng("oscillates"), c.reps)
    res, size = decide(ci, fewest(osc, needed), "swings")
    return claim(*OSCILLATES, measure, point, ci, runs_text(osc), res,
                 "; ".join(x for x in (missing(osc, needed), note) if x), departure, size)


THRESHOLDS_INTRO = (
    "Per run of basic and the faster hiders: how often per 100 steps the distance between the agents reverses. "
    "`turns` is the old measure (sign changes of its 5-step moving average: every wobble of an orbit counts); "
    "`swings >= X m` counts only reversals of at least X m (docs/analysis.md). The claim uses 1 m. "
    "A dash: analysed before the swings existed, and the run's weights are lost.")


def oscillation_thresholds(c, out_dir):
    """oscillation_thresholds.md and .csv: per run of basic and the faster hiders whose analysis has
    swings.csv, its swings per 100 steps at each threshold beside the old measure."""
    rows = []
    for v in ("basic",) + c.faster:
        for n, beh in c.R.analysed(v, "behaviour"):
            row = {"variant": v, "run": n, "turns_per_100": float(beh[0]["distance_turns_per_100"])}
            for r in c.R.analysis(n, "swings") or []:
                row["swings_%sm" % r["threshold_m"]] = float(r["swings_per_100"])
            rows.append(row)
    thresholds = sorted({k for r in rows for k in r if k.startswith("swings_")}, key=lambda k: float(k[7:-1]))
    write_rows(os.path.join(out_dir, "oscillation_thresholds.csv"), rows, ["variant", "run", "turns_per_100"] + thresholds)
    md = ["# Oscillation: what the threshold does", "", THRESHOLDS_INTRO, "",
          "| " + " | ".join(["variant", "run", "turns"] + ["swings >= %s m" % k[7:-1] for k in thresholds]) + " |",
          "|" + " --- |" * (3 + len(thresholds))]
    for r in rows:
        md.append("| " + " | ".join([r["variant"], r["run"], "%.2f" % r["turns_per_100"]] +
                                    ["%.2f" % r[k] if k in r else "-" for k in thresholds]) + " |")
    if not thresholds:
        md += ["", "No run here has swings yet."]
    with open(os.path.join(out_dir, "oscillation_thresholds.md"), "w") as f:
        f.write("\n".join(md) + "\n")


MEMORY_CLAIM = ("Failures come from a lack of memory", "section 5: the hider forgets the seeker once out of view")


def _memory_gain(c, name):
    """A GRU run's living steps with its memory minus its memoryless ablation's, or None."""
    with_memory = c.R.analysis(name, "behaviour")
    without = read_csv(c.R.path(name, "analysis", "memoryless", "behaviour.csv"))
    if with_memory and without:
        return float(with_memory[0]["mean_living_steps"]) - float(without[0]["mean_living_steps"])
    return None


def _memory_row(c, v, gru_living, ff_living, pairs, ablation):
    """memory_seeds' row of a variant: the GRU runs, their twins, the difference and the memory gain."""
    row = {"variant": v, "runs": len(gru_living)}
    for key, runs in (("gru", gru_living), ("ff", ff_living), ("difference", pairs)):
        point, ci = st.pooled_statistic(runs, st.mean, c.rng(v, "memory", key), c.reps)
        row.update({key: round(point, 2), key + "_ci_low": round(ci[0], 2), key + "_ci_high": round(ci[1], 2)})
    row["difference_runs"] = len(pairs)
    if ablation:
        point, ci = st.boot_runs({v: ablation}, lambda x: np.mean(list(x.values())[0]), c.rng(v, "memory", "memory_gain"),
                                 c.reps)
        row.update({"memory_gain": round(point, 2),
                    "memory_gain_ci_low": "" if not np.isfinite(ci[0]) else round(ci[0], 2),
                    "memory_gain_ci_high": "" if not np.isfinite(ci[1]) else round(ci[1], 2),
                    "memory_gain_runs": len(ablation)})
    return row


def memory_pairs(c):
    """Each GRU run <variant>_gru_seed<S> paired with the sweep's feed-forward run of the same variant,
    game and training seed, both evaluated greedy on the same evaluation seeds. Returns (pairs:
    {variant: [GRU minus feed-forward per evaluation seed, per pair]}, ablation: {variant: [memory
    gain per GRU run]}, the table's rows, the GRU runs without a twin)."""
    pairs, ablation, table, unpaired = {}, {}, [], []
    for v in c.gru_variants:
        ff_names = set(c.twins.names(v))
        gru_living, ff_living = [], []
        for name, e in c.gru_found.get(v, []):
            twin = run_name(v, int(e.get("training_seed", -1)), c.game)
            gru_path, ff_path = c.R.path(name, "episodes.csv"), c.R.path(twin, "episodes.csv")
            if twin not in ff_names or not os.path.exists(gru_path) or not os.path.exists(ff_path):
                unpaired.append(name)
                continue
            g, f = evaluation_by_seed(gru_path), evaluation_by_seed(ff_path)
            if sorted(g) != sorted(f):
                raise SystemExit("claims: %s and %s were evaluated on different evaluation seeds" % (name, twin))
            gru_living.append(np.array([g[k] for k in sorted(g)]))
            ff_living.append(np.array([f[k] for k in sorted(g)]))
            pairs.setdefault(v, []).append(gru_living[-1] - ff_living[-1])
            gain = _memory_gain(c, name)
            if gain is not None:
                ablation.setdefault(v, []).append(gain)
        if gru_living:
            table.append(_memory_row(c, v, gru_living, ff_living, pairs[v], ablation.get(v)))
    return pairs, ablation, table, unpaired


def _memory_gain_verdict(c, ablation):
    """(the GRU's memory gain in words, its verdict) over the variants' runs."""
    if not ablation:
        return "no memoryless ablation yet", None
    g_point, g_ci = st.boot_runs(ablation, mean_of_means, c.rng("memory", "memory_gain"), c.reps)
    g_verdict = verdict(g_ci, min(len(ablation.get(v, [])) for v in c.gru_variants), 1.0, PRACTICAL["living"][0])
    return "memory minus memoryless %.1f%s" % (
        g_point, " [%.1f, %.1f]" % g_ci if np.all(np.isfinite(g_ci)) else " (one run of a variant: no interval)"), g_verdict


def memory_claim(c):
    """The memory claim and its table. The difference is the mean over a variant's pairs, with the
    two-level bootstrap (pairs, then evaluation seeds within each pair), averaged over the variants;
    the GRU's own memory, from its memoryless ablation (the same policy with its state zeroed at
    every step, on the per-run analysis' rollouts), one value per GRU run, bootstrapped over each
    variant's runs. Supported: the GRU outlives its twin and its memory is what does it (both
    intervals at or beyond the practical size, the ablation there for every pair); contradicted:
    the GRU's interval lies at or beyond the size below its twin; inconclusive otherwise, or while a
    variant has fewer than MIN_RUNS pairs. Returns
    (claim row, table rows)."""
    pairs, ablation, table, unpaired = memory_pairs(c)
    measure = ("living steps, each GRU run minus the feed-forward run of its variant and training seed on the same "
               "evaluation seeds, mean over %s; beside it the GRU's memory: living steps with its state minus its "
               "memoryless ablation" % ", ".join(c.gru_variants))
    if not pairs:
        note = ("not yet trained on game %s (the GRU runs follow the sweep)" % c.game if not unpaired else
                "GRU runs %s have no evaluation or no evaluated feed-forward twin yet" % ", ".join(unpaired))
        return claim(*MEMORY_CLAIM, measure, note=note, practical=PRACTICAL["living"][1]), table
    variants = list(pairs)
    rng = c.rng("memory", "difference")
    point = float(np.mean([np.mean(np.concatenate(pairs[v])) for v in variants]))
    boot = [np.mean([np.mean(np.concatenate(sample)) for sample in samples])
            for samples in zip(*[st.two_level_samples(pairs[v], rng, c.reps) for v in variants])]
    n_min = min(len(pairs.get(v, [])) for v in c.gru_variants)
    ci = st.interval(boot) if n_min >= MIN_RUNS else (np.nan, np.nan)
    result, size = decide(ci, n_min, "living")
    short = [v for v in c.gru_variants if len(pairs.get(v, [])) < MIN_RUNS]
    notes = ["needs at least %d GRU runs, each with its evaluated feed-forward twin, of: %s" % (MIN_RUNS, ", ".join(short))
             ] if short else []
    no_ablation = [v for v in pairs if len(ablation.get(v, [])) < len(pairs[v])]
    gain_text, g_verdict = _memory_gain_verdict(c, ablation)
    if no_ablation:
        notes.append("no memoryless ablation for every GRU run of: %s (hideseek_pipeline sweep analyze)" % ", ".join(no_ablation))
    if result == "supported" and (no_ablation or g_verdict != "supported"):
        result = "inconclusive"
        if not no_ablation:
            notes.append("the GRU outlives its twins, but without its memory it lives as long: not shown to be memory")
    return claim(*MEMORY_CLAIM, measure + " (%s)" % gain_text, point, ci, runs_text(pairs), result, "; ".join(notes),
                 c.causes("steps"), size), table
MEMORY_FIELDS = ["variant", "runs", "gru", "gru_ci_low", "gru_ci_high", "ff", "ff_ci_low", "ff_ci_high", "difference",
                 "difference_ci_low", "difference_ci_high", "difference_runs", "memory_gain", "memory_gain_ci_low",
                 "memory_gain_ci_high", "memory_gain_runs"]


def write_memory(out_dir, rows, game="v2"):
    """memory_seeds.md and .csv: per variant, the GRU runs against their feed-forward twins."""
    write_rows(os.path.join(out_dir, "memory_seeds.csv"), rows, MEMORY_FIELDS)

    def ci(r, key):
        if r.get(key, "") == "":
            return "-"
        lo, hi = r.get(key + "_ci_low", ""), r.get(key + "_ci_high", "")
        return "%.1f" % r[key] + (" [%.1f, %.1f]" % (lo, hi) if lo != "" else "")
    md = ["# The hider with memory (GRU) against its feed-forward twin", "",
          "Each GRU run `%s` beside the feed-forward run of the same variant and training seed, "
          "both evaluated greedy on the same evaluation seeds (0-99). Living steps: the pooled mean with a 95 % two-level "
          "bootstrap (runs, then episodes). Difference: GRU minus feed-forward on each evaluation seed, pooled over "
          "the pairs of runs, with the same two-level bootstrap (pairs, then evaluation seeds). Memory: the GRU's "
          "living steps on the per-run analysis' 100 rollouts (seeds 10000-10099) minus those of its memoryless ablation (its state zeroed at "
          "every step) on the same rollouts, mean over runs. The claim it decides is in [claims.md](claims.md)."
          .replace("%s", run_name("<variant>", 0, game, "gru").replace("seed0", "seed<S>"), 1), "",
          "| variant | GRU runs | GRU living steps | feed-forward, same seeds | GRU minus feed-forward | "
          "memory minus memoryless |", "| --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        md.append("| %s | %d | %s | %s | %s | %s |" % (r["variant"], r["runs"], ci(r, "gru"), ci(r, "ff"),
                                                      ci(r, "difference"), ci(r, "memory_gain")))
    if not rows:
        md.append("| (no GRU run of the sweep yet) | 0 | - | - | - | - |")
    with open(os.path.join(out_dir, "memory_seeds.md"), "w") as f:
        f.write("\n".join(md) + "\n")


def mark_provisional(r):
    """A claim decided while a variant it involves has fewer than SOUND_RUNS runs is marked
    provisional: a bootstrap over two runs can only return their range, whose coverage is well
    under 95 %; the verdict then says that both runs agree."""
    counts = [int(n) for n in re.findall(r"[a-z_]+ (\d+)(?=,|$)", r["runs"])]
    if r["result"] in ("supported", "contradicted") and counts and min(counts) < SOUND_RUNS:
        r["note"] = "; ".join(x for x in ("provisional: with %d runs of a variant its interval is their range"
                                          % min(counts), r["note"]) if x)


def write(out_dir, rows, header, game="v2"):
    os.makedirs(out_dir, exist_ok=True)
    fields = ["claim", "paper", "result", "effect", "ci_low", "ci_high", "practical", "runs", "measure", "note",
              "departure"]
    write_rows(os.path.join(out_dir, "claims.csv"), rows, fields)
    md = ["# The paper's claims, decided on game %s" % game, "", header, "",
          "| claim | result | effect [95 % CI] | practical size | runs | measure | what could cause a miss |",
          "| --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        eff = effect_text(r)
        md.append("| %s | **%s**%s | %s | %s | %s | %s | %s |" % (r["claim"], r["result"],
                                                                 (" (" + r["note"] + ")") if r["note"] else "", eff,
                                                                 r["practical"], r["runs"], r["measure"],
                                                                 r["departure"]))
    if not os.path.exists(os.path.join(out_dir, "state_frequencies_seeds.png")):  # no analysed run of the game yet
        md += ["", "Beside this table (`make reproduce`): Table 2 across seeds in [table2_seeds/](table2_seeds/table2.md) "
               "and the GRU runs against their feed-forward twins in [memory_seeds.md](memory_seeds.md); Table 3, the "
               "behaviour table and Figures 4-7 across seeds come with the game's first analysed run.", ""]
    else:
        md += ["", "Beside this table (`make reproduce`): Table 2 across seeds in [table2_seeds/](table2_seeds/table2.md), "
               "[Table 3 across seeds](table3_seeds.md), [behaviour across seeds](behaviour_seeds.md), "
               "and Figures 4-7 and the t-SNE across seeds: [states](state_frequencies_seeds.png), "
               "[transitions](transitions_seeds.png), [distance](distance_seeds.png), "
               "[survival against representation](survival_representation.png), [t-SNE](tsne_seeds.png) "
               "(each with its numbers in the .csv of the same name), and the GRU runs against their feed-forward "
               "twins in [memory_seeds.md](memory_seeds.md); the oscillation threshold's effect in "
               "[oscillation_thresholds.md](oscillation_thresholds.md).", ""]
    with open(os.path.join(out_dir, "claims.md"), "w") as f:
        f.write("\n".join(md))




def build(c):
    """Every claim's row, the memory claim last, and memory_seeds' rows."""
    living = {v: c.R.episodes(v) for v in c.variants if c.R.episodes(v)}
    rows = [ordering_claim(c, living), beats_random_claim(c, living)] + features_claims(c)
    rows += [perception_claim(c), concave_claim(c)] + behaviour_claims(c) + [oscillation_claim(c)]
    memory_row, memory_table = memory_claim(c)
    rows.append(memory_row)
    for r in rows:
        mark_provisional(r)
    return rows, memory_table


def header(found, reps):
    """claims.md's paragraph above the table: what was decided on, and how."""
    n = sum(len(x) for x in found.values())
    return ("Decided on %d run(s) of the sweep (%s). Intervals: 95 %% bootstrap over each variant's training seeds "
            "(%d resamples); a claim needs at least %d runs of every variant it involves to be decided. "
            "The interval decides the size as it decides the direction. Supported: the interval lies on the "
            "paper's side of zero, wholly at or beyond the measure's practical size (its column); contradicted: "
            "the same on the other side; negligible: the interval excludes zero and lies wholly under the "
            "practical size; inconclusive: otherwise (an interval across zero, or one that excludes zero but "
            "crosses the practical size: the direction is shown, the size is not). Only each "
            "seed's first training counts (a retrain, <run>_retrain, never does). With two runs of a variant the "
            "bootstrap over its runs can only return "
            "the two runs' range, whose coverage is well under 95 %%: a claim decided on two runs of a variant is "
            "marked provisional (both runs agree), until its third run arrives." % (
                n, ", ".join("%s %d" % (v, len(x)) for v, x in found.items()) or "none", reps, MIN_RUNS))


def decide_game(root, cfg, game, steps, extra, seed, reps, budget=None):
    """Every claim of one game decided on its sweep runs, with the budget check's row last where
    `budget` (the longer budget's steps) is given; returns (rows, memory table rows, Context)."""
    found = sweep_runs(root, steps, extra, warn=False, game=game)  # --extra may name runs of either network
    gru_found = sweep_runs(root, steps, extra, "gru", warn=False, game=game)
    c = Context(root, found, cfg, seed, reps, game, gru_found)
    rows, memory_table = build(c)
    if budget:
        rows.append(budget_check(c, rows, budget))
        mark_provisional(rows[-1])
    return rows, memory_table, c


def write_game(out_dir, rows, memory_table, c):
    """A game's claims table, memory study and oscillation thresholds into `out_dir`."""
    write(out_dir, rows, header(c.R.found, c.reps), c.game)
    write_memory(out_dir, memory_table, c.game)
    oscillation_thresholds(c, out_dir)
    for r in rows:
        print("claims: %s %-67s %s" % (c.game, r["claim"], r["result"]))


BUDGET = ("Training longer: basic at %s steps against 2M", "section 4: the paper trains each hider for 8M steps")


def budget_check(c, rows, big):
    """basic trained for `big` steps (its sweep runs <basic>_<game>_<budget>_seed<S>) against basic at
    2M: the difference of greedy living steps with its two-level bootstrap interval, and which
    verdicts move when basic's 8M runs stand in for its 2M runs. Supported: the longer budget lives
    longer by the practical size."""
    label = "%dm" % (big // 1000000) if big % 1000000 == 0 else "%dk" % (big // 1000)
    found_big = sweep_runs(c.root, big, set(), warn=False, game=c.game, budget=label)
    name, paper = BUDGET[0] % label.upper(), BUDGET[1]
    long_runs, short_runs = Runs(c.root, found_big, c.game).episodes("basic"), c.R.episodes("basic")
    per = {"basic %s" % label: long_runs, "basic 2M": short_runs}
    if not long_runs or not short_runs:
        return claim(name, paper, "living steps, basic at %s minus basic at 2M" % label, runs=runs_text(per),
                     note="needs basic's %s runs (config/sweep.yaml's phase of basic at %s steps) and its 2M runs"
                     % (label, label.upper()),
                     practical=PRACTICAL["living"][1])
    d, ci = st.mean_difference(long_runs, short_runs, c.rng("budget", label), c.reps)
    res, size = decide(ci, min(len(long_runs), len(short_runs)), "living")
    # The same claims with basic's longer runs in its 2M runs' place (the GRU runs keep their 2M twins).
    swapped = dict(c.R.found, basic=found_big.get("basic", []))
    again = build(Context(c.root, swapped, c.cfg, c.seed, c.reps, c.game, c.gru_found, twins=c.R.found))[0]
    moved = [(a["claim"], a["result"], b["result"]) for a, b in zip(rows, again) if a["result"] != b["result"]]
    row = claim(name, paper, "living steps, basic at %s minus basic at 2M (two-level bootstrap)" % label, d, ci,
                runs_text(per), res, "", c.causes("steps"), size)
    row["moved"] = "verdicts that move with basic's %s runs in place of its 2M runs: %s" % (
        label, "; ".join("%s: %s -> %s" % m for m in moved) or "none")
    row["measure"] += "; " + row["moved"]
    return row


def _cell(r):
    """A claim's verdict and effect on one game, for the table on both games."""
    if r is None:
        return "-", "-"
    note = " (%s)" % r["note"] if r["note"] else ""
    within = "; ".join(x for x in (r.get("focus", ""), r["runs"]) if x)
    return "**%s**%s" % (r["result"], note), effect_text(r) + (" (%s)" % within if within else "")


def write_both(out_dir, by_game, reps):
    """claims.md on both games: one row per claim, each game's verdict and effect side by side, and
    what changed between the games that could explain a difference."""
    games = list(by_game)
    names = []
    for rows in by_game.values():
        names += [r["claim"] for r in rows if r["claim"] not in names]
    md = ["# The paper's claims on both games", "",
          "Each claim decided on each game's sweep runs, as in each game's own table (%s), which gives every "
          "measure, practical size and possible cause. Intervals: 95 %% bootstrap over each variant's training "
          "seeds (%d resamples): over as many runs as the cell's count says (one to five a variant, as the "
          "sweep trains seeds 3-4). Game v3 reads the paper's motion as its engine would run it: the last column "
          "names what changed from v2 that bears on a claim; the map's cross, longer on v3, bears on every one." % (
              ", ".join("[%s](%s/claims.md)" % (g, g) for g in games), reps), "",
          "| claim | paper | " + " | ".join("%s: result | %s: effect [95 %% CI] (runs)" % (g, g) for g in games) +
          " | what changed between the games that could explain a difference |",
          "|" + " --- |" * (3 + 2 * len(games))]
    for name in names:
        cells = [next((r for r in by_game[g] if r["claim"] == name), None) for g in games]
        first = next(r for r in cells if r is not None)
        changed = first.get("moved") or "; ".join(CHANGED[k] for k in first.get("causes", ()) if k in CHANGED) or "-"
        md.append("| %s | %s | %s | %s |" % (name, first["paper"], " | ".join(" | ".join(_cell(r)) for r in cells),
                                            changed))
    with open(os.path.join(out_dir, "claims.md"), "w") as f:
        f.write("\n".join(md + [""]))


def main(argv=None):
    """claims.py: with --game, one game's claims table, memory_seeds and oscillation_thresholds into
    --out; with --games (default: config/sweep.yaml's), each game's into OUT/<game>/ and the table on
    both games into OUT/claims.md (default OUT: ROOT/docs/report, and with --game ROOT/docs/report/<game>). The
    budget check is the row of the game config/sweep.yaml trains a longer budget on."""
    args = parse_selection("The paper's claims decided on the sweep's runs, each with its effect size and 95 % "
                           "interval, on one game or side by side on several.", argv,
                           lambda p: p.add_argument("--games", nargs="+", help="decide on these games side by side "
                                                    "(default: the games config/sweep.yaml trains)"), game=None)
    root, extra = args.root, set(args.extra)
    cfg = Config(root)
    games = outputs(args, args.games or cfg.sweep_games())
    if not games:
        raise SystemExit("claims: no game to decide on (config/sweep.yaml has no phase; name one with --games)")
    by_game = {}
    for game, out in games:
        # The budget check is on the game config/sweep.yaml trains a longer budget on (v3's 8M).
        rows, memory_table, c = decide_game(root, cfg, game, args.steps, extra, args.seed, args.reps,
                                            cfg.longer_budget(game) if not args.game else None)
        write_game(out, rows, memory_table, c)
        by_game[game] = rows
    if not args.game:
        write_both(args.out or os.path.join(root, "docs", "report"), by_game, args.reps)
    return 0
