#!/usr/bin/env bash
# Times log-SH frames at 960×540 on this machine's GPU with `lightpaint render
# --time-frames`, for the table in docs/performance.md. Run it on an otherwise idle machine.
# REPEAT=n: only the studio's defaults, n runs back to back (how much one row varies).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/system-packages.sh
lightpaint_build_to_run
bin="$LIGHTPAINT_BIN"
frames="${FRAMES:-10}"
out="$(mktemp -d)"
row() {
    local label="$1"
    shift
    local timing
    timing=$("$bin" render "$@" -o "$out/frame.png" --width 960 --height 540 --time-frames "$frames" | awk "NR == 1")
    echo "| $label | $timing |"
}
studio=projects/studio/studio.lightpaint
sample=projects/sample/sample.lightpaint
echo "| configuration | $frames frames after a warm-up |"
echo "|---|---|"
if [[ -n "${REPEAT:-}" ]]; then
    for _ in $(seq "$REPEAT"); do
        row "studio, defaults" "$studio"
    done
    exit 0
fi
row "studio, defaults (order 4, HYB, fitted blockers, 1024² shadow maps, 1 in 3×3 shaded, edge filter)" "$studio"
row "studio, defaults without antialiasing" "$studio" --aa none
row "studio, defaults without shadow maps" "$studio" --shadow-map-size 0
row "studio, defaults with 4× MSAA" "$studio" --aa msaa
row "studio, 1 in 2×2 shaded" "$studio" --shading-downsample 2
row "studio, 1 in 4×4 shaded" "$studio" --shading-downsample 4
row "studio, every pixel shaded" "$studio" --shading-downsample 1
row "studio, every pixel shaded, 4× MSAA" "$studio" --shading-downsample 1 --aa msaa
row "studio, per vertex" "$studio" --per-vertex
row "studio, order 2, DC" "$studio" --order 2 --exp dc
row "studio, order 8, HYB" "$studio" --order 8
row "studio, 400 spheres (fitted)" "$studio" --blockers 400
row "studio, log-BRDF" "$studio" --brdf log
row "studio, product BRDF" "$studio" --brdf product
row "sample, defaults" "$sample"
row "sample, every pixel shaded" "$sample" --shading-downsample 1
