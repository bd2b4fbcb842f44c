#!/usr/bin/env bash
# Stepping through an animated scene's frames in the viewer (run inside xvfb-run; see
# docs/testing.md). Usage: animation.sh PRISM_BINARY WORK_DIR. Opens WORK_DIR/scene.toml
# (an [animation] of at least 41 frames) at 320×240, clicks the panel's ">" three times and
# takes a screenshot of frame 3, types 40 into the frame number and takes one of frame 40,
# then quits. Leaves the log and images in WORK_DIR.
set -euo pipefail
# shellcheck source=lib.sh
. "$(dirname "$0")/lib.sh"
scene=$work/scene.toml

start_viewer "$scene" --width 320 --height 240 --screenshot-dir "$work/shots"
wait_for "converged" 1 60
# The File section's frame row: "<", the frame number, ">" (window coordinates).
for _ in 1 2 3; do
    xdotool mousemove --window "$window" 129 92 click 1
    sleep 0.3
done
wait_for "frame 3 of" 1 30
wait_for_after "frame 3 of" "converged" 60
import -window root "$work/frame3_window.png"
xdotool key --window "$window" F12
wait_for "saved .*\.png" 1 30
# Type a frame number.
xdotool mousemove --window "$window" 94 92 click 1
sleep 0.3
xdotool key --window "$window" ctrl+a
xdotool type --window "$window" 40
xdotool key --window "$window" Return
wait_for "frame 40 of" 1 30
wait_for_after "frame 40 of" "converged" 60
xdotool key --window "$window" F12
wait_for "saved .*\.png" 2 30

quit_with_ctrl_q
wait $pid
echo "viewer exited cleanly"
