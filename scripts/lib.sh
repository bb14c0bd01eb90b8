# Shared by the README's two commands (scripts/demo.sh, scripts/test.sh): install what is missing from
# Debian 12's own packages, then build in a throwaway catkin workspace outside the repository whose
# src/ links to it. Every step is incremental: nothing is installed or rebuilt that need not be.
# shellcheck shell=bash

REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
PKG="$(sed -n 's:.*<name>\(.*\)</name>.*:\1:p' "$REPO/package.xml" | head -1)"
# One workspace per clone, so two clones never fight over the src/ link.
WS="${SCE_WS:-${TMPDIR:-/tmp}/${PKG}_ws_$(printf '%s' "$REPO" | md5sum | cut -c1-8)}"
# ROS's Python tools need Debian's python3, not a pyenv one that may come first on PATH.
export PYENV_VERSION=system
export PATH="/usr/bin:$PATH"

APT_PACKAGES=(
  build-essential cmake
  ros-core-dev libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  libtf2-ros-dev libtf2-eigen-dev libtf2-geometry-msgs-dev libeigen3-dev
  python3-rostest rosbash python3-rosbag libdiagnostic-updater-dev libnodeletlib-dev libnodelet-dev
  python3-rostopic python3-rosnode python3-rosparam python3-rosmaster rosout python3-roslaunch
  libnodeletlib-tools python3-nav-msgs python3-geometry-msgs python3-diagnostic-msgs python3-nodelet
  libnav-msgs-dev libgeometry-msgs-dev libdiagnostic-msgs-dev libvisualization-msgs-dev libtf2-dev librosbag-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libboost-math-dev nlohmann-json3-dev libcli11-dev libyaml-cpp-dev libtf2-msgs-dev libroslib-dev libstd-srvs-dev
  libceres-dev libsensor-msgs-dev python3-sensor-msgs
  python3-matplotlib python3-yaml python3-tf2-msgs
  rviz
)

log() { printf '\033[1m==> %s\033[0m\n' "$*" >&2; }

install_deps() {
  local missing=()
  for p in "${APT_PACKAGES[@]}"; do
    dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null | grep -qx installed || missing+=("$p")
  done
  if [ ${#missing[@]} -eq 0 ]; then
    log "apt dependencies: all ${#APT_PACKAGES[@]} installed"
    return
  fi
  local sudo=()
  [ "$(id -u)" -eq 0 ] || sudo=(sudo)
  log "apt dependencies: installing ${missing[*]}"
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# build [catkin_make targets...]: configure once, then incremental builds.
build() {
  mkdir -p "$WS/src"
  ln -sfn "$REPO" "$WS/src/$PKG"
  log "building $PKG in $WS (${*:-all})"
  (cd "$WS" && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release -j"$(nproc)" "$@")
  # ROS's setup scripts read unset variables: source them without -u.
  set +u
  # shellcheck disable=SC1091
  source "$WS/devel/setup.bash"
  set -u
}
