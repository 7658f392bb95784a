#!/usr/bin/env bash
# The install space, as a Docker image or a binary package would use it. usage: install_space_test.sh XUNIT_OUTPUT
# 1. A copy of the workspace's sources builds and installs into a temporary prefix (catkin_make
#    install, tests off); then the copy is deleted.
# 2. Nothing installed names the copy or the checkout (every file of the prefix is searched).
# 3. With only the prefix's setup.bash sourced (a clean environment: the checkout is on no path),
#    basic.launch plays a lockstep game with the shipped policy to finished episodes while recording
#    a bag, evaluate.launch evaluates the shipped basic policy, and replay.launch replays the bag.
#    examples/cpp_hider, a package of one's own, builds on the prefix alone and, as an external
#    hider, plays the shipped policy's episodes exactly.
# 4. Every file those graphs open (strace) lies outside the checkout; a failure names each file.
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
out=$1
root="$(cd "$(dirname "$0")/.." && pwd)"
workspace="$(cd "$root/../.." && pwd)"
tmp=$(mktemp -d /tmp/hideseek_install_test.XXXXXX)
copy=$tmp/ws
prefix=$tmp/prefix
port=$((12200 + RANDOM % 100))  # the sweep uses 12100-12112, the fault campaign 12400-12499
failures=()
say() { echo "install_space_test: $*"; }

# --- 1. build a copy and install it ---------------------------------------------------------------
mkdir -p "$copy"
cp -a "$workspace/src" "$workspace/config" "$workspace/policies" "$copy/"
say "building a copy of the workspace into $prefix (about 5 min on 2 cores)"
started=$(date +%s)
if ! env -i HOME="$HOME" PATH=/usr/bin:/bin LANG=C.UTF-8 bash -c "cd '$copy' && catkin_make install \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX='$prefix' -DPYTHON_EXECUTABLE=/usr/bin/python3 \
    -DCATKIN_ENABLE_TESTING=OFF -j$(nproc)" > "$tmp/build.log" 2>&1; then
  failures+=("catkin_make install failed: $(tail -n 5 "$tmp/build.log" | tr '\n' ' ')")
fi
say "built and installed in $(( $(date +%s) - started )) s"
rm -rf "$copy"

# --- 2. no installed text file names a source tree -------------------------------------------------
# (Launch files, YAML, CMake, Python, setup files: what a node or tool would read a path from.
# Compiled files keep their sources' names for log lines and tracebacks; step 4 checks that
# nothing opens them.)
for tree in "$copy" "$workspace"; do
  while IFS= read -r file; do
    failures+=("${file#"$prefix"/} names the source tree $tree")
  done < <(grep -rlIF "$tree/" "$prefix" 2>/dev/null)
done

