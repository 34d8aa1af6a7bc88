#!/usr/bin/env bash
# The benchmark's real-model sites (issue 20 item 5): the shared shrine and the shared house
# (../shared/data/building, CC-BY-4.0: see their SOURCE.md) on the sample terrace under the shared photographed
# skies (../shared/data/env), beside the sample itself, each read by gusuku-bench's site section from the same
# visitor poses: the composite's and direct-only's error against the path-traced truth at a baked instant and 1.5
# hours from it, the frame time of both at 1280x720, and the real model's frame against the sample's (timed in the
# same run, interleaved: --sample-bakeset).
#
# Usage: scripts/bench-sites.sh [--quick] [WORK_DIR [GUSUKU_BENCH_OPTION...]]   (default WORK_DIR: out/sites, outside
# git's view; options after it go to every gusuku-bench run, e.g. --accuracy-size 320x180 --truth-samples 256)
# The goals are read at the displayed frame's size with --accuracy-size 1280x720 --truth-samples 512 (about 85
# minutes for the shrine on 2 cores with new truths; docs/measurements.md, "Every site at 4386099").
# Writes, in WORK_DIR: sample/ (gusuku-bake sample), shrine/site.json and house/site.json (scripts/write-bench-site.py:
# they name the shared files by absolute path; nothing is copied), each site's bakeset/ and bench/ (gusuku-bench's
# results.json, summary.md, frames/), and summary.md: the per-site table, also printed. A bake already up to date
# is not redone. Bakes: the shrine 16 texels/m and the house 12, both 192 samples a texel (about 5 minutes each on
# 2 shared cores); the sample as `gusuku-bake sample` writes it (512 samples, under a minute).
# Without the shared data it prints why and exits 0, having run nothing. GUSUKU_SHARED_DATA: another data folder;
# GUSUKU_BENCH, GUSUKU_BAKE: another build's tools (GUSUKU_BENCH_CODE: the commit they were built from).
set -euo pipefail
cd "$(dirname "$0")/.."
quick=()
if [[ "${1:-}" == "--quick" ]]; then quick=(--quick); shift; fi
work="${1:-out/sites}"
[[ $# -gt 0 ]] && shift
bench_options=("$@")
shared="${GUSUKU_SHARED_DATA:-../shared/data}"
for needed in building/japan_temple_yankobe/scene.gltf building/playcanvas_house_lightmapUV/house.glb \
              env/rooitou_park_1k.hdr env/potsdamer_platz_1k.hdr; do
  if [[ ! -f "$shared/$needed" ]]; then
    echo "scripts/bench-sites.sh: skipping the real-model sites: $shared/$needed not found (the shared data is not there); nothing run"
    exit 0
  fi
done
bench="${GUSUKU_BENCH:-./build/bench/gusuku-bench}"
bake="${GUSUKU_BAKE:-./build/baker/gusuku-bake}"
# Two visitor poses, the same on every site (the buildings all stand where the sample house stands, origin at ENU
# (2, 4, 1.5) m on the terrace's top at 1.5 m): eye height 1.7 m, 9 m in front (south) and from the south-west.
views="front:2,-5,3.2:2,3.5,3;corner:-5,-2.5,3.2:2,3.5,2.8"
code="${GUSUKU_BENCH_CODE:-$(git rev-parse --short HEAD 2>/dev/null || echo 'not a git checkout')$(git diff --quiet HEAD 2>/dev/null || echo ' with uncommitted changes')}"

# The sample as this build writes it (--force: its files replaced, its bake set beside them kept).
"$bake" sample "$work/sample" --force > /dev/null
for site in shrine house; do
  python3 scripts/write-bench-site.py "$work/sample/site.json" "$shared" "$site" "$work/$site/site.json"
done
for site in sample shrine house; do
  start=$SECONDS
  "$bake" bake "$work/$site/site.json" -o "$work/$site/bakeset" --quiet | grep -E '^(building|ground|rays|wall time):' || true
  echo "scripts/bench-sites.sh: $site baked (or up to date) in $((SECONDS - start)) s"
done
for site in sample shrine house; do
  sample_reference=()
  [[ "$site" != sample ]] && sample_reference=(--sample-bakeset "$work/sample/bakeset")
  "$bench" "$work/$site/bakeset" -o "$work/$site/bench" --cache "$work/bench-cache" --only site --views "$views" \
    "${sample_reference[@]}" "${quick[@]}" "${bench_options[@]}" > "$work/$site/bench.log"
  echo "scripts/bench-sites.sh: $site benched ($work/$site/bench/summary.md)"
done
python3 scripts/bench-sites-table.py "$work" sample shrine house > "$work/summary.md.tmp"
printf '\ncode: %s; command: %s\n' "$code" "scripts/bench-sites.sh ${quick[*]:+${quick[*]} }$work${bench_options[*]:+ ${bench_options[*]}}" >> "$work/summary.md.tmp"
mv "$work/summary.md.tmp" "$work/summary.md"
cat "$work/summary.md"
