#!/usr/bin/env bash
# Renders the sample's composites with gusuku-render: the site at 09:00, 12:00, 15:00, 16:30 (between slots:
# the 15:00 slot's light carried to a lower sun) and overcast, each beside direct-only (what AR apps draw today)
# and the camera frame it was drawn into. The camera frames are path-traced (the sample has no photograph). The
# composites use the ground colour match, the runtime's default (ColourMatch::kAuto) on a bake set with ground albedo.
# Then the day's animation, day.webp: the sample walk composited by gusuku-view --render (needs GLFW and img2webp).
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
# The README's animation (docs/session.md): the sample walk through the bake day, 08:00 to 17:00 with a cloud
# passing after noon, gusuku beside direct-only, composited by gusuku-view --render and assembled into an animated
# WebP by img2webp (Debian's webp). The walk's session goes to out/session, its frames to out/day-frames.
if [ ! -x ./build/bench/gusuku-view ] || ! command -v img2webp >/dev/null; then
  echo "== day.webp not made: needs build/bench/gusuku-view (GLFW) and img2webp (bash scripts/install-deps.sh)" >&2
  exit 0
fi
echo "== day (08:00 to 17:00, a cloud passing, beside direct-only)"
./build/bench/gusuku-view --sample-session out/session "$bakeset" --walk-size 320x180
./build/bench/gusuku-view --render out/day-frames out/session --beside-direct-only --mode proposed_ground_match
# Lossy at quality 70, 4 frames a second, looping: 28 frames of 640 x 180 in a few hundred KB.
img2webp -loop 0 -lossy -q 70 -m 6 -d 250 out/day-frames/frame_*.png -o "$out/day.webp"
ls -l "$out/day.webp"
