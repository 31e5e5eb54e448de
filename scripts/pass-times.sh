#!/usr/bin/env bash
# Compares `lightpaint` binaries pass by pass: RUNS interleaved runs of each binary's
# `render … --time-frames 6` at 960×540, then per binary the best and the median over the
# runs of each pass's GPU time (docs/performance.md).
#   scripts/pass-times.sh RUNS BINARY...
# PROJECT: the project (default the studio); WHICH: the line of `render`'s output whose
# pass times to take ("6 frames: mean" for frames drawn anew, the default; "after a light
# edit" for frames after a light edit).
set -euo pipefail
runs="$1"
shift
project="${PROJECT:-projects/studio/studio.lightpaint}"
which="${WHICH:-6 frames: mean}"
out="$(mktemp -d)"
for i in $(seq 1 "$runs"); do
    index=0
    for bin in "$@"; do
        "$bin" render "$project" -o "$out/frame.png" --width 960 --height 540 --time-frames 6 2>&1 \
            | grep -A1 "$which" | tail -1 >>"$out/passes-$index.txt"
        index=$((index + 1))
    done
done
index=0
for bin in "$@"; do
    echo "== $bin"
    python3 - "$out/passes-$index.txt" <<'PY'
import collections, re, sys
times = collections.defaultdict(list)
for line in open(sys.argv[1]):
    for name, ms in re.findall(r'([a-z][a-z -]+?) ([0-9.]+) ms', line.split(':', 1)[1]):
        times[name.strip()].append(float(ms))
print('; '.join(f"{name} {min(v):.1f}/{sorted(v)[len(v) // 2]:.1f}" for name, v in times.items()))
PY
    index=$((index + 1))
done
