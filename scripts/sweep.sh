#!/usr/bin/env bash
# The sweep's queue: trains every missing run of config/sweep.yaml (variants x training seeds,
# seed-major) from a git worktree built at the pinned commit, evaluates each run the moment it
# finishes (seeds 0-99, greedy and sampled) and records it into this checkout (docs/runs/<run>/
# and policies/policies.yaml), ready to commit. Runs resume from their checkpoints.
#
# usage: scripts/sweep.sh [COMMAND]
#   start    (default) start the queue in the background (it builds the worktree first when needed)
#            and return; a queue already running is left alone
#   run      the queue in the foreground (what start runs)
#   build    only create and build the worktree at the pin
#   analyze  the per-run analysis (scripts/analyze_run.sh) of every done run that lacks it and
#            whose weights are on this machine (the t-SNE alone where only that is missing)
#   ship     ship every variant's median sweep run into policies/ (the queue does it as each run
#            ends), where its weights are on this machine
#   retrain RUN ...  train again, after every other run of the queue, done runs whose weights are
#            not on this machine (lost with a change of machine): the run a variant must ship
#            (scripts/sweep.sh ship names it). The retrain is a run of its own, <run>_retrain
#            (draw: retrain, retrain_of: <run> in the registry), recorded beside its first draw:
#            Table 2 and the claims count first draws only, and the retrain may ship. From the
#            same pin on the same kind of CPU it comes out as the first draw did; on another kind
#            the bf16 kernels can sum in another order, and it is a new draw of its seed
#   status   the pin, and every run in queue order: done (with its evaluations, whether it is
#            analysed and whether its weights are on this machine), training (its steps),
#            partial (a checkpoint) or missing; then the runs queued for retraining and the
#            order in which the queue starts what is left
#   pause    SIGSTOP every training run (for make bench, timing work, make test); the paused time
#            is recorded apart from the run's wall time
#   resume   SIGCONT them
#   stop     stop the queue and its runs (each resumes from its last checkpoint at the next start)
#   hold CMD ...  pause a running queue, run CMD, resume it (whatever CMD's exit); with no queue
#            running, just CMD. make bench and make test run under it: benchmarks are taken only
#            while the sweep is paused
#
# SWEEP_DIR (default ~/hideseek_sweep) holds the worktree (tree/), the runs' weights and
# checkpoints (runs/<run>/), the logs (logs/) and the queue's state. SWEEP_<KEY> overrides a key of
# config/sweep.yaml (SWEEP_SEEDS="0 1 2 3 4", SWEEP_JOBS=2, SWEEP_VARIANTS="basic slowerhider").
# SWEEP_RECORD_ROOT (default this checkout) is the checkout that receives the records and whose
# registry says which runs are done.
set -euo pipefail
# Python must not leave __pycache__ in the pinned worktree (it would look modified).
export PYTHONDONTWRITEBYTECODE=1
# The queue runs from a copy of this script (start makes it), so that editing the checkout's copy
# never changes a running queue; SWEEP_CHECKOUT then names the checkout.
cd "${SWEEP_CHECKOUT:-$(dirname "$0")/..}"
main=$PWD
records=$(realpath "${SWEEP_RECORD_ROOT:-$main}")
[ -f "$records/policies/policies.yaml" ] || { echo "sweep: SWEEP_RECORD_ROOT: no policies/policies.yaml in $records" >&2; exit 2; }
source scripts/env.sh
dir=$(realpath -m "${SWEEP_DIR:-$HOME/hideseek_sweep}")
tree=$dir/tree
runs=$dir/runs
state=$dir/state
case "${1:-start}" in start|run|build|analyze|pause|stop|retrain) mkdir -p "$runs" "$state" "$dir/logs" ;; esac

say() { echo "sweep $(date +%H:%M:%S): $*"; }
die() { echo "sweep: $*" >&2; exit 2; }

