# Sourced by the shell integration tests: writes a one-case xunit file that catkin_test_results
# reads. usage: write_xunit OUTPUT SUITE CASE [FAILURE...]  (no failure messages: the case passed)
write_xunit() {
  local out=$1 suite=$2 name=$3
  shift 3
  {
    echo '<?xml version="1.0"?>'
    echo "<testsuite name=\"$suite\" tests=\"1\" failures=\"$([ $# -eq 0 ] && echo 0 || echo 1)\" errors=\"0\">"
    if [ $# -eq 0 ]; then
      echo "<testcase classname=\"$suite\" name=\"$name\"/>"
    else
      local msg
      msg=$(printf '%s; ' "$@" | sed 's/&/\&amp;/g; s/"/\&quot;/g; s/</\&lt;/g')
      echo "<testcase classname=\"$suite\" name=\"$name\"><failure message=\"$msg\"/></testcase>"
    fi
    echo "</testsuite>"
  } > "$out"
}
