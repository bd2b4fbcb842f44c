#!/usr/bin/env bash
# The viewer on a scene no render can finish (WORK_DIR/coincident.toml: more surfaces at
# one place than limits::MAX_COINCIDENT): the panel must say why, in red, and the window
# must stay usable.
# Usage (inside xvfb-run): coincident.sh PRISM_BINARY WORK_DIR
set -euo pipefail
# shellcheck source=lib.sh
. "$(dirname "$0")/lib.sh"

"$prism" view "$work/coincident.toml" --width 320 --height 240 >"$log" 2>&1 &
pid=$!
trap 'kill $pid 2>/dev/null || true' EXIT

find_window
for _ in $(seq 300); do
    grep -q "share one centre" "$log" && break
    sleep 0.1
done
grep -q "share one centre" "$log" || { echo "no refusal reported:"; cat "$log"; exit 1; }
sleep 1
import -window root "$work/coincident.png"
xdotool windowfocus --sync "$window"
quit_with_ctrl_q
set +e
wait $pid
code=$?
set -e
echo "viewer exited with $code"
