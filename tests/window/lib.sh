# Shared by the window scripts, sourced first with the script's arguments: PRISM_BINARY
# WORK_DIR. Sets `prism`, `work` and `log` (the viewer's log), and makes WORK_DIR/shots.
prism=$1
work=$2
log=$work/viewer.log
mkdir -p "$work/shots"
# The list of recent files goes here, not into the user's configuration.
export XDG_CONFIG_HOME=$work/config

# A private runtime folder, as Wayland and Mesa want one.
export XDG_RUNTIME_DIR=$work/xdg
mkdir -p "$XDG_RUNTIME_DIR"
chmod 700 "$XDG_RUNTIME_DIR"

# find_window sets $window to the viewer's X window (waiting up to 60 s for it to appear:
# on a loaded machine lavapipe can take long to start), or prints the log and exits.
find_window() {
    window=""
    for _ in $(seq 600); do
        window=$(xdotool search --name '^prism$' 2>/dev/null | head -1 || true)
        [ -n "$window" ] && return 0
        if [ -n "${pid:-}" ] && ! kill -0 "$pid" 2>/dev/null; then
            echo "the viewer exited before its window appeared:"; cat "$log"; exit 1
        fi
        sleep 0.1
    done
    echo "no window appeared:"; cat "$log"; exit 1
}

# start_viewer ARGS...: runs `prism view ARGS...` with its output in the log (as $pid,
# killed when the script exits), waits for its window ($window) and focuses it.
start_viewer() {
    "$prism" view "$@" >"$log" 2>&1 &
    pid=$!
    trap 'kill $pid 2>/dev/null || true' EXIT
    find_window
    xdotool windowfocus --sync "$window"
}

# wait_for TEXT COUNT SECONDS: until the viewer's log holds COUNT lines with TEXT (the
# viewer runs as $pid), or prints the log and exits.
wait_for() {
    for _ in $(seq $(($3 * 10))); do
        if [ "$(grep -c "$1" "$log" || true)" -ge "$2" ]; then return 0; fi
        if ! kill -0 "$pid" 2>/dev/null; then echo "viewer died:"; cat "$log"; exit 1; fi
        sleep 0.1
    done
    echo "timed out waiting for '$1' x$2:"; cat "$log"; exit 1
}

# quit_with_ctrl_q: sends Ctrl+Q to $window and waits up to 10 s for the viewer to exit,
# or exits with a message.
quit_with_ctrl_q() {
    # The window may vanish before xdotool sends the key release; the check below decides.
    xdotool key --window "$window" ctrl+q || true
    for _ in $(seq 100); do
        kill -0 "$pid" 2>/dev/null || break
        sleep 0.1
    done
    if kill -0 "$pid" 2>/dev/null; then echo "viewer did not quit on Ctrl+Q"; exit 1; fi
}

# wait_for_after MARKER TEXT SECONDS: until a line with TEXT follows the last line with
# MARKER in the viewer's log (TEXT seen since MARKER), or prints the log and exits.
wait_for_after() {
    for _ in $(seq $(($3 * 10))); do
        if awk -v m="$1" -v t="$2" 'index($0, m) { seen = 1; found = 0 }
                                    seen && index($0, t) { found = 1 }
                                    END { exit !found }' "$log"; then
            return 0
        fi
        if ! kill -0 "$pid" 2>/dev/null; then echo "viewer died:"; cat "$log"; exit 1; fi
        sleep 0.1
    done
    echo "timed out waiting for '$2' after '$1':"; cat "$log"; exit 1
}

# shot N: a screenshot with F12, the Nth of the run, waiting up to 30 s for it to be saved.
shot() {
    xdotool key --window "$window" F12
    wait_for "saved .*\.png" "$1" 30
}
