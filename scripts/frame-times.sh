#!/usr/bin/env bash
# Times log-SH frames at 960×540 on this machine's GPU with `lightpaint render
# --time-frames`, for the table in docs/performance.md. Run it on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/system-packages.sh
lightpaint_runtime_dir
cargo build --quiet --bin lightpaint
bin="${CARGO_TARGET_DIR}/debug/lightpaint"
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
row "studio, defaults (order 4, HYB, 48 fitted spheres, 1 in 2×2 shaded), MSAA 4" "$studio"
row "studio, defaults, MSAA 1" "$studio" --msaa 1
row "studio, every pixel shaded, MSAA 4" "$studio" --shading-downsample 1
row "studio, every pixel shaded, MSAA 1" "$studio" --shading-downsample 1 --msaa 1
row "studio, 1 in 4×4 shaded, MSAA 4" "$studio" --shading-downsample 4
row "studio, 1 in 4×4 shaded, MSAA 1" "$studio" --shading-downsample 4 --msaa 1
row "studio, per vertex, MSAA 1" "$studio" --per-vertex --msaa 1
row "studio, order 2, DC, MSAA 1" "$studio" --order 2 --exp dc --msaa 1
row "studio, order 8, HYB, MSAA 1" "$studio" --order 8 --msaa 1
row "studio, 400 spheres (fitted), MSAA 1" "$studio" --blockers 400 --msaa 1
row "studio, log-BRDF, MSAA 1" "$studio" --brdf log --msaa 1
row "studio, product BRDF, MSAA 1" "$studio" --brdf product --msaa 1
row "sample, defaults (19 fitted spheres), MSAA 4" "$sample"
row "sample, every pixel shaded, MSAA 4" "$sample" --shading-downsample 1
