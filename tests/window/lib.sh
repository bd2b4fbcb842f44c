# Shared by the window scripts (sourced after `prism`, `work` and `log` are set).

# A private runtime folder, as Wayland and Mesa want one.
export XDG_RUNTIME_DIR=$work/xdg
mkdir -p "$XDG_RUNTIME_DIR"
chmod 700 "$XDG_RUNTIME_DIR"

# find_window sets $window to the viewer's X window (waiting up to 30 s for it to appear),
# or prints the log and exits.
find_window() {
    window=""
    for _ in $(seq 300); do
        window=$(xdotool search --name '^prism$' 2>/dev/null | head -1 || true)
        [ -n "$window" ] && return 0
        sleep 0.1
    done
    echo "no window appeared:"; cat "$log"; exit 1
}
