#!/usr/bin/env bash
# Set up GeodesicShapes on a fresh Debian 12 machine (run as root from anywhere):
#   bash scripts/setup.sh demo   install, build, run the main job -> output/ (data files, main_job.png)
#   bash scripts/setup.sh test   install, build, run the whole test suite (ctest)
set -euo pipefail

mode="${1:-}"
if [[ "$mode" != "demo" && "$mode" != "test" ]]; then
  echo "usage: bash scripts/setup.sh demo|test" >&2
  exit 2
fi

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

# Packages: see ../shared/docs/BUILDING.md (find_package(ParaView) needs the -dev packages that
# Debian's paraview-dev does not pull in). Never libvtk9-dev: it conflicts with python3-paraview.
packages=(
  paraview paraview-dev python3-paraview libeigen3-dev libopenimageio-dev xvfb xauth
  qtbase5-dev libqt5svg5-dev qttools5-dev libqt5opengl5-dev qtxmlpatterns5-dev-tools
  libutfcpp-dev libhdf5-mpi-dev libboost-dev libtheora-dev libavformat-dev libavcodec-dev
  libavutil-dev libswscale-dev libgl2ps-dev libpng-dev libnetcdf-dev libgdal-dev libx11-dev
  libopenmpi-dev openmpi-bin libglew-dev libexpat1-dev liblzma-dev liblz4-dev libdouble-conversion-dev
  libjpeg-dev libtiff-dev libfreetype-dev zlib1g-dev
  libgtest-dev ninja-build libcgal-demo libcgal-dev libgmp-dev libmpfr-dev openclipart-png openclipart-svg libgl1-mesa-dri
  cmake g++ pkg-config clang
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg -s "$p" >/dev/null 2>&1; then
    missing+=("$p")
  fi
done
if ((${#missing[@]} > 0)); then
  echo "Installing ${#missing[@]} package(s): ${missing[*]}"
  sudo_cmd=()
  if [[ $(id -u) -ne 0 ]]; then
    sudo_cmd=(sudo)
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update
  "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
else
  echo "All packages already installed."
fi

# Tests render into one X server of their own for the whole run (configured before CMake, which
# then runs the rendering tests directly instead of starting an Xvfb per test).
if [[ "$mode" == "test" ]]; then
  display_number=87
  while [[ -e "/tmp/.X${display_number}-lock" ]]; do display_number=$((display_number + 1)); done
  # -noreset: by default an X server resets when its last client leaves, and a test that
  # connects during the reset (slower while other tests load the cores) dies with "bad X server
  # connection"; the rendering tests run one at a time, so each ends with the last client.
  Xvfb ":${display_number}" -screen 0 1280x1024x24 -nolisten tcp -noreset >/dev/null 2>&1 &
  xvfb_pid=$!
  trap 'kill "$xvfb_pid" 2>/dev/null || true' EXIT
  export DISPLAY=":${display_number}"
  for _ in $(seq 50); do
    [[ -e "/tmp/.X11-unix/X${display_number}" ]] && break
    sleep 0.1
  done
fi

# Build (2 parallel jobs at most: small machines).
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2

xvfb=(xvfb-run -a -s "-screen 0 1280x1024x24")
case "$mode" in
  demo)
    "${xvfb[@]}" pvpython --force-offscreen-rendering Examples/main_job.py \
      --plugin "$root/build/lib/paraview-5.11/plugins/GeodesicShapes/GeodesicShapes.so" \
      --output "$root/output"
    echo "Results: $root/output/{surface,placements,decals,outlines}.vtp and $root/output/main_job.png"
    ;;
  test)
    # (A test that fails is run once more: a real failure fails twice.)
    ctest --test-dir build --output-on-failure -j2 --repeat until-pass:2
    ;;
esac
