"""The lists the analysis works through, read from a checkout's config/, never written here:

- the variants: config/variants/*.yaml (through the registry), in Table 2's order;
- the paper's figures per variant, its orderings, its faster hiders and the two readings of its
  stochastic seeker: config/paper_reference.yaml;
- the variants whose GRU hiders the sweep trains: config/sweep.yaml's phases of network gru.
"""
import os

import yaml

from . import registry


def _load(root, name):
    path = os.path.join(root, "config", name)
    with open(path) as f:
        data = yaml.safe_load(f) or {}
    if not isinstance(data, dict):
        raise registry.RegistryError("%s: must be a mapping" % path)
    return data


class Config:
    """config/ of the checkout at `root`, read once."""

    def __init__(self, root):
        self.root = root
        self.reference = _load(root, "paper_reference.yaml")
        self.paper = self.reference.get("variants") or {}

    def _required(self, key):
        if key not in self.reference:
            raise registry.RegistryError("%s: the key %r is missing" % (
                os.path.join(self.root, "config", "paper_reference.yaml"), key))
        return self.reference[key]

    @property
    def paper_variants(self):
        """The paper's variants, in its Table 2's order."""
        return list(self.paper)

    def table_order(self):
        """Every variant (config/variants), the paper's first in its order, then the others by name."""
        return registry.paper_order(os.path.join(self.root, "config", "variants"),
                                    os.path.join(self.root, "config", "paper_reference.yaml"))

    def order_of(self, variants):
        """`variants` in the paper's order, then the others by name."""
        return [v for v in self.paper if v in variants] + sorted(v for v in variants if v not in self.paper)

    def orderings(self, present):
        """The orderings the paper reports among the variants `present`: (better, worse) pairs, the
        listed pairs first, then every variant of the paper above the one it ranks last."""
        spec = self._required("orderings")
        pairs = [tuple(p) for p in spec.get("pairs") or []]
        last = spec.get("every_variant_above")
        if last:
            pairs += [(v, last) for v in present if v != last and v in self.paper]
        return pairs

    def readings(self):
        """Two readings of one of the paper's variants: (its variant, what its seeker does, the other
        reading's variant, what that one's seeker does); the paper's figure is the first's."""
        return [(r["variant"], r["says"], r["other"], r["other_says"]) for r in self._required("readings")]

    @property
    def faster_hiders(self):
        """The variants the paper calls its faster hiders (Figure 6)."""
        return tuple(self._required("faster_hiders"))

    def sweep_games(self):
        """The games config/sweep.yaml's phases train, in the phases' order (v2, v3)."""
        sweep = _load(self.root, "sweep.yaml")
        default_game = sweep.get("game") or registry.default_game(os.path.join(self.root, "config", "games.yaml"))
        games = []
        for phase in sweep.get("phases") or []:
            game = str(phase.get("game", default_game))
            if game not in games:
                games.append(game)
        return games

    def longer_budget(self, game):
        """The longest budget config/sweep.yaml trains hiders for on `game` where it exceeds the
        sweep's own (the paper's 8M on v3), or None (a seeker's or a self-play's steps are not a
        hider's budget)."""
        sweep = _load(self.root, "sweep.yaml")
        default_game = sweep.get("game") or registry.default_game(os.path.join(self.root, "config", "games.yaml"))
        base = int(sweep.get("steps", 2000000))
        budgets = [int(p.get("steps", base)) for p in sweep.get("phases") or []
                   if str(p.get("game", default_game)) == game and p.get("role", "hider") == "hider"]
        return max(budgets) if budgets and max(budgets) > base else None

    def gru_variants(self, game="v2"):
        """The variants config/sweep.yaml trains GRU hiders of on `game`, in the phases' order."""
        sweep = _load(self.root, "sweep.yaml")
        found = []
        for phase in sweep.get("phases") or []:
            network = phase.get("network", sweep.get("network", "ff"))
            default_game = sweep.get("game") or registry.default_game(os.path.join(self.root, "config", "games.yaml"))
            if network != "gru" or str(phase.get("game", default_game)) != game:
                continue
            listed = phase.get("variants", sweep.get("variants", "all"))
            for v in (self.table_order() if listed == "all" else listed):
                if v not in found:
                    found.append(v)
        return tuple(found)
