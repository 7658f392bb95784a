"""Exactness: the same seeds and hider actions give the same episodes from Python as from the C++
in-process game (play_episodes: every step's poses, labels, actions and outcome) and as the ROS graph
in lockstep (world and seeker nodes on their own master; this test answers as the hider): every
decision's image bytes, reward, done flag, outcome, labels, poses, seed, step and episode counter.

Exactness under same-step autoreset means: step t of the environment is decision t of the game. The
step that ends an episode returns the ended episode's reward and outcome beside the next episode's
first image and state, exactly what the world node's ObservationBatch carries for that decision."""

import csv
import os
import socket
import subprocess
import tempfile
import time

import numpy as np
import pytest

import hideseek


def _catkin_find(package, name):
    out = subprocess.run(["catkin_find", package, name, "--first-only"], capture_output=True, text=True)
    path = out.stdout.strip()
    if not path:
        pytest.fail("%s/%s not found by catkin_find: build the workspace and source its setup.bash" % (package, name))
    return path


def _play_with_module(variant, num_envs, seed, policy):
    """The first episode of every arena, row by row as play_episodes writes them."""
    env = hideseek.make_vec(variant, num_envs=num_envs, seed=seed)
    _, infos = env.reset(seed=seed)
    rows = {i: [] for i in range(num_envs)}
    playing = np.ones(num_envs, dtype=bool)
    while playing.any():
        actions = env.scripted_actions(policy)
        before = infos
        _, _, term, trunc, infos = env.step(actions)
        for i in np.flatnonzero(playing):
            rows[i].append((before["seed"][i], before["step"][i], *before["hider_pose"][i], *before["seeker_pose"][i],
                            int(before["S"][i]), int(before["H"][i]), int(before["O"][i]), int(actions[i]),
                            "captured" if term[i] else "survived" if trunc[i] else ""))
            if term[i] or trunc[i]:
                playing[i] = False
    return [r for i in range(num_envs) for r in rows[i]]


@pytest.mark.parametrize("variant,policy,play_policy", [("stochasticmaps", "random", "random"),
                                                        ("stochasticseeker", "flee", "scripted/flee")])
def test_same_episodes_as_play_episodes(variant, policy, play_policy, tmp_path):
    play = _catkin_find("hideseek_play", "play_episodes")
    out = tmp_path / "episodes.csv"
    subprocess.run([play, variant, play_policy, "30", "3", str(out)], check=True, capture_output=True)
    theirs = sorted(csv.DictReader(open(out)), key=lambda r: (int(r["seed"]), int(r["step"])))
    ours = sorted(_play_with_module(variant, 3, 30, policy), key=lambda r: (r[0], r[1]))
    assert len(ours) == len(theirs) > 3
    for a, b in zip(ours, theirs):
        assert (a[0], a[1]) == (int(b["seed"]), int(b["step"]))
        where = "seed %s step %s" % (b["seed"], b["step"])
        # play_episodes prints six significant digits
        expected = [float(b[k]) for k in ("hider_x", "hider_y", "hider_yaw", "seeker_x", "seeker_y", "seeker_yaw")]
        assert np.allclose(a[2:8], expected, rtol=1e-5, atol=1e-5), where
        assert a[8:12] == (int(b["S"]), int(b["H"]), int(b["O"]), int(b["hider_action"])), where
        assert a[12] == b["outcome"], where


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _record_graph(variant, num_envs, seed, actions, port):
    """Plays `actions` (decisions x arenas) as the hider against the real world and seeker nodes in
    lockstep; returns every decision's ObservationBatch, the first one before any action."""
    import rospy
    from hideseek_msgs.msg import ActionBatch, ObservationBatch

    batches = []
    pub = rospy.Publisher("/hider/actions", ActionBatch, queue_size=10)

    def answer(msg):
        key = (tuple(msg.episode), tuple(msg.step))
        if batches and key == batches[-1][0]:
            t = len(batches) - 1  # the world re-sent an unanswered batch: answer it again
        else:
            if len(batches) >= len(actions):
                return
            batches.append((key, msg))
            t = len(batches) - 1
        if t < len(actions):
            pub.publish(ActionBatch(actions=bytes(actions[t].astype(np.uint8)), step=list(msg.step)))

    rospy.Subscriber("/hider/observations", ObservationBatch, answer, queue_size=10)
    deadline = time.time() + 180
    while len(batches) < len(actions) and time.time() < deadline:
        time.sleep(0.1)
    return [m for _, m in batches]


