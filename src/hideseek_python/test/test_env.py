"""The hideseek module's Python interface: Gymnasium's vector and single-environment APIs, same-step
autoreset, seeding, refusals, the GIL released while stepping; with the vendored Gymnasium 1.4.0
(put on the path here, never copied) its VectorEnv, check_env and its vector wrappers."""

import os
import sys
import threading
import time

import numpy as np
import pytest

VENDOR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..", "shared", "vendor",
                      "gymnasium")
if os.path.isdir(os.path.join(VENDOR, "gymnasium")):
    sys.path.insert(0, VENDOR)

import hideseek  # noqa: E402

needs_gymnasium = pytest.mark.skipif(not hideseek.HAVE_GYMNASIUM,
                                     reason="gymnasium not importable: %s holds no gymnasium/" % VENDOR)


@pytest.fixture(scope="module")
def envs():
    e = hideseek.make_vec("basic", num_envs=4, seed=0)
    yield e
    e.close()


def test_spaces_shapes_and_metadata(envs):
    assert envs.num_envs == 4
    assert envs.single_observation_space.shape == (84, 84, 3)
    assert envs.single_observation_space.dtype == np.uint8
    assert envs.single_action_space.n == 5
    assert envs.observation_space.shape == (4, 84, 84, 3)
    assert envs.action_space.shape == (4,)
    assert envs.metadata["autoreset_mode"] == hideseek.AutoresetMode.SAME_STEP
    # one frame a decision step of 0.12 s (6 physics frames of 0.02 s): a video of them plays at game speed
    assert envs.metadata["render_fps"] == pytest.approx(1 / 0.12)
    assert hideseek.make("basic").metadata["render_fps"] == pytest.approx(1 / 0.12)
    assert hideseek.HideSeekVecEnv.metadata["render_fps"] is None  # each environment's own, from its game
    obs, infos = envs.reset(seed=0)
    assert obs.dtype == np.uint8 and obs.shape == (4, 84, 84, 3)
    assert envs.observation_space.contains(obs)
    assert obs.std() > 10  # a rendered arena, not a blank image
    assert list(infos["seed"]) == [0, 1, 2, 3] and list(infos["step"]) == [0, 0, 0, 0]
    for key in ("S", "H", "O", "hider_pose", "seeker_pose", "seed", "step", "episode_index"):
        assert infos["_" + key].all(), key
    assert infos["hider_pose"].shape == (4, 3) and infos["S"].dtype == bool


def test_step_returns_gymnasium_tuple_and_resets_in_the_same_step(envs):
    envs.reset(seed=100)
    ended = 0
    seeds_seen = set()
    for _ in range(400):
        before = envs._game.infos()
        obs, rewards, terminations, truncations, infos = envs.step(envs.action_space.sample())
        assert rewards.dtype == np.float64 and terminations.dtype == bool and truncations.dtype == bool
        assert envs.observation_space.contains(obs)
        done = terminations | truncations
        assert not (terminations & truncations).any()
        if done.any():
            assert (infos["_final_info"] == done).all()
            final = infos["final_info"]
            for i in np.flatnonzero(done):
                ended += 1
                # The next episode started in this very step: its first state, its next seed.
                assert infos["step"][i] == 0
                assert infos["seed"][i] == before["seed"][i] + 4
                assert infos["episode_index"][i] == before["episode_index"][i] + 1
                assert final["length"][i] == before["step"][i] + 1
                assert final["seed"][i] == before["seed"][i]
                assert final["outcome"][i] == (1 if terminations[i] else 2)
                seeds_seen.add(int(infos["seed"][i]))
            # The terminal state's image, rendered for this, where an episode ended (Gymnasium's layout).
            assert (infos["_final_obs"] == done).all() and infos["final_obs"].dtype == object
            for i in range(4):
                if done[i]:
                    assert infos["final_obs"][i].shape == (84, 84, 3) and infos["final_obs"][i].dtype == np.uint8
                    assert not np.array_equal(infos["final_obs"][i], obs[i])  # not the next episode's first
                else:
                    assert infos["final_obs"][i] is None
        not_done = ~done
        assert (infos["step"][not_done] == before["step"][not_done] + 1).all()
    assert ended >= 4  # the random actions' basic episodes are short


