#!/usr/bin/env bash
# The GNU parallel recipe of docs/farm.md, run for real on this machine: the seed scene
# rendered as tiles by `parallel` and stitched, and frames of the turntable example, each
# compared bit for bit with the same image rendered in one process.
#
#   tests/farm/parallel.sh PRISM WORK
#
# PRISM is the prism binary, WORK an empty folder. Exits 0 when every comparison holds.
set -euo pipefail
prism=$(realpath "$1")
work=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$work"
cd "$work"

# ImageMagick's `compare` counts the pixels that differ at all (-metric AE, no fuzz).
differing() {
    # Newer ImageMagick prints "N (fraction)"; the count is the first word.
    compare -metric AE "$1" "$2" null: 2>&1 | awk '{ print $1 }' || true
}
same() {
    local differ
    differ=$(differing "$1" "$2")
    if [ "$differ" != "0" ]; then
        echo "FAIL: $1 and $2 differ in $differ pixels" >&2
        exit 1
    fi
    echo "same: $1 $2"
}

# ---- Tiles of one frame -------------------------------------------------------------
# Adaptive sampling looks at neighbouring pixels: tiles still equal the full render.
size=(--width 320 --height 240 --adaptive)
tiles=6
# One job per tile; {} is the tile's index. --halt now,fail=1: one failed tile fails all.
seq 0 $((tiles - 1)) | parallel --will-cite --halt now,fail=1 \
    "$prism" render "${size[@]}" --quiet --tile {}/$tiles -o "tile_{}.png"
"$prism" stitch tile_*.png -o stitched.png
"$prism" render "${size[@]}" --quiet -o full.png
same stitched.png full.png
# A rerun with --skip-existing renders only the missing tile. Without --quiet each job
# says what it did: one "rendered" line and a "skipped" line for every other tile.
rm tile_3.png
seq 0 $((tiles - 1)) | parallel --will-cite --halt now,fail=1 \
    "$prism" render "${size[@]}" --skip-existing --tile {}/$tiles -o "tile_{}.png" \
    2> rerun.log
if [ "$(grep -c '^rendered' rerun.log)" != 1 ] ||
    [ "$(grep -c '^skipped' rerun.log)" != $((tiles - 1)) ]; then
    echo "FAIL: the rerun did not render just the missing tile" >&2
    cat rerun.log >&2
    exit 1
fi
"$prism" stitch tile_*.png -o stitched_again.png
same stitched_again.png full.png

# ---- Frames of an animation -----------------------------------------------------------
scene=$root/assets/scenes/turntable.toml
small=(--width 120 --height 90)
frames=12
# One job per frame, two at a time; each job renders with one thread.
seq 0 $((frames - 1)) | parallel --will-cite -j 2 --halt now,fail=1 \
    "$prism" render "$scene" "${small[@]}" --quiet --threads 1 --frame {} -o "farm_{}.png"
# The same frames in one process, on every core.
"$prism" render "$scene" "${small[@]}" --quiet --frames 0..$frames -o "one_{frame}.png"
for ((f = 0; f < frames; f++)); do
    same "farm_$f.png" "one_$f.png"
done
# The frames move: the first and the middle one differ.
if [ "$(differing farm_0.png farm_6.png)" = 0 ]; then
    echo "FAIL: frames 0 and 6 are the same image" >&2
    exit 1
fi
echo "farm recipe: all images equal"
