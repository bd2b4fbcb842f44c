#!/usr/bin/env bash
# Placing an object from the panel in a real X window (run inside xvfb-run; see
# docs/testing.md). Usage: transform.sh PRISM_BINARY WORK_DIR. Opens WORK_DIR/scene.toml
# (the two spheres of edit.sh), clicks the right sphere, types its translate x, rotate z and
# (per axis) scale y, takes a screenshot, saves with Ctrl+S, and after the reload undoes the
# three edits with Ctrl+Z and takes another. Leaves the log, the screenshots and the saved
# file (saved.toml) in WORK_DIR.
set -euo pipefail
# shellcheck source=lib.sh
. "$(dirname "$0")/lib.sh"
scene=$work/scene.toml

# type_into X Y TEXT: a click on the number at (X, Y) turns it into a text field; TEXT
# replaces what it holds.
type_into() {
    xdotool mousemove --window "$window" "$1" "$2"
    sleep 0.3
    xdotool click 1
    sleep 0.3
    xdotool key --window "$window" ctrl+a
    xdotool type --window "$window" "$3"
    xdotool key --window "$window" Return
    sleep 1
}

start_viewer "$scene" --width 320 --height 700 --screenshot-dir "$work/shots"
wait_for "converged" 1 120

# The right sphere (280, 350 in the image, right of the 300-point panel).
xdotool mousemove --window "$window" 580 350
sleep 0.3
xdotool click 1
wait_for "selected right" 1 30

# The selection's rows (the panel's default layout): translate at y 243, rotate at 264,
# scale at 285 (one number, then "per axis", which shows x, y and z).
type_into 88 243 "0.5"
type_into 176 264 "20"
xdotool mousemove --window "$window" 100 285
sleep 0.3
xdotool click 1
sleep 0.5
type_into 115 285 "0.5"
import -window root "$work/placed.png"
xdotool mousemove --window "$window" 800 300
wait_for "converged" 2 120
shot 1

xdotool key --window "$window" ctrl+s
wait_for "saved .*scene\.toml" 1 30
cp "$scene" "$work/saved.toml"
wait_for "reloaded" 1 30
wait_for "converged" 3 120

# Each field's edit is one step to undo.
for _ in 1 2 3; do
    xdotool key --window "$window" ctrl+z
    sleep 0.5
done
wait_for_after "undid" "converged" 120
shot 2

quit_with_ctrl_q
wait $pid
echo "viewer exited cleanly"
