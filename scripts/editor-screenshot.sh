#!/usr/bin/env bash
# Screenshots the editor under Xvfb in the middle of a stroke, for
# docs/images/editor-painting.png: the studio sample, the left rim light selected (its gizmo
# showing), one stroke painted and the brighten brush held down halfway through a second. The pointer is driven
# with xdotool (installed with the other packages), so the picture is the real window with real
# input. Usage: scripts/editor-screenshot.sh [OUT.png]
set -euo pipefail
cd "$(dirname "$0")/.."
out="$(realpath -m "${1:-docs/images/editor-painting.png}")"
source scripts/system-packages.sh
lightpaint_build_to_run
# A scratch copy of the sample, and no preferences or window size from earlier runs.
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
cp -r projects/studio "$scratch/"
# A brush big enough to see in the picture.
sed -i 's/"brush": null/"brush": {"kind": "positive", "radius_px": 36, "falloff": "smooth", "strength": 1.0, "target_luminance_nits": 1.0}/' \
    "$scratch/studio/studio.lightpaint"
export XDG_DATA_HOME="$scratch/data" LIGHTPAINT_HIDE_FRAME_TIMINGS=1
export BIN="$LIGHTPAINT_BIN" PROJECT="$scratch/studio/studio.lightpaint" OUT="$out"
xvfb-run -a -s "-screen 0 1280x800x24" bash -c '
    set -euo pipefail
    "$BIN" "$PROJECT" 2>"$OUT.log" &
    editor=$!
    for _ in $(seq 1 180); do grep -q "first frame drawn" "$OUT.log" && break; sleep 1; done
    sleep 5
    xdotool mousemove 110 224 click 1         # the left rim light in the outliner
    sleep 3
    xdotool mousemove 155 37 click 1          # the brighten brush in the tool bar
    sleep 2
    # One stroke across the floor right of the figure, then a second one held halfway,
    # slowly, as a hand paints.
    xdotool mousemove 700 560 mousedown 1
    for x in $(seq 710 20 850); do xdotool mousemove "$x" 570; sleep 0.4; done
    xdotool mouseup 1
    sleep 4
    xdotool mousemove 420 700 mousedown 1
    for x in $(seq 440 20 640); do xdotool mousemove "$x" $(( 700 - (x - 420) / 10 )); sleep 0.4; done
    sleep 3
    import -window root "$OUT"
    xdotool mouseup 1
    kill "$editor"
'
rm -f "$out.log"
echo "wrote $out"