# config/sweep.yaml, with SWEEP_<KEY> overrides; lists come out space-separated.
setting() {
  local key=$1 env_name
  env_name=SWEEP_$(echo "$1" | tr '[:lower:]' '[:upper:]')
  if [ -n "${!env_name:-}" ]; then echo "${!env_name}"; return; fi
  /usr/bin/python3 - "$main/config/sweep.yaml" "$key" <<'PY'
import sys, yaml
with open(sys.argv[1]) as f:
    c = yaml.safe_load(f) or {}
if sys.argv[2] not in c:
    sys.exit("sweep: config/sweep.yaml has no key %r" % sys.argv[2])
v = c[sys.argv[2]]
print(" ".join(str(x) for x in v) if isinstance(v, list) else v)
PY
}
pin=$(setting commit)
seeds=$(setting seeds)
steps=$(setting steps)
network=$(setting network)
precision=$(setting precision)
jobs=$(setting jobs)
threads=$(setting hider_threads)
port_base=$(setting port)
for n in "$steps" "$jobs" "$threads" "$port_base" $seeds; do
  [ "$n" -ge 0 ] 2> /dev/null || die "config/sweep.yaml: '$n' is not a whole number (steps, jobs, hider_threads, port, seeds)"
done
[ "$jobs" -ge 1 ] || die "config/sweep.yaml: jobs must be >= 1"
[ "$threads" -ge 1 ] || die "config/sweep.yaml: hider_threads must be >= 1"
variants=$(setting variants)
if [ "$variants" = all ]; then variants=$(/usr/bin/python3 scripts/hideseek_registry.py variants --paper-order | tr '\n' ' '); fi
known=$(/usr/bin/python3 scripts/hideseek_registry.py variants | tr '\n' ' ')
for v in $variants; do
  case " $known " in *" $v "*) ;; *) die "config/sweep.yaml: variants: no variant '$v' in config/variants" ;; esac
done
run_name() { if [ "$network" = ff ]; then echo "${1}_seed$2"; else echo "${1}_${network}_seed$2"; fi; }

# The queue in seed-major order: "NAME VARIANT SEED" lines.
queue() {
  local s v
  for s in $seeds; do for v in $variants; do echo "$(run_name "$v" "$s") $v $s"; done; done
}

# The runs queued for retraining (scripts/sweep.sh retrain), as "NAME_retrain VARIANT SEED retrain"
# lines: a retrain is a run of its own, <run>_retrain, recorded beside its first draw (which Table 2
# and the claims keep counting). One is still wanted while neither its first draw's weights nor its
# own are here and it is not done.
retrain_queue() {
  local name variant seed
  [ -s "$state/retrain" ] || return 0
  while read -r name variant seed; do
    grep -qx "$name" "$state/retrain" && echo "${name}_retrain $variant $seed retrain"
  done < <(queue)
}
wants_retrain() {
  local first=${1%_retrain}
  grep -qx "$first" "$state/retrain" 2> /dev/null && [ ! -s "$runs/$first/policy.pt" ] && [ ! -s "$runs/$1/policy.pt" ] \
    && ! is_done "$1"
}

# The runs the queue would start, in order: every run not done, seed-major, then every run queued
# for retraining. "NAME VARIANT SEED" lines.
to_train() {
  local name variant seed kind
  while read -r name variant seed kind; do
    if [ "$kind" = retrain ]; then wants_retrain "$name" || continue
    else is_done "$name" && continue; fi
    echo "$name $variant $seed"
  done < <(queue; retrain_queue)
}

# A run is done when this checkout records it as a sweep run (its note, which the queue writes
# last) with all its steps, both evaluations and its trajectories. A run of the same name that
# another command trained is not a sweep run: the queue trains it again.
SWEEP_NOTE="sweep run (config/sweep.yaml)"
recorded_steps() {
  /usr/bin/python3 -c 'import sys; sys.path.insert(0, "scripts"); import hideseek_registry as r
e = r.runs(sys.argv[2]).get(sys.argv[1])
print(e.get("steps", 0) if e and str(e.get("note", "")).startswith(sys.argv[3]) else 0)' \
    "$1" "$records/policies/policies.yaml" "$SWEEP_NOTE"
}
is_done() {
  [ "$(recorded_steps "$1")" -ge "$steps" ] && [ -s "$records/docs/runs/$1/evaluation.csv" ] \
    && [ -s "$records/docs/runs/$1/sampled/evaluation.csv" ] && [ -s "$records/docs/runs/$1/trajectories.png" ]
}
analysed() { [ -s "$records/docs/runs/$1/analysis/behaviour.csv" ]; }
has_tsne() { [ -s "$records/docs/runs/$1/analysis/tsne_neighbours.csv" ]; }
has_memoryless() { [ -s "$records/docs/runs/$1/analysis/memoryless/behaviour.csv" ]; }