def test_reset_without_a_seed_after_construction_skips_no_seed():
    env = hideseek.make_vec("basic", num_envs=3, seed=6)
    _, infos = env.reset()
    assert list(infos["seed"]) == [6, 7, 8] and list(infos["episode_index"]) == [0, 0, 0]
    _, infos = env.reset()
    assert list(infos["seed"]) == [6, 7, 8]
    env.step([0, 0, 0])
    _, infos = env.reset()
    assert list(infos["seed"]) == [9, 10, 11]


def test_a_closed_environment_says_so():
    for env in (hideseek.make_vec("basic", num_envs=2), hideseek.make("basic")):
        env.reset(seed=0)
        env.close()
        for call in (lambda: env.reset(), lambda: env.step(np.zeros(2, int) if hasattr(env, "num_envs") else 0)):
            with pytest.raises(RuntimeError, match="is closed: make a new environment"):
                call()


def test_reset_seeds_one_per_env_and_next(envs):
    a, _ = envs.reset(seed=7)
    _, infos = envs.reset(seed=[3, 1, 4, 1])
    assert list(infos["seed"]) == [3, 1, 4, 1]
    b, infos = envs.reset(seed=7)
    assert list(infos["seed"]) == [7, 8, 9, 10]
    assert np.array_equal(a, b)
    envs.step([0, 0, 0, 0])
    _, infos = envs.reset()
    assert list(infos["seed"]) == [11, 12, 13, 14]


def test_bad_input_is_refused_with_a_clear_error(envs):
    envs.reset(seed=0)
    with pytest.raises(ValueError, match="shape"):
        envs.step([0, 1])
    with pytest.raises(ValueError, match="action 5 of environment 2"):
        envs.step([0, 1, 5, 0])
    with pytest.raises(ValueError, match="integers"):
        envs.step([0.5, 1, 1, 0])
    with pytest.raises(ValueError, match="integers"):
        envs.step(np.array([0.0, 1.0, 1.0, 0.0]))  # a whole float is no integer either, as in Discrete
    with pytest.raises(ValueError, match="integers"):
        envs.step(np.array([0, 1, np.inf, 0]))
    with pytest.raises(ValueError, match="one integer in \\[0, 5\\), got an array of shape \\(1,\\)"):
        hideseek.make("basic").step(np.array([2]))
    with pytest.raises(ValueError, match="integers"):
        envs.step(np.array(["a", "b", "c", "d"]))
    with pytest.raises(ValueError, match="integers"):
        envs.step([True, False, True, False])  # not in Discrete either
    with pytest.raises(ValueError, match=r"^action 7 is not in \[0, 5\)$"):
        hideseek.make("basic").step(7)  # one environment: no index to name
    with pytest.raises(ValueError, match="3 seeds for 4"):
        envs.reset(seed=[1, 2, 3])
    with pytest.raises(ValueError, match="seed"):
        envs.reset(seed=-2)
    with pytest.raises(ValueError, match="integer"):
        envs.reset(seed=1.5)
    with pytest.raises(ValueError, match="seed"):
        hideseek.make_vec("basic", num_envs=2, seed=-1)
    with pytest.raises(ValueError, match="below 2"):
        hideseek.make_vec("basic", num_envs=2, seed=2 ** 32 - 1)
    with pytest.raises(ValueError, match="no reset options"):
        envs.reset(options={"x": 1})
    _, infos = envs.reset(seed=0)
    assert list(infos["step"]) == [0, 0, 0, 0]
    with pytest.raises(ValueError, match="nosuch"):
        hideseek.make_vec("nosuch", num_envs=1)
    with pytest.raises(ValueError, match="num_envs"):
        hideseek.make_vec("basic", num_envs=0)
    with pytest.raises(ValueError, match="'v9' is not a game here"):
        hideseek.make_vec("basic", num_envs=1, game="v9")
    with pytest.raises(ValueError, match="game must be None or a game's name"):
        hideseek.make_vec("basic", num_envs=1, game=3)
    with pytest.raises(ValueError, match="variant must be a variant's name"):
        hideseek.make_vec(None, num_envs=1)
    single = hideseek.make("basic", seed=0)
    for bad in ([1], 1.0, True, "1"):  # the single environment's seed is one integer
        with pytest.raises(ValueError, match="seed"):
            single.reset(seed=bad)
    _, info = single.reset(seed=np.int64(3))  # numpy's integers are integers
    assert info["seed"] == 3


