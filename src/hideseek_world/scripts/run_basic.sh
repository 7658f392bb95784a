#!/usr/bin/env bash
# Starts the basic game; opens rviz only when a display is available. Without one, the world prints
# a line per finished episode and, every 5 s, arena 0's step, the distance and who sees whom.
set -euo pipefail
cd "$(dirname "$(realpath "$0")")/../../.."
source scripts/env.sh
rviz=false
status=5
if [ -n "${DISPLAY:-}" ]; then rviz=true; status=0; fi
exec roslaunch hideseek_world basic.launch rviz:=$rviz status_period:=$status "$@"
