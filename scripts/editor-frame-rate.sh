#!/usr/bin/env bash
# The editor's own frame rate at full quality: the studio sample in a window sized so the
# viewport is about 960×540, under Xvfb, drawing a new frame every frame as while the
# artist paints (LIGHTPAINT_MEASURE_FRAME_RATE=1: the lights are set again each frame and
# the camera rests, so each frame is the defaults' full-quality frame after a light edit,
# not the cheaper one shown while the camera moves), egui's work included. Prints the
# status bar's frame time every two seconds for SECONDS_TO_MEASURE seconds (default 20)
# after the first frame. MEASURE=new-view draws every frame from nothing instead (as the
# first frame after the camera stops); MEASURE=interface only the interface around the
# frame drawn before: what the editor costs besides the renderer. For
# docs/performance.md; run it on an otherwise idle machine. WINDOW_SIZE="W H" sizes the
# window otherwise (default "1513 618").
# BIN_TO_MEASURE=path measures that lightpaint binary instead of building the checkout's
# (an older commit's, for interleaved comparisons).
# Usage: [MEASURE=new-view|interface] [WINDOW_SIZE="W H"] [BIN_TO_MEASURE=bin] scripts/editor-frame-rate.sh [PROJECT]
set -euo pipefail
cd "$(dirname "$0")/.."
project="$(realpath "${1:-projects/studio/studio.lightpaint}")"
source scripts/system-packages.sh
if [[ -n "${BIN_TO_MEASURE:-}" ]]; then
    lightpaint_install_system_packages
    lightpaint_runtime_dir
    LIGHTPAINT_BIN="$(realpath "$BIN_TO_MEASURE")"
else
    lightpaint_build_to_run
fi
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
export XDG_DATA_HOME="$scratch/data" LIGHTPAINT_MEASURE_FRAME_RATE="${MEASURE:-1}"
export BIN="$LIGHTPAINT_BIN" PROJECT="$project" LOG="$scratch/editor.log"
export MEASURE_SECONDS="${SECONDS_TO_MEASURE:-20}" WINDOW_SIZE="${WINDOW_SIZE:-1513 618}"
xvfb-run -a -s "-screen 0 1920x1080x24" bash -c '
    set -euo pipefail
    "$BIN" "$PROJECT" 2>"$LOG" &
    editor=$!
    for _ in $(seq 1 180); do grep -q "first frame drawn" "$LOG" && break; sleep 1; done
    # The outliner (about 217 px) and the inspector (about 336 px) beside the viewport,
    # the menu, tool and status bars (about 78 px) above and below it.
    # shellcheck disable=SC2086 # "W H": two arguments
    xdotool search --sync --name lightpaint windowsize $WINDOW_SIZE >/dev/null
    sleep "$MEASURE_SECONDS"
    kill "$editor"
    wait "$editor" || true
'
grep "ms per frame" "$LOG"
