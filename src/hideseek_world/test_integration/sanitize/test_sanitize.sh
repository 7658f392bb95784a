#!/usr/bin/env bash
# make test-sanitize: the ROS-free cores and their gtests built with AddressSanitizer and
# UndefinedBehaviorSanitizer (clang), then run; any report fails. The suppressions for libraries we
# do not build (libtorch, Mesa) are in config/sanitizers/, each with its reason.
set -uo pipefail
cd "$(dirname "$(realpath "$0")")/../.."
TESTS=(game_core_test seeker_core_test hider_core_test episode_tally_test training_run_test teleop_test
  analysis_core_test vec_game_test config_fuzz_replay action_batch_fuzz_replay checkpoint_fuzz_replay bag_fuzz_replay)
start=$(date +%s)
test/sanitize/sanitize_build.sh "${TESTS[@]}" > build_sanitize.log 2>&1 || {
  tail -n 30 build_sanitize.log; echo "test-sanitize: the build failed (build_sanitize.log)"; exit 1; }
built=$(date +%s)
supp="$PWD/config/sanitizers"
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:abort_on_error=0"
export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$supp/ubsan.supp"
failed=()
for t in "${TESTS[@]}"; do
  bin=$(find devel_sanitize/lib -name "$t" -type f -executable | head -n 1)
  if [ -z "$bin" ]; then failed+=("$t: not built"); continue; fi
  if "$bin" > "build_sanitize/$t.log" 2>&1; then
    echo "test-sanitize: $t clean ($(grep -E '^\[  PASSED  \]' "build_sanitize/$t.log"))"
  else
    failed+=("$t")
    echo "test-sanitize: $t FAILED:"; grep -E "ERROR: |runtime error|FAILED|SUMMARY" "build_sanitize/$t.log" | head -n 10
  fi
done
echo "test-sanitize: build $((built - start)) s, tests $(($(date +%s) - built)) s"
[ ${#failed[@]} -eq 0 ] && echo "test-sanitize: all ${#TESTS[@]} clean" && exit 0
echo "test-sanitize: ${#failed[@]} failed: ${failed[*]}"; exit 1