def test_bad_variant_file_names_file_and_field(tmp_path):
    config = tmp_path / "config"
    real = hideseek._core.config_directory()
    os.makedirs(config / "variants")
    for f in ("game.yaml", "game_v3.yaml", "games.yaml"):  # the default game's file, and the one it extends
        (config / f).write_text(open(os.path.join(real, f)).read())
    os.symlink(os.path.join(real, "maps"), config / "maps")
    (config / "variants" / "broken.yaml").write_text("variant: broken\nmap: deterministic.yaml\nepisode:\n  max_steps: -5\n")
    with pytest.raises(hideseek.ConfigError, match="broken.yaml.*max_steps"):
        hideseek.make_vec("broken", num_envs=1, config_dir=str(config))


def test_a_variant_file_of_ones_own_and_a_misnamed_one(tmp_path):
    real = hideseek._core.config_directory()
    mine = tmp_path / "mine.yaml"
    mine.write_text("variant: mine\nmap: deterministic.yaml\nepisode: {max_steps: 7}\n")  # the game's map folder
    env = hideseek.make_vec("mine", num_envs=2, seed=1000, variant_config=mine)
    assert env.variant == "mine"
    env.reset(seed=1000)
    lengths = []
    for _ in range(7):
        _, _, term, trunc, infos = env.step([0, 0])
        if "final_info" in infos:
            lengths += list(infos["final_info"]["length"][infos["_final_info"]])
    assert 7 in lengths  # the file's max_steps, not basic's
    with pytest.raises(hideseek.ConfigError, match="is 'mine', but the file was given as variant 'yours'"):
        hideseek.make_vec("yours", num_envs=1, variant_config=str(mine))
    # A config folder's own file is held to its name as well.
    config = tmp_path / "config"
    os.makedirs(config / "variants")
    for f in os.listdir(real):
        if f.endswith(".yaml"):
            (config / f).write_text(open(os.path.join(real, f)).read())
    os.symlink(os.path.join(real, "maps"), config / "maps")
    (config / "variants" / "renamed.yaml").write_text(open(os.path.join(real, "variants", "basic.yaml")).read())
    with pytest.raises(hideseek.ConfigError, match="renamed.yaml.*is 'basic', but the file was given as variant"):
        hideseek.make_vec("renamed", num_envs=1, config_dir=str(config))


@pytest.mark.parametrize("role,opponent", [("hider", None), ("hider", "random"), ("seeker", None)])
def test_final_obs_is_what_the_side_played_would_see(tmp_path, role, opponent):
    """A twin whose episodes last longer observes the terminal state one step later: final_obs is
    that image, byte for byte, from the camera of the side played (also where the seeker plays from
    outside on the hider's side), on the ended episode's layout (stochasticmaps)."""
    short = tmp_path / "short.yaml"
    short.write_text("variant: short\nmap: stochastic.yaml\nseeker: {policy: stochastic}\nepisode: {max_steps: 5}\n")
    going = hideseek.make_vec("stochasticmaps", num_envs=4, seed=1000, role=role, opponent=opponent)
    ended = hideseek.make_vec("short", num_envs=4, seed=1000, role=role, opponent=opponent, variant_config=short)
    rng = np.random.default_rng(0)
    for _ in range(5):
        a = rng.integers(0, going.single_action_space.n, 4)
        obs, *_ = going.step(a)
        nobs, _, _, _, infos = ended.step(a)
    lasted = infos["_final_info"] & (infos["final_info"]["length"] == 5)
    assert lasted.sum() >= 3
    for i in np.flatnonzero(lasted):
        assert np.array_equal(infos["final_obs"][i], obs[i]), i
        assert not np.array_equal(nobs[i], obs[i])
    going.close()
    ended.close()


def test_the_single_environment_returns_the_terminal_state_and_reset_starts_the_next():
    """Gymnasium's Env contract: the step that ends an episode returns that episode's terminal image
    and state; reset() then gives the next episode's first, which the vector environment already
    returned in that step; render() shows what was returned."""
    env = hideseek.make("basic", seed=1000, render_mode="rgb_array")
    vec = hideseek.make_vec("basic", num_envs=1, seed=1000)
    env.reset()
    vec.reset()
    for _ in range(2000):
        a = env.scripted_action("random")
        obs, reward, terminated, truncated, info = env.step(a)
        vobs, vrew, vterm, vtrunc, vinfos = vec.step([a])
        assert reward == vrew[0] and terminated == vterm[0] and truncated == vtrunc[0]
        if terminated or truncated:
            break
        assert np.array_equal(obs, vobs[0])
    assert terminated or truncated
    assert np.array_equal(obs, vinfos["final_obs"][0]) and not np.array_equal(obs, vobs[0])
    assert np.array_equal(env.render(), obs)
    assert info["seed"] == 1000 and info["step"] == info["final_info"]["length"]
    assert np.allclose(info["hider_pose"], vinfos["final_info"]["hider_pose"][0])
    first, info = env.reset()
    assert np.array_equal(first, vobs[0]) and info["seed"] == 1001 and info["step"] == 0
    assert np.array_equal(env.render(), first)
    assert "HideSeekEnv(basic" in repr(env)


