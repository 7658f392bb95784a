#!/usr/bin/env bash
# Faults and malformed input thrown at the real nodes, one case per line of a Markdown table:
# what was done, what a user should see, what happened. Not a test (it takes a few minutes and
# prints a report); the behaviours it checks are also held by the tests.
# usage: experiments/fault_campaign/fault_campaign.sh [REPORT.md]
set -uo pipefail
cd "$(dirname "$0")/../.."
source scripts/env.sh
report=${1:-/dev/stdout}
dir=$(mktemp -d /tmp/hideseek_faults.XXXXXX)
port=$((12400 + RANDOM % 100))  # apart from the sweep (12100-12112) and the tests (docs/testing.md, "Ports")
export ROS_MASTER_URI=http://localhost:$port
rows=()
row() { rows+=("| $1 | $2 | $3 | $4 |"); echo "fault_campaign: $1: $4" >&2; }
pass() { [ "$1" -eq 0 ] && echo "**pass**: $2" || echo "**FAIL**: $2"; }

# The process of a node of this campaign's graph (its master port), by its executable's name.
node_pid() {
  local p
  for p in $(pgrep -f "$1"); do
    tr '\0' '\n' < "/proc/$p/environ" 2> /dev/null | grep -q "^ROS_MASTER_URI=.*:$port/\?$" && echo "$p"
  done
}

# --- start-up: each stops the game with a FATAL line naming the problem --------------------------
fatal_case() {  # name, expected text, launch file and arguments...
  local name=$1 expected=$2
  shift 2
  timeout 240 roslaunch -p "$port" hideseek_world "$@" > "$dir/$name.log" 2>&1
  local line
  line=$(grep -F "[FATAL]" "$dir/$name.log" | head -n 1 | sed 's/\x1b\[[0-9;]*m//g; s/|/\\|/g' | cut -c1-160)
  grep -F "[FATAL]" "$dir/$name.log" | grep -F -- "$expected" > /dev/null  # no -q: a grep that stops at the first match breaks its writer's pipe
  row "$name" "\`$*\`" "FATAL naming it" "$(pass $? "$line")"
}
fatal_case missing_checkpoint "cannot be read" basic.launch policy:=/nonexistent/policy.pt
head -c 100000 policies/basic.pt > "$dir/truncated.pt"
fatal_case truncated_checkpoint "truncated.pt" basic.launch policy:="$dir/truncated.pt"
cp policies/basic.pt "$dir/flipped.pt"
printf '\x55' | dd of="$dir/flipped.pt" bs=1 seek=5000000 conv=notrunc status=none
fatal_case flipped_byte "flipped.pt" basic.launch policy:="$dir/flipped.pt"
fatal_case bad_precision "precision" basic.launch precision:=fp16
fatal_case cuda_without_cuda "cuda" basic.launch device:=cuda
fatal_case bad_mode "mode" game.launch.xml variant:=basic mode:=fast
fatal_case bad_num_arenas "num_arenas" basic.launch num_arenas:=0
printf 'variant: basic\nmap: %s/maps/deterministic.yaml\nhider:\n  sped: 3.0\n' "$PWD/config" > "$dir/typo.yaml"
fatal_case misspelt_field "sped" game.launch.xml variant:=basic variant_config:="$dir/typo.yaml"
head -c 60 config/variants/stochasticmaps.yaml > "$dir/trunc_variant.yaml"  # cut inside its first comment
fatal_case truncated_variant "trunc_variant.yaml: field 'variant'" game.launch.xml variant:=basic variant_config:="$dir/trunc_variant.yaml"
head -c 140 config/variants/stochasticmaps.yaml > "$dir/trunc_variant2.yaml"  # cut inside a value: "policy: stoch"
fatal_case truncated_variant_mid_value "trunc_variant2.yaml" game.launch.xml variant:=basic variant_config:="$dir/trunc_variant2.yaml"
# Either the hider or the analysis node may stop first; both name the file.
fatal_case analysis_missing_checkpoint "/nonexistent.pt" analyze.launch policy:=/nonexistent.pt steps:=160 num_arenas:=1 output_dir:="$dir/an"

