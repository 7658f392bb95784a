"""Self-play and the seeker's evaluation, the parts that need no ROS: the opponents' pools and
draws (a pure function of the seed, the generation and the role), resuming from generations.yaml,
the capture summary of an evaluation, and the cross-play table."""
import os
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "src", "hideseek_pipeline", "python"))
from hideseek_pipeline import seeker, selfplay  # noqa: E402


def gen(role, k):
    return {"role": role, "generation": k, "checkpoint": "generations/%s_g%03d.pt" % (role, k)}


def test_each_side_draws_from_the_other_sides_past_generations_and_its_random_policy():
    saved = [gen("seeker", 1), gen("hider", 1), gen("seeker", 2)]
    # The seeker of generation 2 meets the hiders before it; the hider of 2 also the seeker of 2,
    # which trained just before it.
    assert selfplay.pools(saved, "seeker", 2) == ["random", "generations/hider_g001.pt"]
    assert selfplay.pools(saved, "hider", 2) == ["random", "generations/seeker_g001.pt", "generations/seeker_g002.pt"]
    assert selfplay.pools([], "seeker", 1) == ["random"]


def test_the_draw_depends_only_on_the_seed_the_generation_and_the_role():
    pool = ["random"] + ["generations/hider_g%03d.pt" % k for k in range(1, 9)]
    first = [selfplay.draw(pool, 7, k, "seeker") for k in range(1, 40)]
    assert first == [selfplay.draw(pool, 7, k, "seeker") for k in range(1, 40)]  # a resume draws the same
    assert first != [selfplay.draw(pool, 8, k, "seeker") for k in range(1, 40)]  # another seed, other draws
    assert set(first) == set(pool)  # uniform over the pool: every generation is met


def test_each_generation_trains_on_episodes_of_its_own():
    assert [selfplay.world_seed(3, k) for k in (1, 2, 3)] == [3, 100003, 200003]


def test_generations_are_registered_and_read_back(tmp_path):
    saved = [dict(gen("seeker", 1), steps=128, opponent="random"), dict(gen("hider", 1), steps=128,
                                                                        opponent="generations/seeker_g001.pt")]
    selfplay.write_generations(str(tmp_path), saved)
    assert selfplay.load_generations(str(tmp_path)) == saved
    assert selfplay.load_generations(str(tmp_path / "none")) == []


def test_the_learning_rate_is_constant_in_self_play(tmp_path):
    source = os.path.join(ROOT, "config", "ppo.yaml")
    path = selfplay.constant_rate_ppo(source, str(tmp_path))
    text = open(path).read()
    assert "anneal_learning_rate: false" in text and "learning_rate: 0.0003" in text


def test_a_capture_summary_counts_captures_and_their_times(tmp_path):
    table = tmp_path / "episodes.csv"
    table.write_text("seed,living_steps,outcome\n0,20,captured\n1,1000,survived\n2,40,captured\n3,1000,survived\n")
    s = seeker.capture_summary(str(table))
    assert s == {"episodes": 4, "captures": 2, "capture_rate": 0.5, "mean_time_to_capture": 30.0,
                 "mean_living_steps": 515.0}
    table.write_text("seed,living_steps,outcome\n")
    with pytest.raises(seeker.ToolError, match="holds no episode"):
        seeker.capture_summary(str(table))


def test_the_crossplay_table_has_a_row_per_hider_and_a_column_per_seeker(tmp_path):
    rows = [{"hider": h, "seeker": s, "episodes": 10, "captures": c, "capture_rate": c / 10, "mean_living_steps": m}
            for (h, s, c, m) in [("random", "scripted", 9, 50.0), ("random", "seeker_g001", 3, 700.0),
                                 ("hider_g001", "scripted", 5, 400.0), ("hider_g001", "seeker_g001", 1, 900.0)]]
    selfplay.write_crossplay(rows, str(tmp_path), "test")
    md = open(tmp_path / "crossplay.md").read().splitlines()
    assert md[4] == "| hider \\ seeker | scripted | seeker_g001 |"
    assert md[6] == "| random | 90 %, 50 | 30 %, 700 |"
    assert md[7] == "| hider_g001 | 50 %, 400 | 10 %, 900 |"
    assert open(tmp_path / "crossplay.csv").read().splitlines()[1] == "random,scripted,10,9,0.900,50.0"


