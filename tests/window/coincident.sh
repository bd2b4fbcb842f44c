#!/usr/bin/env bash
# The viewer on a scene no render can finish (WORK_DIR/coincident.toml: more surfaces at
# one place than limits::MAX_COINCIDENT): the panel must say why, in red, and the window
# must stay usable.
# Usage (inside xvfb-run): coincident.sh PRISM_BINARY WORK_DIR
set -euo pipefail
# shellcheck source=lib.sh
. "$(dirname "$0")/lib.sh"

start_viewer "$work/coincident.toml" --width 320 --height 240
wait_for "share one centre" 1 30
sleep 1
import -window root "$work/coincident.png"
quit_with_ctrl_q
echo "the viewer quit"
