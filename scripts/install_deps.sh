#!/usr/bin/env bash
# Installs every system dependency from Debian 12's own packages. Idempotent: when all are
# present it changes nothing and needs no network.
set -euo pipefail

PACKAGES=(
  build-essential cmake
  ros-base-dev catkin python3-catkin-pkg python3-rospkg python3-rostest rosbash
  librosbag-dev libimage-transport-dev libtf2-ros-dev libtf2-geometry-msgs-dev libstd-srvs-dev ros-std-srvs libdiagnostic-msgs-dev
  rviz
  tf-tools      # rosrun tf tf_echo map hider/base_link, tf_monitor: the usual ways to look at the frames (Debian's view_frames fails under Python 3)
  python3-std-msgs python3-geometry-msgs python3-sensor-msgs python3-nav-msgs python3-visualization-msgs
  python3-diagnostic-msgs python3-tf2-msgs python3-rosgraph-msgs
  libosmesa6-dev libeigen3-dev libyaml-cpp-dev
  libboost-program-options-dev  # the C++ tools' command lines (hideseek_game_cli)
  libtorch-dev libopenblas0-pthread
  zlib1g-dev  # the checkpoint check inflates TorchScript entries (issue #49)
  libroslz4-dev libbz2-dev  # the bag check decompresses chunks itself (issue #49)
  libopenblas0-openmp  # the BLAS the training programs link: it shares libtorch's OpenMP threads (#27)
  libgtest-dev googletest
  xvfb xauth imagemagick xterm
  python3-matplotlib python3-sklearn python3-scipy python3-pytest python3-yaml
  python3-tqdm  # the pipeline's progress bars (hideseek_pipeline report and bench)
  catkin-lint   # checks the packages' CMake and package.xml files (issue #34)
  strace        # the install-space test lists every file the installed graph opens
  clang-format  # the one C++ formatter (.clang-format), checked by make test
  clang libclang-rt-14-dev  # make test-sanitize and make fuzz: ASan, UBSan and libFuzzer (issue #49)
  pybind11-dev python3-numpy  # the Python environment (hideseek_gym, issue #50)
  python3-torch  # its example PPO (examples/ppo_python.py)
  libgloo-dev iproute2  # training across machines (c10d over Gloo; the test's network namespaces, issue #51)
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install_deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