def test_scripted_hiders_and_single_env_sequence():
    env = hideseek.make("basic", seed=10)
    obs, info = env.reset()
    assert obs.shape == (84, 84, 3) and info["seed"] == 10
    seeds = []
    for _ in range(3):  # the random hider: three episodes, seeds 10, 11, 12 (reset keeps the started one)
        while True:
            obs, reward, terminated, truncated, info = env.step(env.scripted_action("random"))
            if terminated or truncated:
                seeds.append(int(info["final_info"]["seed"]))
                break
        _, info = env.reset()
    assert seeds == [10, 11, 12] and info["seed"] == 13
    vec = hideseek.make_vec("basic", num_envs=2, seed=0)
    for name in hideseek.SCRIPTED_HIDERS:
        a = vec.scripted_actions(name)
        assert a.shape == (2,) and ((a >= 0) & (a < 5)).all(), name
    with pytest.raises(ValueError, match="names no scripted hider"):
        vec.scripted_actions("teleport")


def test_step_releases_the_gil():
    """While one thread is inside the C++ step of 64 arenas, another runs Python: ticks of the main
    thread fall inside the C++ calls themselves, which a held GIL would forbid."""
    env = hideseek.make_vec("stochasticmaps", num_envs=64, seed=0)
    env.reset(seed=0)
    actions = np.ones(64, dtype=np.uint8)
    calls = []

    def stepper():
        for _ in range(10):
            t0 = time.perf_counter()
            env._game.step(actions)
            calls.append((t0, time.perf_counter()))

    ticks = []
    t = threading.Thread(target=stepper)
    t.start()
    while t.is_alive():
        ticks.append(time.perf_counter())
    t.join()
    ticks = np.array(ticks)
    # Leave out each call's first and last 1 ms (the hand-over of the GIL around it); a call of 64
    # arenas takes about 10 ms on a fast 2-core machine, so calls of at least 4 ms are counted.
    inside = [int(((ticks > a + 0.001) & (ticks < b - 0.001)).sum()) for a, b in calls if b - a > 0.004]
    assert len(inside) >= 3, "the steps were too short to tell: %s" % calls
    assert sum(n > 100 for n in inside) >= len(inside) - 1, "main-thread ticks inside each C++ step: %s" % inside


def test_two_environments_step_in_two_threads_as_one_after_the_other():
    rng = np.random.default_rng(9)
    actions = rng.integers(0, 5, (60, 4))

    def play(variant, out):
        env = hideseek.make_vec(variant, num_envs=4, seed=3)
        env.reset(seed=3)
        frames = []
        for a in actions:
            obs, rewards, *_ = env.step(a)
            frames.append((obs.copy(), rewards.copy()))
        out.extend(frames)

    alone_a, alone_b, both_a, both_b = [], [], [], []
    play("basic", alone_a)
    play("stochasticmaps", alone_b)
    threads = [threading.Thread(target=play, args=("basic", both_a)),
               threading.Thread(target=play, args=("stochasticmaps", both_b))]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    for alone, both in ((alone_a, both_a), (alone_b, both_b)):
        assert len(alone) == len(both) == 60
        assert all(np.array_equal(x[0], y[0]) and np.array_equal(x[1], y[1]) for x, y in zip(alone, both))


def test_one_environment_shared_by_two_threads_takes_turns():
    env = hideseek.make_vec("basic", num_envs=2, seed=0)
    env.reset(seed=0)
    errors = []

    def hammer():
        try:
            for _ in range(100):
                env.step([1, 2])
                env._game.infos()
        except Exception as e:  # pragma: no cover - what the test looks for
            errors.append(e)

    threads = [threading.Thread(target=hammer) for _ in range(2)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert not errors
    assert env._game.decisions == 200


@needs_gymnasium
def test_gymnasium_check_env_passes_on_the_single_environment():
    from gymnasium.utils.env_checker import check_env
    import warnings

    env = hideseek.make("basic", seed=0)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env, skip_render_check=True)
    env_warnings = [str(w.message) for w in caught]
    assert not env_warnings, env_warnings
    assert isinstance(env, __import__("gymnasium").Env)


