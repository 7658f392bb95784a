#!/usr/bin/env bash
# The README's rviz picture: basic.launch with rviz on a virtual display (Xvfb), a screenshot
# after SECONDS of play. Look at it before committing it.
# usage: src/hideseek_world/scripts/screenshot_rviz.sh [OUT.png] [SECONDS] [launch args...]
set -euo pipefail
out=$(realpath -m "${1:-docs/rviz_basic.png}")
wait_s=${2:-12}
shift $(( $# > 2 ? 2 : $# ))
cd "$(dirname "$(realpath "$0")")/../../.."
source scripts/env.sh
port=${HIDESEEK_PORT:-11483}
display=:${HIDESEEK_DISPLAY:-93}
export ROS_MASTER_URI=http://localhost:$port DISPLAY=$display
Xvfb "$display" -screen 0 1400x900x24 > /dev/null 2>&1 &
xvfb=$!
roslaunch -p "$port" hideseek_world basic.launch rviz:=true "$@" > /tmp/hideseek_screenshot.log 2>&1 &
launch=$!
# roslaunch starts each node in its own session: stop the whole tree by PID.
stop() { pkill -TERM -P "$launch" 2>/dev/null || true; kill "$launch" 2>/dev/null || true; wait "$launch" 2>/dev/null || true; kill "$xvfb" 2>/dev/null || true; }
trap stop EXIT
sleep "$wait_s"
import -display "$display" -window root "$out"
echo "screenshot_rviz: wrote $out (launch log: /tmp/hideseek_screenshot.log)"