def test_policies_get_short_file_safe_labels():
    assert seeker.label("scripted/flee") == "scripted_flee"
    assert seeker.label("/runs/x/generations/seeker_g004.pt") == "seeker_g004"
    assert seeker.label("shipped") == "shipped"


def test_a_resumed_cross_play_keeps_only_the_pairs_played_to_the_end(tmp_path):
    table = tmp_path / "episodes.csv"
    assert selfplay._played(str(table), 3) is None  # never played
    table.write_text("seed,living_steps,outcome\n0,20,captured\n1,1000,survived\n2,40,captured\n")
    assert selfplay._played(str(table), 3)["captures"] == 2
    assert selfplay._played(str(table), 4) is None  # played with fewer episodes than asked
    assert selfplay._played(str(table), 3, first_seed=100) is None  # other seeds
    table.write_text("seed,living_steps,outcome\n0,20,captured\n1,10")  # cut off mid-write
    assert selfplay._played(str(table), 2) is None
    table.write_text("seed,living_steps,outcome\n0,20,captured\n1,\n")
    assert selfplay._played(str(table), 2) is None


def test_a_generation_s_time_is_its_own_though_each_side_resumes_one_run():
    saved = [dict(gen("seeker", 1), wall_s=100), dict(gen("hider", 1), wall_s=50), dict(gen("seeker", 2), wall_s=230),
             dict(gen("hider", 2), wall_s=110)]
    assert selfplay.generation_seconds(saved) == [100, 50, 130, 60]
    assert sum(selfplay.generation_seconds(saved)) == 230 + 110


def test_a_generation_s_time_leaves_out_the_pauses_that_held_it(tmp_path):
    """seeker_g001 of the 2026-12-02 self-play listed 3,186 s, of which make test held it 2,131 s:
    each pause the queue booked counts against the generation saved first after it ended."""
    saved = [dict(gen("seeker", 1), wall_s=3186), dict(gen("hider", 1), wall_s=900),
             dict(gen("seeker", 2), wall_s=4300)]
    (tmp_path / "generations").mkdir()
    for g, at in zip(saved, (10_000, 11_000, 13_000)):
        path = tmp_path / g["checkpoint"]
        path.write_text("w")
        os.utime(path, (at, at))
    assert selfplay.generation_pauses(str(tmp_path), saved) == [0, 0, 0]  # no pause booked
    (tmp_path / "paused.log").write_text("9000.5 2131\n12000.0 30\n12500.0 40\n14000.0 50\n12600")
    # 2131 s in seeker_g001; 70 s in seeker_g002; 50 s after the last saved generation; a cut line
    assert selfplay.generation_pauses(str(tmp_path), saved) == [2131, 0, 70]
    assert selfplay.training_seconds(str(tmp_path), saved) == [3186 - 2131, 900, 4300 - 3186 - 70]
    (tmp_path / saved[1]["checkpoint"]).unlink()  # weights not on this machine: nothing to place pauses by
    assert selfplay.generation_pauses(str(tmp_path), saved) == [0, 0, 0]


def test_the_records_of_a_self_play_wait_for_every_generation(tmp_path):
    o = selfplay.SelfPlayOptions(out=str(tmp_path), generations=2)
    selfplay.write_generations(str(tmp_path), [gen("seeker", 1), gen("hider", 1), gen("seeker", 2)])
    with pytest.raises(selfplay.ToolError, match="has not saved hider_g002: train them first"):
        selfplay.require_generations(o)
    selfplay.write_generations(str(tmp_path), [gen("seeker", 1), gen("hider", 1), gen("seeker", 2), gen("hider", 2)])
    selfplay.require_generations(o)


