#!/usr/bin/env bash
# Every C++ file of the workspace's packages is formatted as .clang-format says (clang-format
# --dry-run): a failure names each file and the first lines that differ. Fix with
#   clang-format -i $(git ls-files 'src/*.cpp' 'src/*.h')
# usage: clang_format_test.sh WORKSPACE_SRC XUNIT_OUTPUT
set -uo pipefail
src=$1
out=$2
source "$(dirname "$0")/xunit.sh"
mapfile -t files < <(find "$src" \( -name '*.cpp' -o -name '*.h' \) | sort)
failures=()
for f in "${files[@]}"; do
  if ! report=$(clang-format --dry-run --Werror "$f" 2>&1); then
    failures+=("${f#"$src"/}: $(echo "$report" | grep -m 2 -E 'error|warning' | tr '\n' ' ')")
  fi
done
if [ "${#files[@]}" -eq 0 ]; then failures+=("no C++ files found under $src"); fi
echo "clang_format_test: ${#files[@]} files, ${#failures[@]} not formatted"
printf '  %s\n' "${failures[@]}"
write_xunit "$out" clang_format EveryCppFileFormatted "${failures[@]}"
[ "${#failures[@]}" -eq 0 ]
