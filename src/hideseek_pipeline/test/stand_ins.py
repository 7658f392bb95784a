"""A catkin workspace of stand-ins for the pipeline's tests: roslaunch, the resolver, the policy
exporter, the episode player and the analysis scripts, each appending its command line to $CALLS
and writing what the pipeline reads back. No ROS, no training."""

FAKE_ROSLAUNCH = r"""#!/bin/bash
# train.launch: a training log of STEPS steps (or STOP_AT) and a checkpoint; evaluate.launch: an evaluation.
echo "roslaunch $*" >> "$CALLS"
for a in "$@"; do case $a in *:=*) declare "${a%%:=*}=${a#*:=}";; esac; done
case " $* " in
  *" train.launch "*)
    if [ -n "${HOLD:-}" ]; then  # train until a Ctrl-C, then write the log of STOP_AT steps and end as roslaunch does
      trap 'printf "update,steps,wall_s,x\n1,%s,1.0,0\n" "$STOP_AT" > "$output_dir/training_log.csv"
            echo ckpt > "$output_dir/checkpoint.pt"; exit 0' INT
      touch "$HOLD"
      while true; do sleep 0.1; done
    fi
    echo "[ INFO] PPO, network $network, on cpu in auto: bf16, because" > /dev/null
    echo "hider: PPO, network $network, on cpu in auto: fp32, this CPU has neither"
    printf 'update,steps,wall_s,x\n1,%s,123.7,0\n' "${STOP_AT:-$steps}" > "$output_dir/training_log.csv"
    echo ckpt > "$output_dir/checkpoint.pt" ;;
  *" evaluate.launch "*)
    [ "$variant" = "${FAIL_VARIANT:-}" ] && exit 0  # a required node died: no evaluation, roslaunch exits 0
    # the sweep held the run EVAL_HELD seconds more while it was evaluated, booked as 'sweep resume' books it
    [ -z "${EVAL_HELD:-}" ] || echo "$(( $(head -n 1 "$EVAL_HELD_FILE") + EVAL_HELD ))" > "$EVAL_HELD_FILE"
    # as the evaluator writes it since 2026-12-02, the game last (the pins' evaluators write no game)
    printf 'variant,policy,episodes,avg_living_steps,success_rate,game\n%s,%s,100,321.00,0.2500,v3\n' "$variant" "$policy" \
      > "$output_dir/evaluation.csv"
    printf 'seed,living_steps,outcome\n0,321,captured\n' > "$output_dir/episodes.csv"
    echo "| $policy |" > "$output_dir/evaluation.md" ;;
  *" analyze.launch "*)
    mkdir -p "$report_dir" && echo png > "$report_dir/distance_time.png"
    echo "analysis: $variant done" ;;
esac
"""
FAKE_TOOL = r"""#!/bin/bash
echo "$(basename "$0") $*" >> "$CALLS"
case $(basename "$0") in
  resolve) [ "${@: -1}" = game ] && echo v2 || echo "${MAP_FILE:-/maps/x.yaml}" ;;
  export_policy) cp "$1" "$2" ;;
  play_episodes) [ "$1" = --game ] && shift 2; printf 'seed,step\n%s,1\n' "$3" > "$5" ;;
esac
"""
FAKE_SCRIPT = r"""import os, sys
open(os.environ["CALLS"], "a").write(os.path.basename(sys.argv[0]) + " " + " ".join(sys.argv[1:]) + "\n")
for a in sys.argv[1:]:
    if a.endswith(".png"):
        open(a, "w").write("png")
if os.path.basename(sys.argv[0]) == "behaviour.py":
    os.makedirs(sys.argv[2], exist_ok=True)
    open(os.path.join(sys.argv[2], "behaviour.csv"), "w").write("x\n")
"""
FAKE_PROBE_SET = "#!/bin/bash\necho \"probe_set.sh $*\" >> \"$CALLS\"\necho /tmp/probe_set\n"




def stand_in_workspace(w):
    """Writes the stand-ins under the folder `w` (created) and returns it."""
    (w / "scripts").mkdir(parents=True, exist_ok=True)
    (w / "bin").mkdir()
    (w / "scripts" / "env.sh").write_text('export PATH="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/bin:$PATH"\n')
    for path, text in ((w / "bin" / "roslaunch", FAKE_ROSLAUNCH),
                       (w / "devel" / "lib" / "hideseek_game" / "resolve", FAKE_TOOL),
                       (w / "devel" / "lib" / "hideseek_hider" / "export_policy", FAKE_TOOL),
                       (w / "devel" / "lib" / "hideseek_play" / "play_episodes", FAKE_TOOL),
                       (w / "devel" / "lib" / "hideseek_analysis" / "probe_set", FAKE_TOOL),
                       (w / "src" / "hideseek_analysis" / "scripts" / "probe_set.sh", FAKE_PROBE_SET)):
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
        path.chmod(0o755)
    scripts = w / "src" / "hideseek_analysis" / "scripts"
    scripts.mkdir(parents=True, exist_ok=True)
    for name in ("plot_learning_curve.py", "plot_trajectories.py", "plot_crossplay.py", "behaviour.py", "probes.py", "table2.py",
                 "claims.py", "seed_figures.py", "reproduce_report.py"):
        (scripts / name).write_text(FAKE_SCRIPT)
    return w