def _analysis(folder, living, probe_s):
    os.makedirs(folder)
    with open(os.path.join(folder, "behaviour.csv"), "w") as f:
        f.write("run,episodes,steps,mean_living_steps,success_rate,backward_share,sees_seeker_share,seen_share,"
                "line_of_sight_breaks_per_100,seeker_lost_per_100,distance_turns_per_100,distance_swings_per_100\n"
                "r,100,1,%s,0.21,0.84,0.07,0.09,0.25,0.67,2.9,1.03\n" % living)
    with open(os.path.join(folder, "states.csv"), "w") as f:
        f.write("run,state,S,H,O,steps,frequency\nr,S1 H1 O0,1,1,0,1,0.25\nr,S1 H1 O1,1,1,1,1,0.5\n"
                "r,S0 H0 O1,0,0,1,1,0.25\n")
    with open(os.path.join(folder, "probes.csv"), "w") as f:
        f.write("run,representation,target,gain_over_random_init\nr,trained,S,%s\nr,trained,H,0.07\n" % probe_s)


def test_the_last_hider_s_analysis_is_set_beside_the_hiders_trained_only_against_the_scripted_seeker(tmp_path):
    _analysis(str(tmp_path / "last"), 600.5, 0.1)
    _analysis(str(tmp_path / "basic_v3_seed0"), 255.7, 0.02)
    text = selfplay.behaviour_beside("hider_g004", str(tmp_path / "last"),
                                     {"basic_v3_seed0": str(tmp_path / "basic_v3_seed0"),
                                      "basic_v3_seed1": str(tmp_path / "absent")})
    assert "| measure | hider_g004 (self-play) | basic_v3_seed0 | basic_v3_seed1 |" in text
    assert "| mean living steps | 600.5 | 255.7 | - |" in text
    # S1 H1 sums both O states; a probe is its gain over the random-init networks
    assert "| share of steps in S1 H1 (each sees the other) | 0.75 | 0.75 | - |" in text
    assert "| probe S: balanced accuracy over random init | +0.100 | +0.020 | - |" in text


def test_the_latest_share_draws_the_other_side_s_latest_generation_that_often():
    pool = ["random"] + ["generations/hider_g%03d.pt" % k for k in range(1, 9)]
    draws = [selfplay.draw(pool, seed, 5, "seeker", 0.5) for seed in range(2000)]
    # half the draws by the share, and a ninth of the uniform other half: 0.5 + 0.5 / 9
    assert abs(draws.count(pool[-1]) / 2000 - (0.5 + 0.5 / 9)) < 0.04
    assert set(draws) == set(pool)  # the older generations and the random policy are still met
    # share 0 is the uniform draw alone, draw for draw: a self-play saved before the share replays
    uniform = [selfplay.draw(pool, seed, 5, "seeker") for seed in range(200)]
    assert uniform == [selfplay.draw(pool, seed, 5, "seeker", 0.0) for seed in range(200)]
    assert selfplay.draw(["random"], 0, 1, "seeker", 1.0) == "random"


def test_a_self_play_resumes_only_with_the_latest_share_it_drew_with(tmp_path):
    # generations saved before the share existed drew uniformly: they resume with share 0 only
    selfplay.write_generations(str(tmp_path), [gen("seeker", 1), gen("hider", 1)])
    o = selfplay.SelfPlayOptions(out=str(tmp_path), generations=1, game="v3")  # default share 0.5
    with pytest.raises(selfplay.ToolError, match="latest share 0.0: resume it with --latest-share 0.0"):
        selfplay.selfplay(None, o)
    o.latest_share = 0.0
    assert len(selfplay.selfplay(None, o)) == 2  # both saved: nothing left to train


def test_the_command_line_refuses_a_share_outside_0_to_1():
    from hideseek_pipeline import cli
    for bad in ("1.5", "-0.1", "half"):
        with pytest.raises(SystemExit):
            cli.parser().parse_args(["selfplay", "out", "--latest-share", bad])
    assert cli.parser().parse_args(["selfplay", "out"]).latest_share == 0.5