# --- 3. the graphs, from the prefix alone, each under strace ---------------------------------------
# Runs roslaunch in a clean environment with only the prefix sourced; every open of a file goes to
# $tmp/trace.NAME.*. LIMIT only catches a hang: it is minutes, never what the graph needs on a slow
# CPU. With UNTIL ("PATTERN COUNT"), the launch is stopped with SIGINT, as Ctrl-C would, once its log
# holds COUNT lines matching PATTERN: the test waits for what the game does, not for a clock.
launch() {
  local name=$1 limit=$2 until=$3
  shift 3
  : > "$tmp/$name.log"  # exists before the watch below first reads it
  # Started in $tmp, so that no process inherits the checkout as its working directory. The log is a
  # file, where stdout is block-buffered: rosconsole's ROSCONSOLE_STDOUT_LINE_BUFFERED (and Python's
  # PYTHONUNBUFFERED) make each node write its lines as it logs them, so the watch below sees them.
  (cd "$tmp" && exec env -i HOME="$HOME" PATH=/usr/bin:/bin LANG=C.UTF-8 ROSCONSOLE_STDOUT_LINE_BUFFERED=1 \
    PYTHONUNBUFFERED=1 bash -c "source '$prefix/setup.bash' && \
    exec strace -f -qq --seccomp-bpf -e trace=open,openat,execve,stat,newfstatat -e signal=none \
    -o '$tmp/trace.$name' timeout -s INT $limit roslaunch -p $port hideseek_world $*") > "$tmp/$name.log" 2>&1 &
  local job=$!
  if [ -n "$until" ]; then
    local pattern=${until% *} count=${until##* }
    local seen
    while kill -0 $job 2> /dev/null; do
      seen=$(grep -c "$pattern" "$tmp/$name.log" 2> /dev/null)
      [ "${seen:-0}" -ge "$count" ] && break
      sleep 0.5
    done
    # strace's child is `timeout`, which passes SIGINT on to roslaunch as its own limit would.
    pkill -INT -f "^timeout -s INT $limit roslaunch -p $port hideseek_world" 2> /dev/null
  fi
  wait $job
}
where=$(env -i HOME="$HOME" PATH=/usr/bin:/bin bash -c "source '$prefix/setup.bash' && rospack find hideseek_world" 2>&1)
[ "$where" = "$prefix/share/hideseek_world" ] || failures+=("rospack finds hideseek_world at '$where', not in the prefix")

say "the Python module from the prefix: hideseek.make_vec steps a game"
py=$(cd "$tmp" && env -i HOME="$HOME" PATH=/usr/bin:/bin LANG=C.UTF-8 bash -c "source '$prefix/setup.bash' && \
  /usr/bin/python3 -c 'import hideseek; e = hideseek.make_vec(\"basic\", num_envs=2); o, _ = e.reset(seed=0); \
o, *_ = e.step([1, 1]); print(hideseek.__file__, o.shape)'" 2>&1)
case "$(echo "$py" | tail -n 1)" in
  "$prefix"/*"(2, 84, 84, 3)") ;;
  *) failures+=("the installed hideseek module did not step a game: $(echo "$py" | tail -n 2 | tr '\n' ' ')") ;;
esac

# Two finished episodes, however long this CPU takes to play them (a 1000-step episode of the
# shipped policy took 27 s under strace on a 2-core Intel Xeon); 600 s only catches a hang.
say "basic.launch (lockstep, shipped policy, recording a bag): until 2 episodes have finished"
started=$(date +%s)
launch basic 600 "episode [0-9]* (seed [0-9]*): 2" basic.launch mode:=lockstep num_arenas:=2 record:=true bag_dir:="$tmp/bags"
episodes=$(grep -c "episode [0-9]* (seed [0-9]*): " "$tmp/basic.log")
say "basic.launch finished $episodes episodes and was stopped after $(( $(date +%s) - started )) s"
[ "$episodes" -ge 2 ] || failures+=("basic.launch finished $episodes episodes before it stopped or 600 s passed: $(grep -m 3 -E 'ERROR|FATAL|rror' "$tmp/basic.log" | tr '\n' ' ')")
grep -m 4 "episode [0-9]* (seed [0-9]*): " "$tmp/basic.log"

say "evaluate.launch (the shipped basic policy, 4 episodes)"
launch evaluate 600 "" evaluate.launch variant:=basic policy:=shipped episodes:=4 output_dir:="$tmp/eval"
rows=$(tail -n +2 "$tmp/eval/episodes.csv" 2>/dev/null | wc -l)
[ "$rows" = 4 ] || failures+=("evaluate.launch wrote $rows episodes, not 4: $(grep -m 3 -E 'ERROR|FATAL' "$tmp/evaluate.log" | tr '\n' ' ')")
named=$(tail -n 1 "$tmp/eval/evaluation.csv" 2>/dev/null | cut -d, -f2)
case "$named" in
  "$prefix/share/hideseek_world/policies/"*) ;;
  *) failures+=("evaluate.launch's shipped policy is '$named', not a file of the prefix") ;;
esac
cat "$tmp/eval/evaluation.md" 2>/dev/null

# A package of one's own on top of the prefix (examples/cpp_hider: a plain catkin CMakeLists that
# names hideseek_hider and nothing of libtorch), built in a clean environment, then playing the
# shipped basic policy through the library as an external hider: the same 4 episodes as above.
say "examples/cpp_hider built on the prefix alone, then evaluated as policy:=external"
mkdir -p "$tmp/mine/src"
cp -a "$workspace/examples/cpp_hider" "$tmp/mine/src/my_hider"
if ! env -i HOME="$HOME" PATH=/usr/bin:/bin LANG=C.UTF-8 bash -c "source '$prefix/setup.bash' && cd '$tmp/mine' && \
    catkin_make -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 -j$(nproc)" > "$tmp/mine.log" 2>&1; then
  failures+=("examples/cpp_hider did not build on the prefix: $(grep -m 3 -E 'rror' "$tmp/mine.log" | tr '\n' ' ')")
else
  (cd "$tmp" && exec env -i HOME="$HOME" PATH=/usr/bin:/bin LANG=C.UTF-8 ROSCONSOLE_STDOUT_LINE_BUFFERED=1 \
    ROS_MASTER_URI=http://localhost:$port bash -c "source '$tmp/mine/devel/setup.bash' && \
    exec timeout 600 rosrun my_hider policy_hider_node") > "$tmp/my_hider.log" 2>&1 &
  mine=$!
  launch evaluate_mine 600 "" evaluate.launch variant:=basic policy:=external episodes:=4 output_dir:="$tmp/eval_mine"
  kill $mine 2> /dev/null
  wait $mine 2> /dev/null
  cmp -s "$tmp/eval/episodes.csv" "$tmp/eval_mine/episodes.csv" ||
    failures+=("examples/cpp_hider's episodes differ from the shipped policy's: $(tr '\n' ' ' < "$tmp/eval_mine/episodes.csv" 2>/dev/null) against $(tr '\n' ' ' < "$tmp/eval/episodes.csv") ($(grep -m 2 -E 'FATAL|ERROR' "$tmp/my_hider.log" | tr '\n' ' '))")
  grep -m 1 "my_hider: playing" "$tmp/my_hider.log"
  cat "$tmp/eval_mine/evaluation.md" 2>/dev/null
fi

bag=$(ls "$tmp"/bags/*.bag 2>/dev/null | head -n 1)
if [ -z "$bag" ]; then
  failures+=("basic.launch record:=true left no closed bag in $tmp/bags")
else
  say "replay.launch ($(basename "$bag"), headless, 10x)"
  launch replay 600 "" replay.launch bag:="$bag" rviz:=false rate:=10
  status=$?
  grep -q "Done." "$tmp/replay.log" && [ $status -eq 0 ] ||
    failures+=("replay.launch exited $status without playing the bag to its end: $(tail -n 3 "$tmp/replay.log" | tr '\n' ' ')")
fi

# --- 4. nothing opened from a source tree ----------------------------------------------------------
for tree in "$copy" "$workspace"; do
  while IFS= read -r file; do
    failures+=("a node opened $file (in the source tree $tree)")
  done < <(cat "$tmp"/trace.* 2>/dev/null | grep -oE "\"$tree/[^\"]*\"" | tr -d '"' | sort -u)
done
opened=$(cat "$tmp"/trace.* 2>/dev/null | grep -oE "\"$prefix/[^\"]*\"" | sort -u | wc -l)
say "the graphs opened $opened distinct files of the prefix, none of a source tree unless listed below"

write_xunit "$out" install_space InstalledPackagesRunWithoutTheCheckout "${failures[@]}"
[ ${#failures[@]} -eq 0 ] || printf 'failure: %s\n' "${failures[@]}"
[ ${#failures[@]} -eq 0 ] && rm -rf "$tmp"
exit 0
