"""Training across machines as separate processes (test/dd_ppo_check.cpp, one rank each): a rank
killed or frozen mid-run stops the other with an error naming it, and two ranks in two network
namespaces joined by a veth pair, as two hosts, train the same weights as on loopback.
Run with python3 -m pytest; DD_PPO_CHECK names the program (default: the devel space's)."""
import os
import re
import signal
import socket
import subprocess
import time
import uuid

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
CHECK = os.environ.get("DD_PPO_CHECK") or os.path.join(HERE, "..", "..", "..", "devel", "lib", "hideseek_hider",
                                                       "dd_ppo_check")


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def rank(r, address, *extra, prefix=()):
    return subprocess.Popen(list(prefix) + [CHECK, "--rank", str(r), "--world", "2", "--address", address] + list(extra),
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def weights(output):
    found = re.findall(r"^weights (\S+) (\S+)$", output, re.M)
    assert found, output
    return found[-1]


def test_a_killed_rank_stops_the_other_naming_it():
    address = "127.0.0.1:%d" % free_port()
    r0 = rank(0, address, "--updates", "8", "--timeout", "60")
    r1 = rank(1, address, "--updates", "8", "--die-after", "2", "--timeout", "60")
    out1, _ = r1.communicate(timeout=120)
    assert r1.returncode == -signal.SIGKILL, out1
    start = time.monotonic()
    out0, _ = r0.communicate(timeout=120)
    assert r0.returncode == 3, out0
    assert "rank 1 stopped" in out0, out0
    # Gloo sees the closed connection at once: rank 0 does not wait out its 60 s timeout.
    assert time.monotonic() - start < 60, out0


def test_a_frozen_rank_stops_the_other_after_the_timeout_naming_it():
    address = "127.0.0.1:%d" % free_port()
    # The timeout also bounds the rendezvous, where the two ranks' libtorch loads may be seconds
    # apart on a slow or loaded CPU: 15 s, not less, so that only the freeze can exhaust it.
    r0 = rank(0, address, "--updates", "8", "--timeout", "15")
    r1 = rank(1, address, "--updates", "8", "--freeze-after", "2", "--timeout", "15")
    try:
        out0, _ = r0.communicate(timeout=120)
        assert r0.returncode == 3, out0
        assert "rank 1 stopped (no heartbeat" in out0, out0
    finally:
        r1.kill()
        r1.communicate()


def test_two_ranks_on_loopback_agree():
    address = "127.0.0.1:%d" % free_port()
    r0, r1 = rank(0, address), rank(1, address)
    out0, _ = r0.communicate(timeout=120)
    out1, _ = r1.communicate(timeout=120)
    assert r0.returncode == 0 and r1.returncode == 0, out0 + out1
    assert weights(out0) == weights(out1)


def sh(*args):
    subprocess.run(args, check=True, capture_output=True, text=True)


def test_two_ranks_in_two_network_namespaces_train_as_two_hosts():
    """Each rank in its own network namespace, joined only by a veth pair (10.213.x.1 and .2): the
    gradients cross it, and the weights equal the loopback run's."""
    tag = uuid.uuid4().hex[:6]
    ns = ["hs_dd0_" + tag, "hs_dd1_" + tag]
    veth = ["hsv0" + tag, "hsv1" + tag]
    try:
        sh("ip", "netns", "add", ns[0])
    except (OSError, subprocess.CalledProcessError) as e:
        pytest.skip("cannot create a network namespace here (needs CAP_SYS_ADMIN and iproute2): %s"
                    % getattr(e, "stderr", e))
    try:
        sh("ip", "netns", "add", ns[1])
        sh("ip", "link", "add", veth[0], "type", "veth", "peer", "name", veth[1])
        net = "10.213.%d" % (int(tag, 16) % 200 + 20)
        for i in (0, 1):
            sh("ip", "link", "set", veth[i], "netns", ns[i])
            sh("ip", "-n", ns[i], "addr", "add", "%s.%d/24" % (net, i + 1), "dev", veth[i])
            sh("ip", "-n", ns[i], "link", "set", veth[i], "up")
            sh("ip", "-n", ns[i], "link", "set", "lo", "up")
        address = "%s.1:%d" % (net, 29500)
        procs = [rank(i, address, "--updates", "3", prefix=("ip", "netns", "exec", ns[i])) for i in (0, 1)]
        outs = [p.communicate(timeout=180)[0] for p in procs]
        for p, out in zip(procs, outs):
            assert p.returncode == 0, "\n".join(outs)
        assert weights(outs[0]) == weights(outs[1])
        # The same ranks on loopback: the same weights (the run is fixed by the ranks' seeds).
        loop = "127.0.0.1:%d" % free_port()
        l0, l1 = rank(0, loop, "--updates", "3"), rank(1, loop, "--updates", "3")
        lo0, _ = l0.communicate(timeout=120)
        l1.communicate(timeout=120)
        assert weights(lo0) == weights(outs[0])
    finally:
        for n in ns:
            subprocess.run(["ip", "netns", "del", n], capture_output=True)
