#!/usr/bin/env bash
# Packs the Release build for the GPU machine into .gpu/ (ignored by git): the executable, the
# plugins, the Embree ground-truth module and their non-system libraries (../shared/gpu/README.md).
#   tools/gpu-pack.sh [--timing-only]
# --timing-only leaves the ground-truth module and Embree (about 42 MiB) behind, for runs without
# accuracy: the tracked tree and the pack must fit the device tool's 64 MiB together.
set -euo pipefail
cd "$(dirname "$0")/.."
rm -rf .gpu
if [ "${1:-}" = "--timing-only" ]; then
  bash ../shared/gpu/pack-runtime.sh .gpu build/shadowlab build/plugins
else
  bash ../shared/gpu/pack-runtime.sh .gpu build/shadowlab build/libshadowlab_groundtruth.so build/plugins
fi
# The device tool carries at most 64 MiB with the tracked tree: leave out the plugins' CMake
# folder (object files) and strip what was built here (Embree alone is 42 MiB).
rm -rf .gpu/bin/plugins/CMakeFiles
strip --strip-unneeded .gpu/bin/shadowlab $(ls .gpu/bin/*.so 2>/dev/null) .gpu/bin/plugins/*.so
du -sh .gpu
