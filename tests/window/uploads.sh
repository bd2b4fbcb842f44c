#!/usr/bin/env bash
# Frames drawn for the panel alone upload no image (run inside xvfb-run; see
# docs/testing.md). Usage: uploads.sh PRISM_BINARY WORK_DIR. Opens the seed scene at
# 320×240 with --log-timing, waits for it to converge, moves the mouse over the panel's
# buttons (each move redraws the panel), then quits. Leaves the log in WORK_DIR.
set -euo pipefail
# shellcheck source=lib.sh
. "$(dirname "$0")/lib.sh"

start_viewer --width 320 --height 240 --log-timing
wait_for "converged" 1 60
sleep 1
for y in 70 90 110 130 150 170 190 210; do
    xdotool mousemove --window "$window" 40 $y
    sleep 0.3
done
quit_with_ctrl_q
wait $pid
echo "viewer exited cleanly"