# The process tree under a PID (itself first).
tree_pids() {
  local pid=$1 child
  echo "$pid"
  for child in $(ps -o pid= --ppid "$pid" 2> /dev/null); do tree_pids "$child"; done
}
alive() { [ -n "${1:-}" ] && kill -0 "$1" 2> /dev/null; }
# A queue runs while its lock is held (a PID file alone could name a process that has since
# reused the PID); its runs' PIDs count only then.
queue_running() { [ -e "$state/queue.lock" ] && ! flock -n "$state/queue.lock" true 2> /dev/null; }
queue_pid() { if queue_running; then cat "$state/queue.pid" 2> /dev/null || echo "?"; fi; }
job_pids() {
  local f p
  queue_running || return 0
  for f in "$state"/job.*; do [ -e "$f" ] || continue; p=$(cat "$f"); alive "$p" && echo "$p"; done
  true
}
port_free() { ! (exec 3<> "/dev/tcp/127.0.0.1/$1") 2> /dev/null; }

native_bf16() { grep -qwE 'avx512_bf16|amx_bf16' /proc/cpuinfo; }

# The worktree at the pinned commit, built (catkin_make, Release, no tests) once per commit.
prepare_tree() {
  [ "$pin" != PIN ] || die "config/sweep.yaml: commit is not set (pin a commit of main)"
  git rev-parse --verify -q "$pin^{commit}" > /dev/null || die "config/sweep.yaml: commit $pin is not in this repository (fetch it first)"
  pin=$(git rev-parse "$pin")
  git worktree prune
  if [ ! -e "$tree/.git" ]; then
    say "creating the worktree $tree at $pin"
    git worktree add --detach "$tree" "$pin" > /dev/null
  elif [ "$(git -C "$tree" rev-parse HEAD)" != "$pin" ]; then
    say "moving the worktree from $(git -C "$tree" rev-parse --short=12 HEAD) to the new pin $pin"
    git -C "$tree" checkout -q --detach "$pin"
  fi
  [ -z "$(git -C "$tree" status --porcelain)" ] || die "the worktree $tree has uncommitted changes; a sweep run trains from a clean tree (git -C $tree status)"
  if [ "$(cat "$state/built" 2> /dev/null || true)" != "$pin" ]; then
    say "building the worktree at $pin (log: $dir/logs/build.log)"
    (cd "$tree" && source scripts/env.sh && catkin_make -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 \
      -DPython3_EXECUTABLE=/usr/bin/python3 -DCATKIN_ENABLE_TESTING=OFF -j"$(nproc)") > "$dir/logs/build.log" 2>&1 \
      || die "the worktree's build failed: $dir/logs/build.log"
    echo "$pin" > "$state/built"
  fi
}

# One run: train (or resume), export, record and evaluate into this checkout.
job() {
  local name=$1 variant=$2 seed=$3 slot=$4 port rc paused draw=()
  # A retrain records what it is, and the first draw it repeats.
  case $name in *_retrain) draw=(draw=retrain retrain_of="${name%_retrain}") ;; esac
  port=$((port_base + 10 * slot))
  for p in "$port" $((port + 1)) $((port + 2)); do
    port_free "$p" || { say "$name: port $p is in use; not started"; return 3; }
  done
  [ -z "$(git -C "$tree" status --porcelain)" ] || { say "$name: the worktree is not clean; not started"; return 3; }
  say "$name: training (slot $slot, port $port, $threads learner threads; log $dir/logs/$name.log)"
  set +e
  RECORD_ROOT=$records PRECISION=$precision HIDER_THREADS=$threads ROS_PORT=$port HIDESEEK_PORT=$((port + 1)) \
    EVAL_MODES="greedy sampled" PAUSED_FILE=$runs/$name/paused_s \
    "$tree/scripts/train_variant.sh" "$variant" "$seed" "$steps" "$runs" "$network" "$name" > "$dir/logs/$name.log" 2>&1
  rc=$?
  set -e
  if [ $rc -eq 0 ]; then
    # paused_s again, as train_variant.sh records it (none when 0: `paused_s=` removes the field),
    # so that a retrained run keeps no paused time of its first training: train_variant.sh at pins
    # before 2026-11-27 left it. Redundant once the pin is later than that.
    paused=$(head -n 1 "$runs/$name/paused_s" 2> /dev/null || true)
    paused=${paused%.*}
    [ "${paused:-0}" != 0 ] || paused=
    /usr/bin/python3 scripts/hideseek_registry.py --registry "$records/policies/policies.yaml" record "$name" \
      note="$SWEEP_NOTE, pinned at $(git rev-parse --short=12 "$pin")" paused_s="$paused" "${draw[@]}"
    analyze "$name" || true
    ship "$variant"
    say "$name: done: $(grep 'evaluate_run:.*(greedy)\|evaluate_run:.*(sampled)' "$dir/logs/$name.log" | sed 's/.*(\(greedy\|sampled\)): \([^(]*\).*/\1 \2/' | paste -sd ';')"
  else
    say "$name: failed (exit $rc); see $dir/logs/$name.log"
  fi
  return $rc
}

