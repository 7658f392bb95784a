"""The game as Python environments with Gymnasium's interface, over the C++ game loop (hideseek._core).

make_vec(variant, num_envs, seed) gives a batched environment with Gymnasium's vector API; make(variant)
a single environment with Gymnasium's Env API. Only numpy is needed: where gymnasium can be imported, the
classes subclass gymnasium.vector.VectorEnv and gymnasium.Env and use gymnasium.spaces.

Autoreset: the C++ game starts an arena's next episode within the step that ends the previous one, so
the vector environment resets in the same step (AutoresetMode.SAME_STEP): where terminations[i] or
truncations[i] is set, rewards[i] closes the episode that ended, and obs[i] and everything in infos
already belong to the first state of the next episode. infos["final_obs"] (masked by
infos["_final_obs"]) holds the terminal state's image, rendered for this (the game itself never shows
it), and infos["final_info"] (masked by infos["_final_info"]) the ended episode's length, return,
outcome and terminal state (poses and labels). A capture is a termination; surviving max_steps is a
truncation (a time limit the image does not show). The single environment follows Gymnasium's Env:
a step that ends an episode returns its terminal image, and reset() starts the next.

Two players, one side at a time: role="hider" (the default) gives the hider's side, the seeker played
by the variant's scripted seeker (opponent None or "scripted"), the random seeker ("random") or a
callable; role="seeker" gives the seeker's side, from its own camera alone, with its rewards (the game
file's seeker_rewards), the hider played by a scripted hider (opponent None or "random", "backpedal",
"flee", "hide", "lap") or a callable. A callable opponent gets its own side's images (uint8 [num_envs,
H, W, 3]) and the infos, and returns one action per environment: a trained policy, say. Wherever the
seeker is not the scripted one, it decides once a step on its camera, as the seeker node's policy and
train modes play (its actions: 5, or 7 in game v3). infos["final_info"]["return"] is the return of
the side the environment plays.
"""

import os

import numpy as np

from . import _core

try:  # gymnasium is optional: Debian 12 does not package it
    import gymnasium
    from gymnasium import spaces as _spaces
    from gymnasium.vector import AutoresetMode

    _EnvBase = gymnasium.Env
    _VectorBase = gymnasium.vector.VectorEnv
    HAVE_GYMNASIUM = True
except ImportError:  # pragma: no cover - exercised where gymnasium is absent
    from . import spaces as _spaces
    from .spaces import AutoresetMode

    _EnvBase = object
    _VectorBase = object
    HAVE_GYMNASIUM = False

# The hider's actions, ActionBatch's values.
ACTIONS = ("stay", "forward", "backward", "turn_left", "turn_right")
# Scripted hiders for baselines and opponents (scripted_actions): the paper's random hider and evaders
# that read the true state.
SCRIPTED_HIDERS = ("random", "backpedal", "flee", "hide", "lap")
OUTCOME_CAPTURED, OUTCOME_SURVIVED = 1, 2
ROLES = ("hider", "seeker")
SEEKER_OPPONENTS = ("scripted", "random")  # role hider: the seeker, besides a callable


def _config_dir(config_dir):
    if config_dir is not None:
        return str(config_dir)
    try:
        return _core.config_directory()
    except RuntimeError as e:
        raise RuntimeError(
            "%s (or pass config_dir=, the folder holding game.yaml and variants/)" % e
        ) from None


def _seed(value, what="seed"):
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise ValueError("%s must be an integer in [0, 2^32), got %r" % (what, value))
    if not 0 <= int(value) < 2 ** 32:
        raise ValueError("%s must be in [0, 2^32), got %d" % (what, value))
    return int(value)


def _seed_list(seed, num_envs):
    """reset's seed argument as the C++ side takes it: [] (the next seeds), [seed] or one per env."""
    if seed is None:
        return []
    if isinstance(seed, (int, np.integer)) and not isinstance(seed, (bool, np.bool_)):
        return [_seed(seed)]
    try:
        seeds = [_seed(s, "every seed") for s in seed]
    except TypeError:
        raise ValueError("seed must be None, an integer or one integer per environment, got %r" % (seed,)) from None
    if len(seeds) != num_envs:
        raise ValueError("%d seeds for %d environments" % (len(seeds), num_envs))
    return seeds