@needs_gymnasium
def test_gymnasiums_sync_vector_env_over_the_single_environment_plays_the_same_episodes():
    """Gymnasium's own vector env (next-step autoreset) over make(): its terminal observations are
    make_vec's final_obs, and the step after one is the next episode's first state (the next seed,
    nothing skipped), as make_vec returned it in the terminal step."""
    import gymnasium

    sync = gymnasium.vector.SyncVectorEnv([lambda: hideseek.make("basic", seed=1000)])
    vec = hideseek.make_vec("basic", num_envs=1, seed=1000)
    sync.reset()
    vec.reset()
    ends, pending = 0, None
    for _ in range(300):
        a = vec.scripted_actions("random")
        obs, rewards, term, trunc, infos = sync.step(a)
        if pending is not None:  # the autoreset step: the action is not played
            assert np.array_equal(obs[0], pending[0]) and infos["seed"][0] == pending[1] and rewards[0] == 0
            pending = None
            continue
        vobs, vrewards, vterm, vtrunc, vinfos = vec.step(a)
        assert rewards[0] == vrewards[0] and term[0] == vterm[0] and trunc[0] == vtrunc[0]
        if vterm[0] or vtrunc[0]:
            ends += 1
            assert np.array_equal(obs[0], vinfos["final_obs"][0])
            pending = (vobs[0], vinfos["seed"][0])
        else:
            assert np.array_equal(obs[0], vobs[0])
    assert ends >= 3
    sync.close()
    vec.close()


@needs_gymnasium
def test_is_a_gymnasium_vector_env_and_record_episode_statistics_counts_episodes():
    import gymnasium
    from gymnasium.wrappers.vector import RecordEpisodeStatistics

    envs = RecordEpisodeStatistics(hideseek.make_vec("basic", num_envs=4, seed=0))
    assert isinstance(envs.unwrapped, gymnasium.vector.VectorEnv)
    envs.reset(seed=0)
    checked = 0
    for _ in range(200):
        _, _, term, trunc, infos = envs.step(envs.action_space.sample())
        if "episode" in infos:
            done = infos["_episode"]
            assert (infos["episode"]["l"][done] == infos["final_info"]["length"][done]).all()
            assert np.allclose(infos["episode"]["r"][done], infos["final_info"]["return"][done])
            checked += done.sum()
    assert checked >= 4


# Gymnasium 1.4.0's vector wrappers under same-step autoreset: observation wrappers
# (VectorObservationWrapper) refuse it; the others take it. docs/python.md lists the same.
ACCEPTED = ["RecordEpisodeStatistics", "DictInfoToList", "NormalizeReward", "ClipReward", "TransformReward",
            "TransformAction"]
REFUSED = ["NormalizeObservation", "TransformObservation", "GrayscaleObservation", "ResizeObservation",
           "FlattenObservation", "DtypeObservation"]


def _wrap(name, envs):
    import gymnasium.wrappers.vector as w
    import gymnasium

    if name == "TransformReward":
        return w.TransformReward(envs, lambda r: 0.5 * r)
    if name == "TransformAction":
        return w.TransformAction(envs, lambda a: a, action_space=envs.action_space)
    if name == "TransformObservation":
        return w.TransformObservation(envs, lambda o: o, observation_space=envs.observation_space)
    if name == "ResizeObservation":
        return w.ResizeObservation(envs, (42, 42))
    if name == "ClipReward":
        return w.ClipReward(envs, -1.0, 1.0)
    if name == "DtypeObservation":
        return w.DtypeObservation(envs, np.float32)
    return getattr(w, name)(envs)


@needs_gymnasium
@pytest.mark.parametrize("name", ACCEPTED)
def test_vector_wrappers_that_accept_same_step_autoreset(name):
    """Each steps through several episode ends (where autoreset matters) without an error."""
    envs = _wrap(name, hideseek.make_vec("basic", num_envs=2, seed=0))
    envs.reset(seed=0)
    ends = 0
    for _ in range(400):
        _, rewards, term, trunc, infos = envs.step(envs.action_space.sample())
        assert np.all(np.isfinite(rewards))
        ends += int(np.sum(np.logical_or(term, trunc)))
        if ends >= 4:
            break
    assert ends >= 4


@needs_gymnasium
@pytest.mark.parametrize("name", REFUSED)
def test_vector_observation_wrappers_refuse_same_step_autoreset(name):
    with pytest.raises(ValueError, match="NEXT_STEP or DISABLED"):
        _wrap(name, hideseek.make_vec("basic", num_envs=2, seed=0))


