#!/usr/bin/env bash
# Starts the basic game; opens rviz only when a display is available.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/env.sh
rviz=false
if [ -n "${DISPLAY:-}" ]; then rviz=true; fi
exec roslaunch hideseek_world basic.launch rviz:=$rviz "$@"