# Hostile checkpoints: archives that pass as archives but lie about what they hold.
/usr/bin/python3 - "$dir/wrong_shape.pt" <<'PY'
import sys, torch
m = torch.jit.load("policies/basic.pt")  # a valid archive written by torch.jit.save, conv1 of 16 filters
m.model.conv1._c.setattr("weight", torch.zeros(16, 3, 8, 8))
torch.jit.save(m, sys.argv[1])
PY
fatal_case wrong_tensor_shapes "conv1.weight has shape [16, 3, 8, 8]" basic.launch policy:="$dir/wrong_shape.pt"
/usr/bin/python3 - policies/basic.pt "$dir/huge_sizes.pt" <<'PY'
import struct, sys
b = bytearray(open(sys.argv[1], "rb").read())
eocd = b.rfind(b"PK\x05\x06")
first = struct.unpack_from("<I", b, eocd + 16)[0]
struct.pack_into("<II", b, first + 20, 0xF0000000, 0xF0000000)  # the first entry claims 4 GB
open(sys.argv[2], "wb").write(b)
PY
fatal_case huge_declared_sizes "4026531840" basic.launch policy:="$dir/huge_sizes.pt"

# --- a running lockstep game under malformed input -----------------------------------------------
roslaunch -p "$port" hideseek_world basic.launch mode:=lockstep num_arenas:=2 policy:=random > "$dir/game.log" 2>&1 &
game=$!
for _ in $(seq 1 100); do rostopic list 2>/dev/null | grep -q /world/steps && break; sleep 0.2; done
sleep 2
# (rostopic takes seconds to start on a loaded machine; /diagnostics comes once a second)
steps() { timeout 30 rostopic echo -n 1 /diagnostics 2>/dev/null | grep -A1 'key: "decision_steps"' | tail -n 1 | grep -o '[0-9]*'; }
count() { timeout 30 rostopic echo -n 1 /diagnostics 2>/dev/null | grep -A1 "key: \"$1\"" | tail -n 1 | grep -o '[0-9]*'; }
flood() {  # message for hider/actions, seconds
  timeout "$2" rostopic pub -r 50 /hider/actions hideseek_msgs/ActionBatch "$1" > /dev/null 2>&1
}
before=$(steps)
flood "{actions: [1, 1], step: [0, 0]}" 12  # rostopic needs seconds to start under load
after=$(steps)
n=$(count rejected_second_publisher)
[ -n "$before" ] && [ -n "$after" ] && [ "$after" -gt "$before" ] && [ "${n:-0}" -gt 0 ]
row second_publisher "\`rostopic pub\` on /hider/actions beside the hider (12 s at 50 Hz, its start included)" "rejected, counted; the game goes on" "$(pass $? "decision steps $before -> $after; rejected_second_publisher $n")"
kill -INT "$game"; wait "$game" 2>/dev/null
# Without a hider node the injector owns hider/actions, so its batches are checked one by one.
roslaunch -p "$port" hideseek_world game.launch.xml variant:=basic mode:=lockstep num_arenas:=2 start_hider:=false \
  > "$dir/game.log" 2>&1 &
