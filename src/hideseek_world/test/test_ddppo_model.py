"""Tests of experiments/ddppo/ddppo_model.py, the speed-up model of training across machines
(docs/distributed.md): run with python3 -m pytest."""
import os
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "experiments", "ddppo"))
import ddppo_model as m  # noqa: E402

GB = 1e9 / 8


def test_one_machine_is_the_baseline_and_pays_no_communication():
    assert m.allreduce_s(1, 8.8e6, GB, 50e-6) == 0.0
    assert m.speedup(1, 1.1, 16, 8.8e6, GB, 50e-6) == 1.0


def test_the_ring_moves_twice_the_gradient_less_a_share_per_rank():
    # 2 ranks: each sends and receives half the gradient twice (reduce-scatter, all-gather)
    assert abs(m.allreduce_s(2, 1e6, 1e6, 0.0) - 1.0) < 1e-12
    assert abs(m.allreduce_s(4, 1e6, 1e6, 0.0) - 1.5) < 1e-12


def test_free_communication_gives_linear_speed_up_and_slow_links_give_less():
    assert abs(m.speedup(8, 1.1, 16, 8.8e6, 1e30, 0.0) - 8.0) < 1e-9
    assert m.speedup(8, 1.1, 16, 8.8e6, GB, 50e-6) < m.speedup(8, 1.1, 16, 8.8e6, 10 * GB, 50e-6) < 8.0


def test_the_command_prints_a_row_per_machine_count_from_the_ppo_file():
    out = subprocess.run([sys.executable, os.path.join(ROOT, "experiments", "ddppo", "ddppo_model.py"), "900", "8841880",
                          "--machines", "1", "2", "16"], capture_output=True, text=True, check=True).stdout
    assert "16 all-reduces of 8.84 MB per update" in out  # 4 epochs x 4 minibatches (config/ppo.yaml)
    rows = [line for line in out.splitlines() if line.startswith("| ") and line[2].isdigit()]
    assert [r.split("|")[1].strip() for r in rows] == ["1", "2", "16"]
    assert "| 1 | 0.00 s | 1.00x | 0.00 s | 1.00x |" in out
