#!/bin/sh
# Renders the JOD validation's GL inputs (tests/perception/data/renders/*.png, the left eye
# of each frame) with foveal render on the bundled Dungeon: the reference, a wider
# reference the panning sequences are cut from, and foveal's methods at levels and gazes.
# usage: tests/perception/data/render_inputs.sh [BUILD_DIR]   (docs/metrics.md, "JOD")
set -eu
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../../../build}/bin/foveal
out=$here/renders
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
left() {  # left() NAME DISPLAY WIDTH ARGS...: render, keep the left eye
  name=$1 display=$2 w=$3
  shift 3
  "$bin" render --display "$here/$display.json" --size "$((2 * w))x224" --no-distortion --dominant left \
    --frames 1 --warmup 0 -o "$tmp/$name.png" "$@" >/dev/null
  /usr/bin/python3 -c "import sys; from PIL import Image; Image.open(sys.argv[1]).convert('RGB').crop((0, 0, int(sys.argv[3]), 224)).save(sys.argv[2], optimize=True)" \
    "$tmp/$name.png" "$out/$name.png" "$w"
}
left full vive_window_384x224 384 --method full
left full_wide vive_window_448x224 448 --method full
left rmfr_s1.5_c vive_window_384x224 384 --method rmfr --sigma-d 1.5 --sigma-nd 1.5
left rmfr_s3_c vive_window_384x224 384 --method rmfr --sigma-d 3 --sigma-nd 3
left rmfr_s2_g25_40 vive_window_384x224 384 --method rmfr --sigma-d 2 --sigma-nd 2 --fovea-left 0.25,0.4
left kfr_s2_c vive_window_384x224 384 --method kfr --sigma-d 2 --sigma-nd 2
left uniform_s2 vive_window_384x224 384 --method uniform --sigma-d 2 --sigma-nd 2
left hyperbolic_s2_c vive_window_384x224 384 --method hyperbolic --sigma-d 2 --sigma-nd 2
