#!/usr/bin/env bash
# One-command set-up for a fresh Debian 12 machine.
#   tools/setup.sh run    install missing packages, build Release, run the main job on the default
#                         scene (the window with a display; otherwise the report: every technique
#                         rendered to out/images/<scene>-<technique>.png with its error heatmap, a
#                         table of timings, out/README.md)
#   tools/setup.sh test   install missing packages, build Release, run the whole test suite (ctest)
# Everything comes from Debian packages; nothing is downloaded at build time.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-run}
shift || true

packages=(build-essential cmake ninja-build pkg-config python3 python3-glad
          libglfw3-dev libglm-dev libimgui-dev libtinyobjloader-dev libstb-dev
          libegl-dev libgl-dev libosmesa6-dev libegl-mesa0 libgl1-mesa-dri
          libgtest-dev libcli11-dev libpng-dev nlohmann-json3-dev libembree-dev
          glslang-tools python3-matplotlib xvfb xauth xdotool fonts-dejavu-core
          chromium
          ffmpeg)   # optional for the app (--export needs it, and says so); lecturer_cli checks exports with it
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  sudo=""
  [ "$(id -u)" = 0 ] || sudo=sudo
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"

case "$mode" in
  run)  exec ./build/shadowlab "$@" ;;
  test) cd build && exec ctest --output-on-failure -j"$(nproc)" "$@" ;;
  *)    echo "usage: $0 run|test [arguments]" >&2; exit 2 ;;
esac
