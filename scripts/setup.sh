#!/bin/sh
# pronk quickstart on Debian 12 (as root, or with sudo available).
#   scripts/setup.sh demo   install, build, run the main job
#   scripts/setup.sh test   install, build, run the whole test suite
# Set PRONK_SKIP_APT=1 to skip the package installation.
set -eu

cd "$(dirname "$0")/.."
mode="${1:-}"
case "$mode" in
  demo|test) ;;
  *) echo "usage: scripts/setup.sh demo|test" >&2; exit 2 ;;
esac

# Every build and run dependency, from Debian's archive.
PACKAGES="build-essential cmake pkg-config
  libsimbody-dev liburdfdom-dev libtinyxml2-dev libeigen3-dev libassimp-dev
  libcli11-dev nlohmann-json3-dev libfmt-dev libgtest-dev libgmock-dev libbenchmark-dev
  libosmesa6-dev libavcodec-dev libavformat-dev libavutil-dev libswscale-dev
  libfreetype-dev fonts-dejavu-core gnuplot-nox libssl-dev
  libopenmpi-dev openmpi-bin
  clang libclang-rt-dev llvm"  # scripts/fuzz.sh: libFuzzer, ASan/UBSan runtimes, llvm-symbolizer

if [ "${PRONK_SKIP_APT:-0}" != 1 ]; then
  SUDO=""
  if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
  missing=""
  for p in $PACKAGES; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
  done
  if [ -n "$missing" ]; then
    $SUDO apt-get update
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends $missing
  fi
fi

jobs="$(nproc 2>/dev/null || echo 2)"
cmake --preset release
cmake --build --preset release -j "$jobs"

if [ "$mode" = demo ]; then
  ./build/release/bin/pronk run scenarios/go1/forward.xml --policy assets/policies/go1_omni.json --trace \
    --out out/go1-forward \
    --video out/go1-forward/forward.mp4
else
  ctest --preset release -j "$jobs"
fi
