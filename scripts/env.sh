# Sourced by every script that builds or launches: Debian's ROS needs Debian's python3 (a pyenv
# python3 may shadow it), and the workspace's devel space once built.
export PATH="/usr/bin:$PATH"
export ROS_PYTHON_VERSION=3
_hideseek_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ -f "$_hideseek_root/devel/setup.bash" ]; then
  # shellcheck disable=SC1091
  source "$_hideseek_root/devel/setup.bash"
fi
