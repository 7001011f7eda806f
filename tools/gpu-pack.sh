#!/usr/bin/env bash
# Packs the Release build for the GPU machine into .gpu/ (ignored by git): the executable, the
# plugins, the Embree ground-truth module and their non-system libraries (../shared/gpu/README.md).
set -euo pipefail
cd "$(dirname "$0")/.."
rm -rf .gpu
bash ../shared/gpu/pack-runtime.sh .gpu build/shadowlab build/libshadowlab_groundtruth.so build/plugins