def _actions(actions, num_envs, count=_core.num_actions, what="action"):
    a = np.asarray(actions)
    if a.shape != (num_envs,):
        raise ValueError("%ss must have shape (%d,), got %s" % (what, num_envs, a.shape))
    # integers only, as Discrete contains them: floats, strings, objects and booleans are refused
    if a.dtype.kind not in "iu":
        raise ValueError("%ss must be integers in [0, %d), got %s (dtype %s)" % (what, count, a, a.dtype))
    if np.any(a < 0) or np.any(a >= count):
        bad = int(np.flatnonzero((a < 0) | (a >= count))[0])
        where = " of environment %d" % bad if num_envs > 1 else ""
        raise ValueError("%s %s%s is not in [0, %d)" % (what, a[bad], where, count))
    return a.astype(np.uint8)


def _check_names(variant, game, config_dir, variant_config):
    if not isinstance(variant, str):
        raise ValueError("variant must be a variant's name (a string), got %r" % (variant,))
    if game is not None and not isinstance(game, str):
        raise ValueError("game must be None or a game's name such as 'v3', got %r" % (game,))
    for name, value in (("config_dir", config_dir), ("variant_config", variant_config)):
        if value is not None and not isinstance(value, (str, os.PathLike)):
            raise ValueError("%s must be None or a path, got %r" % (name, value))


def _check_opponent(role, opponent):
    if role not in ROLES:
        raise ValueError("role must be 'hider' or 'seeker', got %r" % (role,))
    if opponent is None or callable(opponent):
        return
    allowed = SEEKER_OPPONENTS if role == "hider" else SCRIPTED_HIDERS
    if opponent not in allowed:
        raise ValueError("opponent of the %s must be None, a callable or one of %s, got %r"
                         % (role, ", ".join(allowed), opponent))


def _with_masks(d, mask):
    """Gymnasium's vector info layout: every key k beside a boolean mask _k of the envs it holds for
    (each its own array, so that a wrapper changing one changes no other)."""
    out = {}
    for k, v in d.items():
        out[k] = v
        out["_" + k] = mask.copy()
    return out