def test_same_decisions_as_the_ros_graph():
    num_envs, seed, decisions, variant = 3, 20, 160, "stochasticmaps"
    actions = np.random.default_rng(5).integers(0, 5, (decisions, num_envs))
    port = _free_port()
    env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % port)
    log = tempfile.NamedTemporaryFile(prefix="hideseek_exactness_", suffix=".log", delete=False)
    launch = subprocess.Popen(
        ["roslaunch", "-p", str(port), "hideseek_world", "game.launch.xml", "variant:=" + variant, "mode:=lockstep",
         "start_hider:=false", "num_arenas:=%d" % num_envs, "seed:=%d" % seed, "world_output:=log",
         "resend_period:=0.5"], env=env, stdout=log, stderr=subprocess.STDOUT)
    saved_master = os.environ.get("ROS_MASTER_URI")
    try:
        os.environ["ROS_MASTER_URI"] = env["ROS_MASTER_URI"]
        import rospy
        for _ in range(150):  # the master is up
            try:
                rospy.get_master().getSystemState()
                break
            except Exception:
                time.sleep(0.2)
        rospy.init_node("exactness_hider", anonymous=True, disable_signals=True)
        batches = _record_graph(variant, num_envs, seed, actions, port)
    finally:
        if saved_master is None:
            os.environ.pop("ROS_MASTER_URI", None)
        else:
            os.environ["ROS_MASTER_URI"] = saved_master
        subprocess.run(["pkill", "-INT", "-P", str(launch.pid)])
        launch.terminate()
        launch.wait(timeout=30)
    assert len(batches) == decisions, "the graph answered %d of %d decisions (log: %s)" % (
        len(batches), decisions, log.name)

    vec = hideseek.make_vec(variant, num_envs=num_envs, seed=seed)
    obs, infos = vec.reset(seed=seed)
    rewards = np.zeros(num_envs)
    done = np.zeros(num_envs, dtype=bool)
    outcome = np.zeros(num_envs, dtype=np.uint8)
    episodes_ended = 0
    for t, msg in enumerate(batches):
        if t > 0:
            obs, rewards, term, trunc, infos = vec.step(actions[t - 1])
            done = term | trunc
            outcome = np.where(term, 1, np.where(trunc, 2, 0))
            episodes_ended += done.sum()
        where = "decision %d" % t
        graph_images = np.frombuffer(msg.images, dtype=np.uint8).reshape(num_envs, msg.height, msg.width, 3)
        assert np.array_equal(obs, graph_images), where
        assert np.array_equal(np.float32(rewards), np.asarray(msg.rewards, dtype=np.float32)), where
        assert list(done) == [bool(x) for x in msg.done], where
        assert list(outcome) == list(msg.outcome), where
        assert list(infos["step"]) == list(msg.step) and list(infos["seed"]) == list(msg.seed), where
        assert list(infos["episode_index"]) == list(msg.episode), where
        assert list(infos["S"]) == [bool(x) for x in msg.hider_sees_seeker], where
        assert list(infos["H"]) == [bool(x) for x in msg.seeker_sees_hider], where
        assert list(infos["O"]) == [bool(x) for x in msg.obstacle_in_view], where
        assert np.array_equal(infos["hider_pose"], [[p.x, p.y, p.theta] for p in msg.hider_pose]), where
        assert np.array_equal(infos["seeker_pose"], [[p.x, p.y, p.theta] for p in msg.seeker_pose]), where
    assert episodes_ended >= 3  # the comparison crossed episode ends (same-step autoreset)
