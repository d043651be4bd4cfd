#!/bin/sh
# The benchmark as the thesis measured on its GTX 760: 1920x1080, light counts up to 64 spot lights, 1024^2
# shadow maps; on each API, the thesis's tables and the k-buffer, light-volume, post-processing, layout and
# specular sections, each measured once (`dstrans bench --backend-only`).
#
#   bench/gpu_bench.sh DSTRANS DIR [DEVICE]
#
# DSTRANS: the dstrans command; DIR: one folder, which receives DIR/vk and DIR/gl, each a results.json and
# report.md (with its plots); DEVICE: the GPU for both APIs, by index or part of its name (default: each
# API's default; `DSTRANS bench --device list` lists them). WIDTH, HEIGHT, SHADOW_SIZE and FRAMES in the
# environment replace 1920, 1080, 1024 and 9 (a small size checks the script on a CPU rasteriser), PAIRS
# caps the pairs a comparison times (`dstrans bench --pairs`), and QUICK=1 measures fewer light counts.
set -eu
if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  echo "usage: bench/gpu_bench.sh DSTRANS DIR [DEVICE]" >&2
  exit 2
fi
dstrans=$1
dir=$2
device=${3:-}
set -- --width "${WIDTH:-1920}" --height "${HEIGHT:-1080}" --shadow-size "${SHADOW_SIZE:-1024}" --frames "${FRAMES:-9}"
if [ -n "$device" ]; then set -- "$@" --device "$device"; fi
if [ -n "${PAIRS:-}" ]; then set -- "$@" --pairs "$PAIRS"; fi
if [ "${QUICK:-0}" = 1 ]; then set -- "$@" --quick; fi
mkdir -p "$dir"
for backend in vk gl; do
  "$dstrans" bench --backend "$backend" --backend-only --out "$dir/$backend" "$@"
done
echo "gpu_bench: $dir/vk and $dir/gl"