class HideSeekVecEnv(_VectorBase):
    """num_envs arenas of a variant played together; arena i's first episode has seed seed + i, its
    later ones seed + i + k * num_envs (the world node's num_arenas and seed)."""

    # render_fps: one frame a decision step; set from the game's step (0.12 s: 8.33 frames a second).
    metadata = {"autoreset_mode": AutoresetMode.SAME_STEP, "render_modes": ["rgb_array"], "render_fps": None}

    def __init__(self, variant="basic", num_envs=16, seed=0, game=None, config_dir=None,
                 render_threads=2, render_mode=None, role="hider", opponent=None, variant_config=None):
        _check_names(variant, game, config_dir, variant_config)
        _check_opponent(role, opponent)
        if render_mode not in (None, "rgb_array"):
            raise ValueError("render_mode must be None or 'rgb_array', got %r" % (render_mode,))
        if isinstance(num_envs, bool) or not isinstance(num_envs, (int, np.integer)):
            raise ValueError("num_envs must be an integer in [1, 64], got %r" % (num_envs,))
        seed = _seed(seed)
        if seed + int(num_envs) - 1 >= 2 ** 32:
            raise ValueError("seed + num_envs - 1 must be below 2^32")
        config_dir = _config_dir(config_dir)
        game = game or _core.default_game(config_dir)  # None: config/games.yaml's default
        outside = role == "seeker" or opponent not in (None, "scripted")
        self._game = _core.VecGame(config_dir, game, variant, int(num_envs), seed, int(render_threads), outside,
                                   os.fspath(variant_config) if variant_config is not None else "")
        self._game.keep_terminal_views(role == "seeker")  # final_obs: the side played's camera
        self.variant, self.game, self.role = variant, game, role
        self.opponent = opponent if opponent is not None else ("scripted" if role == "hider" else "random")
        self.num_envs = self._game.num_envs
        self.render_mode = render_mode
        h, w = self._game.height, self._game.width
        count = self._game.seeker_actions if role == "seeker" else _core.num_actions
        self.single_observation_space = _spaces.Box(0, 255, (h, w, 3), np.uint8)
        self.single_action_space = _spaces.Discrete(count)
        self.observation_space = _spaces.Box(0, 255, (self.num_envs, h, w, 3), np.uint8)
        self.action_space = _spaces.MultiDiscrete(np.full(self.num_envs, count))
        self.metadata = dict(self.metadata, render_fps=1.0 / self._game.step_duration)
        self.closed = False
        self._everyone = np.ones(self.num_envs, dtype=bool)

    @property
    def _live(self):
        """The game, or a clear error once close() freed it."""
        if self._game is None:
            raise RuntimeError("%r is closed: make a new environment" % self)
        return self._game

    def reset(self, *, seed=None, options=None):
        """New episodes in every arena: seed (int) gives arena i seed + i, a list one seed per arena,
        None the next seed of each arena's sequence."""
        if options:
            raise ValueError("hideseek environments take no reset options, got %r" % (options,))
        seeds = _seed_list(seed, self.num_envs)
        self._live.reset(seeds)  # first: it refuses a bad seed, changing nothing
        if HAVE_GYMNASIUM and seed is not None:
            super().reset(seed=seeds[0])  # seeds the vector env's own np_random, as Gymnasium's do
        return self._observations(), self._infos()

    def step(self, actions):
        n, game = self.num_envs, self._live  # a closed environment says so before the actions are checked
        if self.role == "hider":
            hider = _actions(actions, n)
            seeker = self._opponent_actions() if game.seeker_outside else None
        else:
            seeker = _actions(actions, n, game.seeker_actions, "seeker action")
            hider = self._opponent_actions()
        game.step(hider, seeker)
        outcomes = game.outcomes()
        infos = self._infos()
        done = game.done()
        if done.any():
            final = game.finished()
            del final["_mask"]  # the same as done
            if self.role == "seeker":
                final["hider_return"], final["return"] = final["return"], final["seeker_return"]
            del final["seeker_return"]
            infos["final_info"] = _with_masks(final, done)
            infos["_final_info"] = done
            # Gymnasium's layout: an object array, the terminal image where an episode ended, else None
            terminal = game.terminal_observations()
            final_obs = np.full(n, None, dtype=object)
            for i in np.flatnonzero(done):
                final_obs[i] = terminal[i]
            infos["final_obs"] = final_obs
            infos["_final_obs"] = done.copy()
        rewards = game.seeker_rewards() if self.role == "seeker" else game.rewards()
        return (self._observations(), rewards.astype(np.float64), outcomes == OUTCOME_CAPTURED,
                outcomes == OUTCOME_SURVIVED, infos)

    def _observations(self):
        return self._live.seeker_observations() if self.role == "seeker" else self._live.observations()

    def _opponent_actions(self):
        """The other side's actions for the current state: a script's, or a callable's on its own images."""
        n, o = self.num_envs, self.opponent
        if self.role == "hider":
            if o == "random":
                return self._live.random_seeker_actions()
            return _actions(o(self._live.seeker_observations(), self._infos()), n, self._live.seeker_actions,
                            "opponent's action")
        if isinstance(o, str):
            return self._live.scripted_actions(o)
        return _actions(o(self._live.observations(), self._infos()), n, _core.num_actions, "opponent's action")

    def scripted_actions(self, name):
        """A scripted hider's actions for every arena's current state: random (the paper's random
        hider) or an evader reading the true state (backpedal, flee, hide, lap). The evaders keep a
        goal and a path within an episode: ask once per step, as the graph asks them."""
        return self._live.scripted_actions(name).astype(np.int64)

    def render(self):
        """The images of the side played, a tuple of num_envs uint8 [H, W, 3] frames (render_mode
        'rgb_array')."""
        return tuple(self._observations()) if self.render_mode == "rgb_array" else None

    def close(self, **kwargs):
        """Frees the game (its renderer and images); the environment cannot be used after."""
        self._game = None
        self.closed = True

    def _infos(self):
        return _with_masks(self._live.infos(), self._everyone)

    def __repr__(self):
        return "HideSeekVecEnv(%s, num_envs=%d, game=%s%s)" % (
            self.variant, self.num_envs, self.game, "" if self.role == "hider" else ", role=seeker")


