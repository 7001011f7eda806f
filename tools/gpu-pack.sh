#!/usr/bin/env bash
# Packs the Release build for the GPU machine into .gpu/ (ignored by git): the executable, the
# plugins, the Embree ground-truth module and their non-system libraries (../shared/gpu/README.md).
set -euo pipefail
cd "$(dirname "$0")/.."
rm -rf .gpu
bash ../shared/gpu/pack-runtime.sh .gpu build/shadowlab build/libshadowlab_groundtruth.so build/plugins
# The device tool carries at most 64 MiB with the tracked tree: leave out the plugins' CMake
# folder (object files) and strip what was built here (Embree alone is 42 MiB).
rm -rf .gpu/bin/plugins/CMakeFiles
strip --strip-unneeded .gpu/bin/shadowlab .gpu/bin/*.so .gpu/bin/plugins/*.so
du -sh .gpu