# The per-run analysis (scripts/analyze_run.sh of the records' checkout, with its own build):
# probes on the shared probe set and behaviour, into docs/runs/<run>/analysis/. Its failure does
# not undo the run: `scripts/sweep.sh analyze` retries every done run whose weights are here.
analyze() {
  local name=$1
  [ -s "$runs/$name/policy.pt" ] || { say "$name: no weights in $runs/$name: not analysed"; return 1; }
  if RECORD_ROOT=$records "$records/scripts/analyze_run.sh" "$name" "$runs/$name/policy.pt" >> "$dir/logs/$name.analysis.log" 2>&1; then
    say "$name: analysed into $records/docs/runs/$name/analysis"
  else
    say "$name: the analysis failed; see $dir/logs/$name.analysis.log"
    return 1
  fi
}

# Ships the variant's median sweep run (hideseek_registry.py ship-median) into the records'
# policies/, from its weights in $runs; where the median run's weights are not on this machine the
# shipped run stays, and the message names the run to retrain.
ship() {
  local out
  if out=$(/usr/bin/python3 "$records/scripts/hideseek_registry.py" --registry "$records/policies/policies.yaml"       ship-median "$1" --weights-dir "$runs" --network "$network" 2>&1); then
    say "${out#hideseek_registry: }"
  else
    say "${out#hideseek_registry: }"
  fi
}

# One part of a run's analysis alone (tsne or memoryless), while its weights are here.
analyze_part() {
  if RECORD_ROOT=$records "$records/scripts/analyze_run.sh" "--$2-only" "$1" "$runs/$1/policy.pt" \
    >> "$dir/logs/$1.analysis.log" 2>&1; then
    say "$1: $2 into $records/docs/runs/$1/analysis"
  else
    say "$1: the $2 part failed; see $dir/logs/$1.analysis.log"
    return 1
  fi
}

analyze_all() {
  local name n=0
  while read -r name _ _; do
    is_done "$name" || continue
    if ! analysed "$name"; then
      if analyze "$name"; then n=$((n + 1)); fi
      continue
    fi
    [ -s "$runs/$name/policy.pt" ] || continue
    # Analysed before the per-run t-SNE or a GRU's memoryless ablation existed, or the part failed.
    if ! has_tsne "$name" && analyze_part "$name" tsne; then n=$((n + 1)); fi
    if [ "$network" = gru ] && ! has_memoryless "$name" && analyze_part "$name" memoryless; then n=$((n + 1)); fi
  done < <(queue; retrain_queue)
  say "$n runs or parts of runs analysed"
}

