#!/usr/bin/env bash
# End-to-end test of the viewer in a real X window (run inside xvfb-run; see
# docs/testing.md). Usage: e2e.sh PRISM_BINARY WORK_DIR
# Opens the viewer on the seed scene, waits for convergence, takes a screenshot with F12,
# moves the camera with W, waits again, takes a second screenshot with P, photographs the
# whole screen, squeezes the window narrower than its panel and back, taps D and takes a
# third screenshot, moves the keyboard focus into the panel with Tab, and quits with Ctrl+Q. Leaves the viewer's log and the
# images in WORK_DIR.
set -euo pipefail
# shellcheck source=lib.sh
. "$(dirname "$0")/lib.sh"

start_viewer --width 320 --height 240 --aa 2 --screenshot-dir "$work/shots"

wait_for "converged" 1 120
xdotool key --window "$window" F12
wait_for "saved" 1 30

# Fly forward for a moment: accumulation must restart and converge again.
xdotool keydown --window "$window" w
sleep 0.4
xdotool keyup --window "$window" w
wait_for "converged" 2 120
xdotool key --window "$window" p
wait_for "saved" 2 30
import -window root "$work/screen.png"

# Narrower than the panel: no image fits beside it, and nothing may break.
xdotool windowsize --sync "$window" 290 240 || xdotool windowsize "$window" 290 240
sleep 1
kill -0 $pid 2>/dev/null || { echo "viewer died when narrowed:"; cat "$log"; exit 1; }
import -window root "$work/narrow.png"
xdotool windowsize "$window" 620 240
wait_for "converged" 3 120

# A tap of D (press and release at once) moves one step to the right.
xdotool windowfocus --sync "$window"
xdotool key --window "$window" d
wait_for "converged" 4 120
xdotool key --window "$window" F12
wait_for "saved" 3 30

# Tab moves the keyboard focus into the panel; Ctrl+Q must still quit.
xdotool windowfocus --sync "$window"
xdotool key --window "$window" Tab
sleep 0.3
quit_with_ctrl_q
wait $pid
echo "viewer exited cleanly"
