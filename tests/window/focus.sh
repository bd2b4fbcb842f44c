#!/usr/bin/env bash
# The lens in a real X window (run inside xvfb-run; see docs/testing.md). Usage: focus.sh
# PRISM_BINARY WORK_DIR. Opens WORK_DIR/lens.toml (a camera with an aperture, focused far
# away), waits for convergence, saves a screenshot, clicks the centre of the image (a near
# sphere), waits for the viewer to report the new focus and converge again, saves a second
# screenshot, and quits. Leaves the log and the images in WORK_DIR.
set -euo pipefail
# shellcheck source=lib.sh
. "$(dirname "$0")/lib.sh"

start_viewer "$work/lens.toml" --width 200 --height 200 --screenshot-dir "$work/shots"
wait_for "converged" 1 120
xdotool key --window "$window" F12
wait_for "saved" 1 30

# A click (press and release without a drag) on the image's centre, right of the 300-point
# panel: the near sphere.
xdotool mousemove --window "$window" 400 100
sleep 0.3
xdotool click 1
wait_for "focused at" 1 30
wait_for "converged" 2 120
xdotool key --window "$window" F12
wait_for "saved" 2 30

quit_with_ctrl_q
wait $pid
echo "viewer exited cleanly"
