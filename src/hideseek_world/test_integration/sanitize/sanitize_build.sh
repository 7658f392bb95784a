#!/usr/bin/env bash
# Builds TARGETS in the sanitizer workspace: the same sources compiled by clang with
# AddressSanitizer, UndefinedBehaviorSanitizer and libFuzzer's coverage (HIDESEEK_SANITIZE,
# HIDESEEK_FUZZ), in build_sanitize/ and devel_sanitize/ beside the normal build (issue #49).
# usage: test/sanitize/sanitize_build.sh TARGET...
set -euo pipefail
cd "$(dirname "$(realpath "$0")")/../.."
source scripts/env.sh
catkin_make --build build_sanitize -DCATKIN_DEVEL_PREFIX="$PWD/devel_sanitize" \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 -DCATKIN_ENABLE_TESTING=ON \
  -DHIDESEEK_SANITIZE=ON -DHIDESEEK_FUZZ=ON -j"${JOBS:-$(nproc)}" "$@"