def test_the_seekers_side_sees_its_own_camera_and_earns_its_own_rewards():
    """role="seeker": the seeker's images and rewards (+1 on capture, -0.001 a step), the hider
    played by a script; its actions are the scripted seeker's in the game (5 in game v2, 7 in game v3)."""
    seekers = hideseek.make_vec("basic", num_envs=2, seed=3, game="v2", role="seeker", opponent="random")
    hiders = hideseek.make_vec("basic", num_envs=2, seed=3, game="v2")

    def chase(infos):  # the test's seeker reads the true poses to turn towards the hider
        d = infos["hider_pose"][:, :2] - infos["seeker_pose"][:, :2]
        off = np.angle(np.exp(1j * (np.arctan2(d[:, 1], d[:, 0]) - infos["seeker_pose"][:, 2])))
        return np.where(np.abs(off) < 0.3, 1, np.where(off > 0, 3, 4))

    try:
        assert seekers.single_action_space.n == 5 and seekers.opponent == "random"
        obs, infos = seekers.reset(seed=3)
        hider_obs, _ = hiders.reset(seed=3)
        assert obs.shape == (2, 84, 84, 3) and obs.std() > 10
        assert not np.array_equal(obs, hider_obs)  # the seeker's camera, not the hider's
        assert list(infos["seed"]) == [3, 4]
        captured = 0
        for _ in range(600):
            obs, rewards, terminations, truncations, infos = seekers.step(chase(infos))
            for i in range(2):
                if terminations[i]:
                    captured += 1
                    assert rewards[i] == pytest.approx(1.0)
                    final = infos["final_info"]
                    assert final["return"][i] == pytest.approx(1.0 - 0.001 * (final["length"][i] - 1))
                    assert final["hider_return"][i] == pytest.approx(-1.0 + 0.001 * (final["length"][i] - 1))
                elif not truncations[i]:
                    assert rewards[i] == pytest.approx(-0.001)
        assert captured > 0
        with pytest.raises(ValueError, match="seeker action 5 of environment 1 is not in \\[0, 5\\)"):
            seekers.step([0, 5])
    finally:
        seekers.close()
        hiders.close()
    v3 = hideseek.make_vec("basic", num_envs=1, seed=0, game="v3", role="seeker")
    assert v3.single_action_space.n == 7 and v3.opponent == "random"
    v3.reset(seed=0)
    v3.step([6])  # forward while turning right: game v3's seeker has it
    v3.close()


def test_a_callable_plays_the_other_side_on_its_own_images():
    """A policy as the opponent: it gets its side's images and the infos; the random seeker and
    the hider's scripted seeker are the other choices, and a bad opponent is named."""
    seen = []

    def hider_policy(images, infos):
        seen.append(images.shape)
        return np.zeros(len(images), dtype=np.int64)  # stays

    env = hideseek.make_vec("basic", num_envs=2, seed=0, role="seeker", opponent=hider_policy)
    env.reset(seed=0)
    start = env._game.infos()["hider_pose"].copy()
    env.step([3, 4])
    assert seen == [(2, 84, 84, 3)]
    assert np.allclose(env._game.infos()["hider_pose"], start)  # the callable's "stay" was played
    env.close()
    # The random seeker: its draws depend on seed and step alone, so two games replay it alike,
    # and it is not the scripted seeker.
    poses = []
    for opponent in ("random", "random", None):
        hider = hideseek.make_vec("basic", num_envs=2, seed=0, opponent=opponent)
        hider.reset(seed=0)
        assert hider._game.seeker_outside == (opponent == "random")
        for _ in range(20):
            hider.step([0, 0])
        poses.append(hider._game.infos()["seeker_pose"].copy())
        hider.close()
    assert np.array_equal(poses[0], poses[1])
    assert not np.allclose(poses[0], poses[2])
    with pytest.raises(ValueError, match="opponent of the seeker must be None, a callable or one of random, "):
        hideseek.make_vec("basic", num_envs=1, role="seeker", opponent="scripted")
    with pytest.raises(ValueError, match="role must be 'hider' or 'seeker', got 'both'"):
        hideseek.make_vec("basic", num_envs=1, role="both")


@needs_gymnasium
def test_gymnasium_check_env_passes_on_the_seekers_side():
    from gymnasium.utils.env_checker import check_env

    env = hideseek.make("basic", seed=0, role="seeker")
    check_env(env, skip_render_check=True)
    env.close()