class HideSeekEnv(_EnvBase):
    """One arena, with Gymnasium's Env API. A step that ends an episode returns its terminal image
    and state (info["final_info"]: its length, return and outcome); the game has already started the
    next episode, which reset() keeps instead of skipping a seed, so episodes have seeds seed,
    seed + 1, ... (a step without that reset plays on in it)."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": None}  # set from the game, as the vector env's

    def __init__(self, variant="basic", seed=0, game=None, config_dir=None, render_threads=2,
                 render_mode=None, role="hider", opponent=None, variant_config=None):
        self._vec = HideSeekVecEnv(variant, 1, seed, game, config_dir, render_threads, role=role, opponent=opponent,
                                   variant_config=variant_config)
        if render_mode not in (None, "rgb_array"):
            raise ValueError("render_mode must be None or 'rgb_array', got %r" % (render_mode,))
        self.render_mode = render_mode
        self.metadata = dict(self.metadata, render_fps=self._vec.metadata["render_fps"])
        self.observation_space = self._vec.single_observation_space
        self.action_space = self._vec.single_action_space
        self._fresh = True  # an episode has just started and taken no step
        self._terminal = None  # the image of the episode the last step ended, until reset

    # The vector environment of one arena, or a clear error naming this environment once closed.
    @property
    def _open_vec(self):
        if self._vec._game is None:
            raise RuntimeError("%r is closed: make a new environment" % self)
        return self._vec

    def reset(self, *, seed=None, options=None):
        if options:
            raise ValueError("hideseek environments take no reset options, got %r" % (options,))
        vec = self._open_vec
        if seed is not None:
            seed = _seed(seed)  # one integer (numpy's too); no list, as Gymnasium's Env takes none
        if seed is not None or not self._fresh:
            vec._live.reset(_seed_list(seed, 1))
        if HAVE_GYMNASIUM:
            super().reset(seed=seed)
        self._fresh, self._terminal = True, None
        return vec._observations()[0], self._info()

    def step(self, action):
        vec = self._open_vec
        a = np.asarray(action)
        if a.shape != ():
            raise ValueError("action must be one integer in [0, %d), got an array of shape %s"
                             % (self.action_space.n, a.shape))
        obs, rewards, terminations, truncations, infos = vec.step(a.reshape(1))
        ended = bool(terminations[0] or truncations[0])
        self._fresh = ended
        if ended:  # the terminal state, as Gymnasium's Env returns it; the next episode waits for reset()
            final = {k: v[0] for k, v in infos["final_info"].items() if not k.startswith("_")}
            info = {k: final[k] for k in ("S", "H", "O", "hider_pose", "seeker_pose", "seed")}
            info["step"] = np.int64(final["length"])
            info["final_info"] = final
            self._terminal = infos["final_obs"][0]
            return self._terminal, float(rewards[0]), bool(terminations[0]), bool(truncations[0]), info
        self._terminal = None
        return obs[0], float(rewards[0]), False, False, self._info()

    def scripted_action(self, name):
        return int(self._open_vec.scripted_actions(name)[0])

    def render(self):
        vec = self._open_vec
        if self.render_mode != "rgb_array":
            return None
        return self._terminal if self._terminal is not None else vec._observations()[0]

    def close(self):
        self._vec.close()

    def _info(self):
        # The arena's episode counter is left out: it counts resets, so that a reset with the same
        # seed gives the same info (check_env's determinism).
        return {k: v[0] for k, v in self._open_vec._live.infos().items() if k != "episode_index"}

    def __repr__(self):
        v = self._vec
        return "HideSeekEnv(%s, game=%s%s)" % (v.variant, v.game, "" if v.role == "hider" else ", role=seeker")


def make_vec(variant="basic", num_envs=16, seed=0, *, game=None, config_dir=None, variant_config=None,
             render_threads=2, render_mode=None, role="hider", opponent=None):
    """A batched environment of `variant` with num_envs arenas (1 to 64); arena i's first episode has
    seed seed + i, its later ones seed + i + k * num_envs.

    game: 'v3', 'v2' or 'v1' (None: config/games.yaml's default). config_dir: the folder holding the
    game files and variants/ (None: the hideseek_game package's config/). variant_config: a variant
    file of one's own, whose variant field must be `variant` (None: config_dir/variants/VARIANT.yaml).
    render_threads: llvmpipe's rasteriser threads (the process's first environment sets them).
    render_mode: None or 'rgb_array'. role: 'hider' or 'seeker', the side played; opponent: the other
    side (see the module's docstring)."""
    return HideSeekVecEnv(variant, num_envs, seed, game=game, config_dir=config_dir, render_threads=render_threads,
                          render_mode=render_mode, role=role, opponent=opponent, variant_config=variant_config)


def make(variant="basic", seed=0, *, game=None, config_dir=None, variant_config=None, render_threads=2,
         render_mode=None, role="hider", opponent=None):
    """One arena of `variant` with Gymnasium's Env API (what gymnasium's check_env takes); its
    episodes have seeds seed, seed + 1, ... The keyword arguments are make_vec's."""
    return HideSeekEnv(variant, seed, game=game, config_dir=config_dir, render_threads=render_threads,
                       render_mode=render_mode, role=role, opponent=opponent, variant_config=variant_config)