game=$!
for _ in $(seq 1 100); do rostopic list 2>/dev/null | grep -q /world/steps && break; sleep 0.2; done
sleep 2
malformed() {  # name, what, message, diagnostics key
  local before_n after_n
  before_n=$(count "$4")
  flood "$3" 12
  after_n=$(count "$4")
  [ -n "$after_n" ] && [ "${after_n:-0}" -gt "${before_n:-0}" ]
  row "$1" "$2 (12 s at 50 Hz, its start included, as the only hider)" "rejected and counted; the world stays up" "$(pass $? "$4: ${before_n:-?} -> ${after_n:-?}")"
}
malformed wrong_arena_count "ActionBatch with 3 actions for 2 arenas" "{actions: [1, 1, 1], step: [0, 0, 0]}" rejected_wrong_arena_count
malformed invalid_action "action 9" "{actions: [9, 9], step: [0, 0]}" rejected_invalid_action
malformed stale_step_ids "step ids that are not the current step" "{actions: [1, 1], step: [999999, 999999]}" rejected_wrong_step
# Bytes no ActionBatch is: a length prefix claiming 4 billion actions (roscpp's own reader would
# allocate them before any check), sent as ActionBatch by a publisher that writes raw bytes.
before_n=$(count rejected_malformed)
timeout 10 /usr/bin/python3 - > /dev/null 2>&1 <<'PY'
import struct, time
import rospy
from hideseek_msgs.msg import ActionBatch

class Hostile(ActionBatch):
    def serialize(self, buff):
        buff.write(struct.pack("<IIII", 0, 0, 0, 0) + struct.pack("<I", 0xFFFFFFF0) + b"\x01\x01")

rospy.init_node("hostile_publisher", anonymous=True)
pub = rospy.Publisher("/hider/actions", ActionBatch, queue_size=10)
time.sleep(1.5)
for _ in range(100):
    pub.publish(Hostile())
    time.sleep(0.02)
PY
after_n=$(count rejected_malformed)
alive=$(rosnode list 2>/dev/null | grep -c "^/world$")
[ "${after_n:-0}" -gt "${before_n:-0}" ] && [ "$alive" -eq 1 ]
row hostile_length "ActionBatch bytes whose actions length claims 4,294,967,280 entries (100 at 50 Hz)" "rejected before any allocation, counted; the world stays up" "$(pass $? "rejected_malformed: ${before_n:-?} -> ${after_n:-?}; world up: $alive")"
lines=$(grep -c "rejected" "$dir/game.log")
[ "$lines" -le 40 ]
row warning_flood "the four floods above: up to 48 s of bad input at 50 Hz" "warnings throttled on the wall clock" "$(pass $? "$lines warning lines for up to about 2,400 bad messages")"
kill -INT "$game"; wait "$game" 2>/dev/null
roslaunch -p "$port" hideseek_world basic.launch mode:=lockstep num_arenas:=2 policy:=random > "$dir/game2.log" 2>&1 &
game=$!
for _ in $(seq 1 100); do rostopic list 2>/dev/null | grep -q /world/steps && break; sleep 0.2; done
sleep 2
for k in 1 2 3; do timeout 10 rosservice call /world/reset "{arena: -1, seed: $((500 + k))}" > /dev/null 2>&1; sleep 1; done
before=$(steps); sleep 2; after=$(steps)
[ -n "$before" ] && [ -n "$after" ] && [ "$after" -gt "$before" ]
row lockstep_reset "\`rosservice call /world/reset\` three times in lockstep" "the game goes on" "$(pass $? "decision steps $before -> $after")"
kill -INT "$game"; wait "$game" 2>/dev/null

# --- realtime: a killed hider stands still; the world reports it and goes on ----------------------
# (in the variant launch files the hider is a required node: killing it ends the game by design)
roslaunch -p "$port" hideseek_world game.launch.xml variant:=basic start_hider:=false > "$dir/rt.log" 2>&1 &
game=$!
sleep 4
rosrun hideseek_hider hider_node __name:=hider _game_config:="$PWD/config/game.yaml" \
  _variant_config:="$PWD/config/variants/basic.yaml" > "$dir/hider.log" 2>&1 &
sleep 6
rosnode kill /hider > /dev/null 2>&1
sleep 3
before=$(steps); sleep 2; after=$(steps)
stale=$(count stale_decisions)
[ -n "$before" ] && [ -n "$after" ] && [ "$after" -gt "$before" ]
row realtime_hider_killed "\`rosnode kill /hider\` in realtime (a hider started apart)" "world goes on, the hider stands still" "$(pass $? "decision steps $before -> $after; stale_decisions $stale")"
kill -INT "$game"; wait "$game" 2>/dev/null

