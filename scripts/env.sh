# Sourced by every script that builds or launches: Debian's ROS needs Debian's python3 (a pyenv
# python3 may shadow it), and the workspace's devel space once built.
export PATH="/usr/bin:$PATH"
export ROS_PYTHON_VERSION=3
_hideseek_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ -f "$_hideseek_root/devel/setup.bash" ]; then
  # ROS's setup scripts read unset variables; allow that while they run.
  case $- in *u*) _hideseek_nounset=1; set +u ;; *) _hideseek_nounset=0 ;; esac
  # shellcheck disable=SC1091
  source "$_hideseek_root/devel/setup.bash"
  [ "$_hideseek_nounset" = 1 ] && set -u
fi
# The pipeline's command by its name, as the README and docs write it (rosrun finds it once built).
hideseek_pipeline() { rosrun hideseek_pipeline hideseek_pipeline "$@"; }
true
