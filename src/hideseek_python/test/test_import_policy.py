"""A policy from Python in the project's checkpoint format: examples/ppo_python.py's network, saved as
TorchScript and converted by import_policy, is played by the C++ hider (play_episodes, greedy, fp32)
exactly as Python plays it through the hideseek module; a file of another shape is refused, naming
the parameter."""

import csv
import importlib.util
import os
import subprocess

import numpy as np
import pytest

torch = pytest.importorskip("torch", reason="python3-torch (scripts/install_deps.sh) is not installed")

import hideseek  # noqa: E402

EXAMPLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "examples", "ppo_python.py")


def _example():
    spec = importlib.util.spec_from_file_location("ppo_python", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _tool(package, name):
    path = subprocess.run(["catkin_find", package, name, "--first-only"], capture_output=True, text=True).stdout.strip()
    if not path:
        pytest.fail("%s/%s not found: build the workspace and source its setup.bash" % (package, name))
    return path


def _actor_hidden(agent, images):
    F = torch.nn.functional
    x = images.permute(0, 3, 1, 2).float() / 255.0
    for conv in (agent.conv1, agent.conv2, agent.conv3):
        x = F.leaky_relu(conv(x), 0.01)
    x = F.leaky_relu(agent.features(x.flatten(1)), 0.01)
    return F.leaky_relu(agent.actor_hidden(x), 0.01)


def _decisive(agent):
    """A random network whose greedy action changes with the image, far from ties: the actor's
    output reads the actor's hidden units centred and scaled on frames of random play."""
    env = hideseek.make_vec("basic", num_envs=2, seed=500)
    frames = []
    obs, _ = env.reset(seed=500)
    for _ in range(40):
        frames.append(obs)
        obs = env.step(env.scripted_actions("random"))[0]
    with torch.no_grad():
        h = _actor_hidden(agent, torch.from_numpy(np.concatenate(frames)))
        w = torch.randn(5, 512) / (h.std(0) + 1e-6) * 5.0
        agent.actor_out.weight.copy_(w)
        agent.actor_out.bias.copy_(-(w * h.mean(0)).sum(1))


def test_imported_policy_plays_as_in_python(tmp_path):
    torch.manual_seed(3)
    agent = _example().Agent()
    _decisive(agent)
    script = tmp_path / "policy_torchscript.pt"
    torch.jit.script(agent).save(str(script))
    checkpoint = tmp_path / "policy.pt"
    subprocess.run([_tool("hideseek_hider", "import_policy"), str(script), str(checkpoint), "basic", "1024"],
                   check=True, capture_output=True)
    out = tmp_path / "episodes.csv"
    subprocess.run([_tool("hideseek_play", "play_episodes"), "basic", str(checkpoint), "0", "2", str(out)],
                   check=True, capture_output=True)
    theirs = {}
    for r in csv.DictReader(open(out)):
        theirs.setdefault(int(r["seed"]), []).append(int(r["hider_action"]))

    env = hideseek.make_vec("basic", num_envs=2, seed=0)
    obs, _ = env.reset(seed=0)
    ours = {0: [], 1: []}
    playing = [True, True]
    with torch.no_grad():
        while any(playing):
            actions = agent(torch.from_numpy(obs))[0].argmax(-1).numpy()
            obs, _, term, trunc, _ = env.step(actions)
            for i in (0, 1):
                if playing[i]:
                    ours[i].append(int(actions[i]))
                    playing[i] = not (term[i] or trunc[i])
    assert len(set(ours[0] + ours[1])) > 1  # the policy does not just repeat one action
    assert ours == theirs


def test_a_network_of_another_shape_is_refused_naming_the_parameter(tmp_path):
    agent = _example().Agent()
    agent.actor_out = torch.nn.Linear(512, 4)
    script = tmp_path / "bad.pt"
    torch.jit.script(agent).save(str(script))
    r = subprocess.run([_tool("hideseek_hider", "import_policy"), str(script), str(tmp_path / "out.pt"), "basic"],
                       capture_output=True, text=True)
    assert r.returncode == 1
    assert "actor_out.weight" in r.stderr and "[4, 512]" in r.stderr and "[5, 512]" in r.stderr
    assert not (tmp_path / "out.pt").exists()
    (tmp_path / "junk.pt").write_bytes(b"not a zip archive")
    r = subprocess.run([_tool("hideseek_hider", "import_policy"), str(tmp_path / "junk.pt"), str(tmp_path / "out.pt"),
                        "basic"], capture_output=True, text=True)
    assert r.returncode == 1 and "not a TorchScript file" in r.stderr


def test_the_checkpoint_records_the_game_it_was_trained_on(tmp_path):
    """The game is recorded (the default game's unless --game names another), so that a node playing it
    on another game says so; an unknown game is refused, naming the games there are."""
    script = tmp_path / "agent.pt"
    torch.jit.script(_example().Agent()).save(str(script))
    tool = _tool("hideseek_hider", "import_policy")
    subprocess.run([tool, str(script), str(tmp_path / "default.pt"), "basic"], check=True, capture_output=True)
    subprocess.run([tool, str(script), str(tmp_path / "v2.pt"), "basic", "--game", "v2"], check=True,
                   capture_output=True)
    assert torch.jit.load(str(tmp_path / "default.pt")).game == hideseek._core.default_game(
        hideseek._core.config_directory())
    assert torch.jit.load(str(tmp_path / "v2.pt")).game == "v2"
    r = subprocess.run([tool, str(script), str(tmp_path / "v9.pt"), "basic", "--game", "v9"], capture_output=True,
                       text=True)
    assert r.returncode == 1 and "'v9' is not a game here" in r.stderr and not (tmp_path / "v9.pt").exists()


def test_a_height_without_a_width_is_refused(tmp_path):
    script = tmp_path / "agent.pt"
    torch.jit.script(_example().Agent()).save(str(script))
    r = subprocess.run([_tool("hideseek_hider", "import_policy"), str(script), str(tmp_path / "out.pt"), "basic", "0",
                        "64"], capture_output=True, text=True)
    assert r.returncode == 1 and "HEIGHT and WIDTH go together" in r.stderr
    assert not (tmp_path / "out.pt").exists()