run_queue() {
  exec 9> "$state/queue.lock"
  flock -n 9 || die "a queue is already running (pid $(cat "$state/queue.pid" 2> /dev/null))"
  echo $$ > "$state/queue.pid"
  rm -f "$state"/job.* "$state/stop"
  if [ -e "$state/paused" ]; then say "a pause from an earlier queue is cleared (its runs were stopped)"; rm -f "$state/paused"; fi
  native_bf16 || die "this CPU has no native bf16 (avx512_bf16 or amx_bf16): sweep runs train only in bf16 on such a CPU; evaluate and analyse here instead"
  prepare_tree
  say "queue: $(queue | wc -l) runs (seeds $seeds; $steps steps; $network; $precision; $jobs at once, $threads learner threads each) at $(git rev-parse --short=12 "$pin")"
  trap 'say "stopping"; for p in $(job_pids); do kill -INT $(tree_pids "$p") 2> /dev/null || true; done; wait; rm -f "$state/queue.pid"; exit 143' INT TERM
  # The launch lock: a pause waits while a run is being started, so no run starts unseen by it.
  exec 8> "$state/launch.lock"
  declare -A slot_of=() failed=()
  local name variant seed slot free started
  while [ ! -e "$state/stop" ]; do
    started=0
    if [ ! -e "$state/paused" ] && [ "${#slot_of[@]}" -lt "$jobs" ]; then
      flock 8
      [ ! -e "$state/paused" ] && while read -r name variant seed; do
        [ -z "${slot_of[$name]:-}" ] && [ -z "${failed[$name]:-}" ] || continue
        for ((slot = 0; slot < jobs; slot++)); do
          free=1
          for n in "${!slot_of[@]}"; do [ "${slot_of[$n]}" != "$slot" ] || free=0; done
          [ $free = 0 ] || break
        done
        job "$name" "$variant" "$seed" "$slot" &
        echo $! > "$state/job.$name"
        slot_of[$name]=$slot
        started=1
        break
      done < <(to_train)
      flock -u 8
    fi
    [ $started = 1 ] && continue
    if [ "${#slot_of[@]}" = 0 ]; then
      if [ ! -e "$state/paused" ]; then
        local left=0
        while read -r name _ _; do is_done "$name" || left=$((left + 1)); done < <(queue)
        while read -r name _ _ _; do wants_retrain "$name" && left=$((left + 1)); done < <(retrain_queue)
        if [ $left = 0 ]; then say "every run of the queue is done"; else say "nothing left to start: $left runs failed (see the logs); start again to retry them"; fi
        break
      fi
      sleep 5
      continue
    fi
    sleep 5
    for name in "${!slot_of[@]}"; do
      if ! alive "$(cat "$state/job.$name")"; then
        wait "$(cat "$state/job.$name")" || failed[$name]=1
        rm -f "$state/job.$name"
        unset "slot_of[$name]"
      fi
    done
  done
  rm -f "$state/queue.pid"
}

