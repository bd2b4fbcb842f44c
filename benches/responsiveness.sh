#!/usr/bin/env bash
# The viewer's responsiveness (issue 18's targets): with a 1600×1000 image area, the panel
# and image keep redrawing at 30 fps or more while passes run, and a slider change shows its
# first new image within 100 ms. Opens `prism view --log-timing` on the seed scene in a
# virtual X screen, drags the panel's "ambient r" number for a few seconds (each step an
# edit the render thread must pick up), and summarises the viewer's timing lines.
#
# Usage: benches/responsiveness.sh [--quick] [PRISM_BINARY] [OUT_DIR]
#   --quick: a 640×600 image and a short drag (proves the pipeline works; CI runs it).
# Writes OUT_DIR/responsiveness.md (default docs/benchmarks) and prints it.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
quick=0
if [ "${1:-}" = "--quick" ]; then quick=1; shift; fi
prism=${1:-$here/target/release/prism}
out=${2:-$here/docs/benchmarks}
if [ -z "${PRISM_BENCH_INSIDE_X:-}" ]; then
    q=(); [ "$quick" = 1 ] && q=(--quick)
    exec env PRISM_BENCH_INSIDE_X=1 xvfb-run -a -s '-screen 0 1920x1080x24' "$0" "${q[@]}" "$prism" "$out"
fi
mkdir -p "$out"
work=$(mktemp -d)
trap 'kill "${pid:-0}" 2>/dev/null || true; rm -rf "$work"' EXIT
export XDG_RUNTIME_DIR=$work/xdg XDG_CONFIG_HOME=$work/config
mkdir -p "$XDG_RUNTIME_DIR"; chmod 700 "$XDG_RUNTIME_DIR"
log=$work/viewer.log
if [ "$quick" = 1 ]; then width=640; height=600; steps=6; else width=1600; height=1000; steps=40; fi

"$prism" view --width $width --height $height --log-timing --screenshot-dir "$work" >"$log" 2>&1 &
pid=$!
window=""
for _ in $(seq 300); do
    window=$(xdotool search --name '^prism$' 2>/dev/null | head -1 || true)
    [ -n "$window" ] && break
    sleep 0.1
done
[ -n "$window" ] || { echo "no window:"; cat "$log"; exit 1; }
xdotool windowfocus --sync "$window"
for _ in $(seq 600); do grep -q converged "$log" && break; sleep 0.1; done

# The seed's panel: "ambient r" in the Scene section, at (107, 420) with the panel's
# default layout. Each 4-pixel move of the drag changes it by 0.02: one edit.
xdotool mousemove --window "$window" 107 420
sleep 0.3
xdotool mousedown 1
for _ in $(seq $steps); do
    xdotool mousemove_relative 4 0
    sleep 0.25
done
xdotool mouseup 1
sleep 3
xdotool key --window "$window" ctrl+q || true
wait $pid || true

edits=$(grep -c "prism-timing: shown edit" "$log" || true)
[ "$edits" -ge 1 ] || { echo "no edit reached the screen:"; tail -20 "$log"; exit 1; }
# Frames while passes run: from the first change's image to the last one's.
summary=$(awk '
    /prism-timing: shown edit/ { n++; lat[n] = $4; kind[n] = $5; if (!first) first = NR; last = NR }
    /prism-timing: frame/ { fn++; line[fn] = NR; gap[fn] = $5 }
    function sort(a, k,   i, j, t) { for (i = 2; i <= k; i++) { t = a[i]; for (j = i - 1; j > 0 && a[j] > t; j--) a[j + 1] = a[j]; a[j + 1] = t } }
    END {
        m = 0; for (i = 1; i <= fn; i++) if (line[i] > first && line[i] <= last) g[++m] = gap[i]
        sort(lat, n); sort(g, m)
        coarse = 0; for (i = 1; i <= n; i++) if (kind[i] == "coarse") coarse++
        p = int(n * 0.95 + 0.5); if (p < 1) p = 1
        q = int(m * 0.95 + 0.5); if (q < 1) q = 1
        fmed = 0; f5 = 0; fmin = 0
        if (m) { fmed = 1000 / g[int((m + 1) / 2)]; f5 = 1000 / g[q]; fmin = 1000 / g[m] }
        printf "%d %.1f %.1f %.1f %d %d %.1f %.1f %.1f\n", n, lat[int((n + 1) / 2)], lat[p], lat[n], coarse, m, fmed, f5, fmin
    }' "$log")
read -r n lat_med lat_p95 lat_max coarse frames fps_med fps_p5 fps_min <<<"$summary"
report=$out/responsiveness.md
{
    echo "# Viewer responsiveness"
    echo
    echo "The seed scene in \`prism view --log-timing\` with a ${width}×${height} image area under Xvfb"
    echo "(Mesa's lavapipe draws the window on the CPU, beside the tracer), while the panel's"
    echo "\"ambient r\" number is dragged for $steps steps a quarter of a second apart. Measured"
    echo "$(date -u +%Y-%m-%d) on $(nproc) cores by:"
    echo
    echo '```sh'
    echo "benches/responsiveness.sh$([ "$quick" = 1 ] && echo ' --quick')"
    echo '```'
    echo
    echo "| measure | median | 95th percentile | worst |"
    echo "|---|---|---|---|"
    echo "| an edit to its first image on screen (ms), $n edits, $coarse of them shown first coarse | $lat_med | $lat_p95 | $lat_max |"
    echo "| frames per second the drawing keeps up with while passes run (1000 / a frame's drawing time; $frames frames; the 95th percentile and worst are the slowest) | $fps_med | $fps_p5 | $fps_min |"
    echo
    echo "The targets: every edit on screen within 100 ms, and frames drawn fast enough for 30"
    echo "a second or more. A frame is drawn only when an input or a pass's image is new (not"
    echo "every vertical blank): between them nothing on screen changes, and the cores are the"
    echo "tracer's."
} >"$report"
cat "$report"
