#!/usr/bin/env bash
# A scene that fails to load at start (run inside xvfb-run; see docs/testing.md). Usage:
# broken_start.sh PRISM_BINARY WORK_DIR. Opens WORK_DIR/scene.toml, which has an error: the
# window must open and show it. Photographs the screen, fixes the file, waits for the scene
# to load and converge, takes a screenshot and quits. Leaves the log and images in WORK_DIR.
set -euo pipefail
# shellcheck source=lib.sh
. "$(dirname "$0")/lib.sh"
scene=$work/scene.toml

start_viewer "$scene" --width 320 --height 240 --screenshot-dir "$work/shots"
wait_for "did not load" 1 30
# The empty window converges at once; then it is on screen.
wait_for "converged" 1 60
sleep 0.5
import -window root "$work/broken.png"
sed -i 's/^radius = -1$/radius = 1/' "$scene"
wait_for "reloaded" 1 30
wait_for "converged" 2 120
xdotool key --window "$window" F12
wait_for "saved .*\.png" 1 30

quit_with_ctrl_q
wait $pid
echo "viewer exited cleanly"
