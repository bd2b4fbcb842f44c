#!/usr/bin/env bash
# The viewer when its render thread panics (PRISM_INJECT_PANIC makes every pass panic):
# the panel must say so, the window must stay usable, and the exit code must be 1.
# Usage (inside xvfb-run): panic.sh PRISM_BINARY WORK_DIR
set -euo pipefail
# shellcheck source=lib.sh
. "$(dirname "$0")/lib.sh"

PRISM_INJECT_PANIC=1 "$prism" view --width 320 --height 240 >"$log" 2>&1 &
pid=$!
trap 'kill $pid 2>/dev/null || true' EXIT

find_window
for _ in $(seq 300); do
    grep -q "the render failed" "$log" && break
    sleep 0.1
done
grep -q "the render failed" "$log" || { echo "no failure reported:"; cat "$log"; exit 1; }
sleep 1
import -window root "$work/panic.png"
xdotool windowfocus --sync "$window"
quit_with_ctrl_q
set +e
wait $pid
code=$?
set -e
echo "viewer exited with $code"
