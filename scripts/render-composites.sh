#!/usr/bin/env bash
# Renders the sample's composites with gusuku-render: the site at 09:00, 12:00, 15:00, 16:30 (between slots:
# the 15:00 slot's light carried to a lower sun) and overcast, each beside direct-only (what AR apps draw today)
# and the camera frame it was drawn into. The camera frames are path-traced (the sample has no photograph). The
# composites use the ground colour match, the runtime's default (ColourMatch::kAuto) on a bake set with ground albedo.
# Usage: scripts/render-composites.sh [BAKESET] [OUTDIR] [WxH] [SAMPLES]
#   defaults: out/bakeset out/composites 480x270 32
# The pictures of README.md and docs/runtime.md are remade with: scripts/render-composites.sh out/bakeset docs/images 384x216 64
set -euo pipefail
cd "$(dirname "$0")/.."
bakeset="${1:-out/bakeset}"
out="${2:-out/composites}"
size="${3:-480x270}"
samples="${4:-32}"
mkdir -p "$out"
# name, time on the site's clock (UTC+9), weather
conditions=(
  "0900 2026-06-21T09:00:00+09:00 sunny"
  "1200 2026-06-21T12:00:00+09:00 sunny"
  "1500 2026-06-21T15:00:00+09:00 sunny"
  "1630 2026-06-21T16:30:00+09:00 sunny"
  "overcast 2026-06-21T12:00:00+09:00 overcast"
)
for condition in "${conditions[@]}"; do
  read -r name time weather <<<"$condition"
  echo "== $name ($time, $weather)"
  ./build/bench/gusuku-render "$bakeset" -o "$out/composite_$name.png" --direct-only "$out/direct_$name.png" \
    --camera-out "$out/camera_$name.png" --size "$size" --samples "$samples" --time "$time" --weather "$weather" \
    --position 9,-19,5.5 --look-at 0,-1,1.2 --fov 55 --frames 5 --colour-match ground |
    grep -E "composite|sun|slots|frame|passes"
done
