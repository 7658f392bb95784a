#!/usr/bin/env bash
# make fuzz: builds every fuzz target with libFuzzer, ASan and UBSan (test/sanitize/sanitize_build.sh),
# then runs each for FUZZ_SECONDS (default 120) from its committed corpus. New inputs go to
# fuzz_runs/NAME/ (not the committed corpus); a crash, hang (FUZZ_TIMEOUT s per input) or
# allocation over FUZZ_RSS_MB leaves its input in fuzz_runs/NAME/findings/. One line per target:
# executions, seconds, findings.
set -uo pipefail
cd "$(dirname "$(realpath "$0")")/../.."
SECONDS_EACH=${FUZZ_SECONDS:-120}
TARGETS=(${FUZZ_TARGETS:-config_fuzz action_batch_fuzz checkpoint_fuzz bag_fuzz})
declare -A CORPUS=([config_fuzz]=src/hideseek_game/fuzz/corpus/config
  [action_batch_fuzz]=src/hideseek_game/fuzz/corpus/action_batch
  [checkpoint_fuzz]=src/hideseek_hider/fuzz/corpus/checkpoint
  [bag_fuzz]=src/hideseek_analysis/fuzz/corpus/bag)
test/sanitize/sanitize_build.sh "${TARGETS[@]}" > build_sanitize.log 2>&1 || {
  tail -n 30 build_sanitize.log; echo "fuzz: the build failed (build_sanitize.log)"; exit 1; }
export ASAN_OPTIONS="detect_leaks=0"  # libFuzzer's -rss_limit_mb bounds memory; leaks are make test-sanitize's
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$PWD/config/sanitizers/ubsan.supp"
status=0
for t in "${TARGETS[@]}"; do
  bin=$(find devel_sanitize/lib -name "$t" -type f -executable | head -n 1)
  work="fuzz_runs/$t"
  mkdir -p "$work/corpus" "$work/findings"
  "$bin" "$work/corpus" "${CORPUS[$t]}" -max_total_time="$SECONDS_EACH" -timeout="${FUZZ_TIMEOUT:-10}" \
    -rss_limit_mb="${FUZZ_RSS_MB:-2048}" -max_len="${FUZZ_MAX_LEN:-65536}" -artifact_prefix="$work/findings/" -print_final_stats=1 \
    > "$work/log.txt" 2>&1
  rc=$?
  runs=$(grep -oE "stat::number_of_executed_units: *[0-9]+" "$work/log.txt" | grep -oE "[0-9]+$")
  findings=$(find "$work/findings" -type f | wc -l)
  echo "fuzz: $t ${runs:-?} executions in ${SECONDS_EACH} s, $findings findings (exit $rc; log $work/log.txt)"
  [ "$rc" -eq 0 ] && [ "$findings" -eq 0 ] || status=1
done
exit $status
