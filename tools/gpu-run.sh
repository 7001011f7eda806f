#!/usr/bin/env bash
# Runs on the GPU machine (device tool), from the repository root, with .gl and .gpu carried:
#   tools/gpu-run.sh COMMAND...     e.g. tools/gpu-run.sh report --out "$OUT/report"
# Unpacks the GL entry libraries, points the program at the packed libraries, plugins and this
# tree's GLSL, and uses EGL on the NVIDIA device.
set -euo pipefail
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
export LD_LIBRARY_PATH=$PWD/.gpu/lib
export SHADOWLAB_PLUGIN_DIR=$PWD/.gpu/bin/plugins
export SHADOWLAB_DATA_DIR=$PWD
if [ -f /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json ]; then
  export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
fi
exec .gpu/bin/shadowlab "$@" --backend egl