# --- recording: SIGINT closes the bag -------------------------------------------------------------
# The recorder opens its bag at the first message: wait for it (seconds on a loaded machine), then record a while.
recording() { for _ in $(seq 1 300); do [ -s "$(ls "$1"/*.bag.active 2> /dev/null | head -n 1)" ] && break; sleep 0.2; done; sleep 5; }
roslaunch -p "$port" hideseek_world basic.launch mode:=lockstep num_arenas:=2 policy:=random record:=true bag_dir:="$dir/bags" > "$dir/rec.log" 2>&1 &
game=$!
recording "$dir/bags"
kill -INT "$game"; wait "$game" 2>/dev/null
bag=$(ls "$dir"/bags/*.bag 2>/dev/null | head -n 1)
info=$(rosbag info "$bag" 2>/dev/null | grep -E "^messages" | tr -s ' ')
[ -n "$bag" ] && [ -n "$info" ]
row bag_on_sigint "Ctrl-C (SIGINT) on a recording launch" "the bag is closed and indexed" "$(pass $? "${info:-no readable bag}")"

# --- analysis bags: one cut mid-chunk, one whose recorder was killed -------------------------------
analyze() {  # bag, output dir, log
  timeout 300 rosrun hideseek_analysis analyze_bag basic "$PWD/policies/basic.pt" "$1" "$2" > "$3" 2>&1
}
files_in() { find "$1" -type f 2> /dev/null | wc -l; }
head -c "$(($(stat -c %s "$bag" 2> /dev/null || echo 0) / 2))" "$bag" > "$dir/cut.bag"  # half: inside a chunk
analyze "$dir/cut.bag" "$dir/cut_out" "$dir/cut_an.log"
rc=$?
line=$(grep -m 1 "cannot read bag" "$dir/cut_an.log" | sed 's|/tmp/hideseek_faults[^:]*/||' | cut -c1-200)
[ "$rc" -ne 0 ] && echo "$line" | grep -q "the bag is cut" && [ "$(files_in "$dir/cut_out")" -eq 0 ]
row analysis_bag_cut "\`analyze_bag\` on the bag above cut at half its size (inside a chunk)" "refused before rosbag reads it, naming the bag and the byte; nothing written" "$(pass $? "exit $rc; ${line:-no error line}; files written: $(files_in "$dir/cut_out")")"
roslaunch -p "$port" hideseek_world basic.launch mode:=lockstep num_arenas:=2 policy:=random record:=true bag_dir:="$dir/killed" > "$dir/rec2.log" 2>&1 &
game=$!
recording "$dir/killed"
recorder=$(node_pid "rosbag/record")
[ -n "$recorder" ] && kill -KILL "$recorder"
sleep 1
kill -INT "$game"; wait "$game" 2>/dev/null
active=$(ls "$dir"/killed/*.bag.active 2>/dev/null | head -n 1)
analyze "$active" "$dir/killed_out" "$dir/killed_an.log"
refused=$(grep -m 1 "cannot read bag" "$dir/killed_an.log" | sed 's|/tmp/hideseek_faults[^:]*/||' | cut -c1-200)
rosbag reindex "$active" > /dev/null 2>&1
analyze "$active" "$dir/killed_out2" "$dir/killed_an2.log"
# After the repair the bag is read to its end, or, where the recorder dropped messages (its queue
# overflows on a loaded machine), refused at the first hole, naming the missing decisions.
read_back=$(grep -m 1 -o -E "analysis: [0-9]* decisions of 2 arenas.*missing|decisions [0-9]* to [0-9]* are missing.*analysed" "$dir/killed_an2.log")
[ -n "$recorder" ] && echo "$refused" | grep -q "was not closed" && [ -n "$read_back" ]
row recorder_killed "SIGKILL to \`rosbag record\` of a recording game, then \`analyze_bag\`, then \`rosbag reindex\` and \`analyze_bag\` again" "refused as unindexed, saying how to repair it; after the repair every recorded step is read, or a hole the recorder left is named and nothing past it analysed" "$(pass $? "${refused:-not refused}; after reindex: ${read_back:-nothing read}")"

# --- evaluation: an evaluator that starts late still sees every episode ----------------------------
timeout 300 roslaunch -p "$port" hideseek_world evaluate.launch variant:=basic policy:=random episodes:=20 output_dir:="$dir/eval" > "$dir/eval.log" 2>&1
n=$(tail -n +2 "$dir/eval/episodes.csv" 2>/dev/null | wc -l)
[ "$n" = 20 ]
row evaluator "evaluate.launch (lockstep waits for the evaluator)" "20 episodes, seeds 0-19" "$(pass $? "$n episodes")"

# --- training: the world killed with SIGKILL; the same command resumes -----------------------------
# The training log's updates are 1..N with steps k x ROLLOUT, none twice and none missing.
log_is_whole() {  # log, rollout samples, total steps
  /usr/bin/python3 - "$@" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
rollout, total = int(sys.argv[2]), int(sys.argv[3])
updates = [int(r["update"]) for r in rows]
steps = [int(r["steps"]) for r in rows]
ok = updates == list(range(1, len(rows) + 1)) and steps == [rollout * u for u in updates] and steps[-1] >= total
print("%d rows, updates 1..%d, steps %d..%d%s" % (len(rows), updates[-1], steps[0], steps[-1], "" if ok else ": NOT WHOLE"))
sys.exit(0 if ok else 1)
PY
}
train=(roslaunch -p "$port" hideseek_world train.launch num_arenas:=4 hider_threads:=1 steps:=40960
  checkpoint_interval:=5 output_dir:="$dir/train")
"${train[@]}" > "$dir/train1.log" 2>&1 &
game=$!
for _ in $(seq 1 600); do [ -f "$dir/train/checkpoint.pt" ] && break; sleep 0.2; done
sleep 4
world=$(node_pid hideseek_world/world_node)
[ -n "$world" ] && kill -KILL "$world"
timeout 60 tail --pid="$game" -f /dev/null
stopped=$?
timeout 600 "${train[@]}" > "$dir/train2.log" 2>&1
second=$?
resumed=$(grep -o "resumed at step [0-9]*" "$dir/train2.log" | head -n 1)
whole=$(log_is_whole "$dir/train/training_log.csv" 256 40960)
[ -n "$world" ] && [ "$stopped" -eq 0 ] && [ "$second" -eq 0 ] && [ -n "$resumed" ] && log_is_whole "$dir/train/training_log.csv" 256 40960 > /dev/null
row world_killed_in_training "SIGKILL to the world node 4 s after the first checkpoint of \`train.launch\` (4 arenas, 40,960 steps), then the same command" "the launch stops (the world is required); the same command resumes from the checkpoint; the log has no duplicate and no gap" "$(pass $? "launch stopped: $([ "$stopped" -eq 0 ] && echo yes || echo no); ${resumed:-not resumed}; log: $whole")"

# --- the master: restarted under a training run that uses it, killed under one that started it -----
kill_master() {  # the master of this port and its rosout, as a crash would
  kill -KILL $(pgrep -f "rosmaster --core -p $port") $(node_pid rosout/rosout) "$@" 2> /dev/null
}
roscore -p "$port" > "$dir/core1.log" 2>&1 &
core=$!
sleep 3
mtrain=(roslaunch -p "$port" hideseek_world train.launch num_arenas:=4 hider_threads:=1 steps:=40960
  checkpoint_interval:=5 output_dir:="$dir/mtrain")
"${mtrain[@]}" > "$dir/mtrain1.log" 2>&1 &
game=$!
for _ in $(seq 1 600); do [ -f "$dir/mtrain/checkpoint.pt" ] && break; sleep 0.2; done
kill_master "$core"
sleep 6
roscore -p "$port" > "$dir/core2.log" 2>&1 &
core=$!
sleep 8
known=$(rosnode list 2> /dev/null | grep -c -E "^/(world|hider|seeker)$")
timeout 900 tail --pid="$game" -f /dev/null
wait "$game"
first=$?
said=$(grep -c "a new ROS master answers" "$dir/mtrain1.log")
timeout 300 "${mtrain[@]}" > "$dir/mtrain2.log" 2>&1
second=$?
resumed=$(grep -o "resumed at step [0-9]*" "$dir/mtrain2.log" | head -n 1)
whole=$(log_is_whole "$dir/mtrain/training_log.csv" 256 40960)
kill -INT "$core"; wait "$core" 2> /dev/null
[ "$said" -eq 3 ] && [ "$first" -eq 0 ] && [ "$second" -eq 0 ] && [ "$resumed" = "resumed at step 40960" ] &&
  log_is_whole "$dir/mtrain/training_log.csv" 256 40960 > /dev/null
row master_restarted "\`roscore\` killed with SIGKILL after the first checkpoint of \`train.launch\` run against it, and started again 6 s later; then the same command" "training goes on over the nodes' connections and finishes; each node says the new master does not know it, and what to do; the same command finds the run complete; the log has no duplicate and no gap" "$(pass $? "launch exit $first; $said of 3 nodes said so; nodes the new master knows: $known; then: ${resumed:-not resumed}; log: $whole")"
otrain=(roslaunch -p "$port" hideseek_world train.launch num_arenas:=4 hider_threads:=1 steps:=40960
  checkpoint_interval:=5 output_dir:="$dir/otrain")
"${otrain[@]}" > "$dir/otrain1.log" 2>&1 &
game=$!
for _ in $(seq 1 600); do [ -f "$dir/otrain/checkpoint.pt" ] && break; sleep 0.2; done
sleep 4
kill_master
timeout 60 tail --pid="$game" -f /dev/null
stopped=$?
died=$(grep -c "REQUIRED process \[master\] has died" "$dir/otrain1.log")
timeout 600 "${otrain[@]}" > "$dir/otrain2.log" 2>&1
second=$?
resumed=$(grep -o "resumed at step [0-9]*" "$dir/otrain2.log" | head -n 1)
whole=$(log_is_whole "$dir/otrain/training_log.csv" 256 40960)
[ "$stopped" -eq 0 ] && [ "$died" -ge 1 ] && [ "$second" -eq 0 ] && [ -n "$resumed" ] &&
  log_is_whole "$dir/otrain/training_log.csv" 256 40960 > /dev/null
row master_killed_under_launch "SIGKILL to the master that \`train.launch\` started, 4 s after its first checkpoint; then the same command" "the launch stops (the master is a required process); the same command resumes from the checkpoint; the log has no duplicate and no gap" "$(pass $? "launch stopped: $([ "$stopped" -eq 0 ] && echo yes || echo no) (REQUIRED process [master] has died: $died); ${resumed:-not resumed}; log: $whole")"

# --- a full disk under a checkpoint: the previous one survives, the error is clear ------------------
# A 40 MB tmpfs holds one checkpoint (about 26 MB: weights and Adam's state) but not a second
# beside it while it is written.
mkdir -p "$dir/small"
if mount -t tmpfs -o size=40m tmpfs "$dir/small" 2> /dev/null; then
  full=(roslaunch -p "$port" hideseek_world train.launch num_arenas:=4 hider_threads:=1 steps:=40960
    checkpoint_interval:=5 output_dir:="$dir/small/run")
  timeout 600 "${full[@]}" > "$dir/full.log" 2>&1
  line=$(grep -F "[FATAL]" "$dir/full.log" | head -n 1 | sed 's/\x1b\[[0-9;]*m//g; s/|/\\|/g' | cut -c1-200)
  survivor=$(/usr/bin/python3 -c 'import zipfile, sys; zipfile.ZipFile(sys.argv[1]).testzip() is None and print("readable")' \
    "$dir/small/run/checkpoint.pt" 2> /dev/null)
  leftovers=$(ls "$dir/small/run" | grep -c "tmp" || true)
  # Space again (the run moved to a disk with room): the same command resumes from the checkpoint
  # that survived.
  cp -r "$dir/small/run" "$dir/moved"
  umount "$dir/small"
  timeout 600 roslaunch -p "$port" hideseek_world train.launch num_arenas:=4 hider_threads:=1 steps:=40960 \
    checkpoint_interval:=5 output_dir:="$dir/moved" > "$dir/full2.log" 2>&1
  resumed=$(grep -o "resumed at step [0-9]*" "$dir/full2.log" | head -n 1)
  echo "$line" | grep -q "No space left on device" && [ "$survivor" = readable ] && [ "$leftovers" = 0 ] && [ -n "$resumed" ]
  row full_disk_checkpoint "\`train.launch\` into a 40 MB tmpfs: the second checkpoint cannot be written; then the run moved to a disk with room and the same command" "the hider stops with an error naming the file and the cause; the previous checkpoint survives intact, no temporary file is left; the same command resumes from it" "$(pass $? "${line:-no FATAL line}; previous checkpoint: ${survivor:-unreadable}; temporary files left: $leftovers; ${resumed:-not resumed}")"
else
  row full_disk_checkpoint "\`train.launch\` into a small tmpfs" "the previous checkpoint survives" "**not run**: mounting a tmpfs needs CAP_SYS_ADMIN"
fi

# --- a truncated run registry -------------------------------------------------------------------
hider_with_registry() {  # registry file, log
  timeout 30 rosrun hideseek_hider hider_node __name:=hider _game_config:="$PWD/config/game.yaml" \
    _variant_config:="$PWD/config/variants/basic.yaml" _policy:=shipped _policy_registry:="$1" > "$2" 2>&1
}
roscore -p "$port" > "$dir/roscore.log" 2>&1 &
core=$!
sleep 3
cut_at=$(grep -n "^  weights: basic.pt" policies/policies.yaml | cut -d: -f1)
head -n $((cut_at - 6)) policies/policies.yaml > "$dir/trunc_registry.yaml"  # cut inside the shipped run's entry
head -c "$(($(grep -b "^  weights: basic.pt" policies/policies.yaml | cut -d: -f1) + 12))" policies/policies.yaml > "$dir/trunc_registry2.yaml"  # inside its value
hider_with_registry "$dir/trunc_registry.yaml" "$dir/reg1.log"
line1=$(grep -E "\[ ?(FATAL|WARN)\]" "$dir/reg1.log" | head -n 1 | sed 's/\x1b\[[0-9;]*m//g; s/|/\\|/g' | cut -c1-200)
hider_with_registry "$dir/trunc_registry2.yaml" "$dir/reg2.log"
line2=$(grep -E "\[ ?(FATAL|WARN)\]" "$dir/reg2.log" | head -n 1 | sed 's/\x1b\[[0-9;]*m//g; s/|/\\|/g' | cut -c1-200)
kill -INT "$core"; wait "$core" 2> /dev/null
echo "$line1" | grep -q "trunc_registry.yaml" && echo "$line2" | grep -q "trunc_registry2.yaml"
row truncated_registry "policies.yaml cut at a line inside the shipped run's entry, and inside its weights value; a hider asked for the shipped policy" "refused or warned with the registry's file named; never a wrong policy played silently" "$(pass $? "line cut: $line1; value cut: $line2")"

{
  echo "| case | done | expected | outcome |"
  echo "| --- | --- | --- | --- |"
  printf '%s\n' "${rows[@]}"
} > "$report"
rm -rf "$dir"
