#!/usr/bin/env bash
# Picking, editing, saving and reloading in a real X window (run inside xvfb-run; see
# docs/testing.md). Usage: edit.sh PRISM_BINARY WORK_DIR. Opens WORK_DIR/scene.toml (two
# spheres on a floor; tests/viewer_window.rs writes it) and, with a screenshot after each
# step: clicks the left sphere (selecting it), types 0.9 as its colour's green, saves with
# Ctrl+S, shrinks the right sphere in the file on disk, breaks the file, and fixes it. Leaves
# the log, the screenshots and a photograph of the broken state in WORK_DIR.
set -euo pipefail
# shellcheck source=lib.sh
. "$(dirname "$0")/lib.sh"
scene=$work/scene.toml

start_viewer "$scene" --width 320 --height 700 --screenshot-dir "$work/shots"
wait_for "converged" 1 120
shot 1

# A click on the left sphere (97, 350 in the image, right of the 300-point panel).
xdotool mousemove --window "$window" 397 350
sleep 0.3
xdotool click 1
wait_for "selected left" 1 30
import -window root "$work/selected.png"

# Its colour's green: a click on the number turns it into a text field.
xdotool mousemove --window "$window" 182 306
sleep 0.3
xdotool click 1
sleep 0.3
xdotool key --window "$window" ctrl+a
xdotool type --window "$window" "0.9"
xdotool key --window "$window" Return
wait_for "converged" 2 120
shot 2

# Ctrl+S writes the file, which the viewer then sees change and loads again.
xdotool mousemove --window "$window" 800 300
xdotool key --window "$window" ctrl+s
wait_for "saved .*scene\.toml" 1 30
cp "$scene" "$work/saved.toml"
wait_for "reloaded" 1 30
wait_for "converged" 3 120
shot 3

# An edit on disk, with no key pressed: the right sphere shrinks.
sed -i 's/^radius = 1  # right$/radius = 0.6  # right/' "$scene"
wait_for "reloaded" 2 30
wait_for "converged" 4 120
shot 4

# A broken edit: the error is shown and the last good scene stays.
sed -i 's/^radius = 0.6  # right$/radius = -0.6  # right/' "$scene"
wait_for "did not load" 1 30
sleep 0.5
import -window root "$work/broken.png"
shot 5

# The fix brings the scene back.
sed -i 's/^radius = -0.6  # right$/radius = 0.8  # right/' "$scene"
wait_for "reloaded" 3 30
wait_for "converged" 5 120
shot 6

quit_with_ctrl_q
wait $pid
echo "viewer exited cleanly"