status() {
  local name variant seed f steps_now
  echo "sweep: pin $(git rev-parse --short=12 "$pin" 2> /dev/null || echo "$pin") (config/sweep.yaml), worktree $tree, runs $runs"
  echo "sweep: queue $(if [ -n "$(queue_pid)" ]; then echo "running (pid $(queue_pid))"; else echo "not running"; fi)$([ -e "$state/paused" ] && echo ", PAUSED since $(date -d @"$(cat "$state/paused")" +%H:%M:%S)")"
  native_bf16 || echo "sweep: this CPU has no native bf16: the queue will not train here"
  while read -r name variant seed _; do
    if [ -e "$state/job.$name" ] && alive "$(cat "$state/job.$name")"; then
      steps_now=$(tail -n 1 "$runs/$name/training_log.csv" 2> /dev/null | cut -d, -f2,3 || true)
      printf '%-34s training  %s steps of %s, %s s%s\n' "$name" "${steps_now%,*}" "$steps" "${steps_now#*,}" \
        "$(wants_retrain "$name" && echo " (retraining)")"
    elif is_done "$name"; then
      printf '%-34s done      greedy %s, sampled %s (living steps, success); %s; %s\n' "$name" \
        "$(tail -n 1 "$records/docs/runs/$name/evaluation.csv" | cut -d, -f4,5 | tr , /)" \
        "$(tail -n 1 "$records/docs/runs/$name/sampled/evaluation.csv" | cut -d, -f4,5 | tr , /)" \
        "$(analysed "$name" && echo analysed || echo "NOT analysed")" \
        "$([ -s "$runs/$name/policy.pt" ] && echo "weights in $runs/$name" || echo "weights not on this machine")"
    elif [ -s "$runs/$name/checkpoint.pt" ]; then
      printf '%-34s partial   checkpoint in %s (resumes at the next start)\n' "$name" "$runs/$name"
    else
      printf '%-34s missing\n' "$name"
    fi
  done < <(queue; retrain_queue)
  local queued=() order=()
  while read -r name _ _ _; do wants_retrain "$name" && queued+=("${name%_retrain}"); done < <(retrain_queue)
  [ ${#queued[@]} = 0 ] || echo "sweep: queued for retraining (weights lost; after every other run): ${queued[*]}"
  while read -r name _ _; do order+=("$name"); done < <(to_train)
  echo "sweep: left to train, in order: ${order[*]:-nothing}"
}

# Queues done runs whose weights are not on this machine for retraining after every other run.
retrain() {
  [ $# -gt 0 ] || die "retrain: name the runs to train again (scripts/sweep.sh ship names the ones a variant needs)"
  local name found
  for name in "$@"; do
    found=$(queue | awk -v n="$name" '$1 == n' || true)
    [ -n "$found" ] || die "retrain: '$name' is not a run of the queue (scripts/sweep.sh status lists them)"
    is_done "$name" || die "retrain: '$name' is not done: the queue trains it anyway"
    if [ -s "$runs/$name/policy.pt" ]; then echo "sweep: $name: its weights are here ($runs/$name/policy.pt); nothing to retrain"; continue; fi
    grep -qx "$name" "$state/retrain" 2> /dev/null || echo "$name" >> "$state/retrain"
    echo "sweep: $name queued for retraining, after every other run of the queue, as ${name}_retrain beside its first draw"
  done
  [ -z "$(queue_pid)" ] || echo "sweep: the running queue takes it up when a slot frees"
}

pause() {
  [ ! -e "$state/paused" ] || { echo "sweep: already paused"; return 0; }
  exec 7> "$state/launch.lock"
  flock 7
  date +%s > "$state/paused"
  local f p n=0
  : > "$state/paused.runs"
  if queue_running; then
    for f in "$state"/job.*; do
      [ -e "$f" ] || continue
      p=$(cat "$f")
      alive "$p" || continue
      kill -STOP $(tree_pids "$p") 2> /dev/null || true
      echo "${f##*/job.} $p" >> "$state/paused.runs"
      n=$((n + 1))
    done
  fi
  flock -u 7
  echo "sweep: paused ($n runs held; the queue starts no new run until 'scripts/sweep.sh resume')"
}

# SIGCONT to the runs the pause held; `book` adds the held time to each one's paused_s (not when
# the runs are being stopped: they restart from a checkpoint older than the pause).
resume() {
  [ -e "$state/paused" ] || { echo "sweep: not paused"; return 0; }
  local book=${1:-book} since p name held
  since=$(cat "$state/paused")
  held=$(($(date +%s) - since))
  while read -r name p; do
    alive "$p" || continue
    kill -CONT $(tree_pids "$p") 2> /dev/null || true
    [ "$book" = book ] || continue
    mkdir -p "$runs/$name"
    echo $(($(cat "$runs/$name/paused_s" 2> /dev/null || echo 0) + held)) > "$runs/$name/paused_s"
  done < "$state/paused.runs"
  rm -f "$state/paused" "$state/paused.runs"
  echo "sweep: resumed after $held s"
}

stop() {
  local q p
  q=$(queue_pid)
  touch "$state/stop"
  [ ! -e "$state/paused" ] || resume no-book > /dev/null
  for p in $(job_pids); do kill -INT $(tree_pids "$p") 2> /dev/null || true; done
  [ -z "$q" ] || kill -TERM "$q" 2> /dev/null || true
  for _ in $(seq 60); do [ -z "$(queue_pid)$(job_pids)" ] && break; sleep 1; done
  for p in $(job_pids); do kill -KILL $(tree_pids "$p") 2> /dev/null || true; done
  echo "sweep: stopped; 'scripts/sweep.sh start' resumes each run from its last checkpoint"
}

case "${1:-start}" in
  start)
    if [ -n "$(queue_pid)" ]; then echo "sweep: the queue is already running (pid $(queue_pid)); scripts/sweep.sh status"; exit 0; fi
    native_bf16 || die "this CPU has no native bf16 (avx512_bf16 or amx_bf16): sweep runs train only in bf16 on such a CPU; evaluate and analyse here instead"
    cp "$main/scripts/sweep.sh" "$state/queue.sh"
    SWEEP_CHECKOUT=$main nohup setsid "$state/queue.sh" run >> "$dir/logs/queue.log" 2>&1 < /dev/null &
    echo "sweep: queue started (log: $dir/logs/queue.log; scripts/sweep.sh status)"
    ;;
  run) run_queue ;;
  build) prepare_tree ;;
  analyze) analyze_all ;;
  ship) for v in $variants; do ship "$v"; done ;;
  status) status ;;
  pause) pause ;;
  resume) resume ;;
  stop) stop ;;
  retrain) shift; retrain "$@" ;;
  hold)
    shift
    [ $# -gt 0 ] || die "hold: name the command to run while the sweep is paused"
    if [ -z "$(queue_pid)" ] || [ -e "$state/paused" ]; then exec "$@"; fi
    pause
    trap 'resume' EXIT
    trap 'exit 130' INT TERM
    rc=0
    "$@" || rc=$?
    exit $rc
    ;;
  *) die "unknown command '$1' (start, run, build, analyze, ship, status, pause, resume, stop, retrain, hold)" ;;
esac
