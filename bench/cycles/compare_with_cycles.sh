#!/usr/bin/env bash
# gusuku against Blender's Cycles (the tool the paper baked with), on this machine, in one run: relative RMS error
# of the building lightmap against each tool's own converged bake, and the wall time each took to get there, for
# every slot (overcast and sunny) of two sites: the sample site, and the shared shrine on the sample's terrace
# under the shared photographed skies (make_shrine_site.py; skipped with a message when ../shared/data is absent);
# SITES may also name house, the benchmark's shared house (scripts/write-bench-site.py).
#
# Needs a built gusuku (scripts/build.sh) and Debian's Blender: apt-get install blender python3-numpy.
# Usage: bench/cycles/compare_with_cycles.sh [OUT_DIR]   (default out/cycles-comparison)
# Settings (environment): SLOTS (default "overcast sunny_0900 sunny_1200 sunny_1500"), SITES (default "sample
# shrine"), MAX_SAMPLES (default 512: the studies double from 1 up to it), REFERENCE_SAMPLES (default 4096: each
# tool's converged bake; its own noise is measured and taken out, see cycles_lightmap_bake.py), CYCLES_MODES
# (default "fixed,adaptive"), REPEAT_TIMINGS (default 1: time each series twice, interleaved, keep the faster),
# SHARED_DATA (default ../shared/data), BAKE_SAMPLES (default 1024: the bake set whose lightmaps Cycles is checked against). The defaults take hours on 2 cores; MAX_SAMPLES=256 REFERENCE_SAMPLES=1024
# CYCLES_MODES=fixed REPEAT_TIMINGS=0 takes about 10 minutes a slot.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-out/cycles-comparison}
bake=${GUSUKU_BAKE:-./build/baker/gusuku-bake}
bake_samples=${BAKE_SAMPLES:-1024}
slots=${SLOTS:-overcast sunny_0900 sunny_1200 sunny_1500}
sites=${SITES:-sample shrine}
max_samples=${MAX_SAMPLES:-512}
reference=${REFERENCE_SAMPLES:-4096}
shared=${SHARED_DATA:-../shared/data}
export CYCLES_MODES=${CYCLES_MODES:-fixed,adaptive}
repeat=${REPEAT_TIMINGS:-1}
command -v blender >/dev/null || { echo "compare_with_cycles: needs Blender (apt-get install blender python3-numpy)" >&2; exit 1; }
counts=""
for ((n = 1; n <= max_samples; n *= 2)); do counts="$counts $n"; done
mkdir -p "$out"
"$bake" sample "$out/sample" --force > /dev/null

echo "== $(blender --version 2>/dev/null | head -1) (CPU, 2 threads) against gusuku (lavapipe, $(nproc) cores)"
for site in $sites; do
  site_json="$out/$site/site.json"
  if [[ "$site" == sample ]]; then
    site_json="$out/sample/site.json"
  elif [[ "$site" == shrine ]]; then
    python3 bench/cycles/make_shrine_site.py "$out/sample/site.json" "$shared" "$site_json" ||
      { echo "compare_with_cycles: skipping the shrine site"; continue; }
  elif [[ "$site" == house ]]; then
    # The benchmark's house site (scripts/bench-sites.sh): the shared house diorama at 12 texels a metre.
    python3 scripts/write-bench-site.py "$out/sample/site.json" "$shared" house "$site_json" ||
      { echo "compare_with_cycles: skipping the house site"; continue; }
  else
    echo "compare_with_cycles: unknown site '$site' (sample, shrine or house)" >&2; exit 1
  fi
  # The bake set supplies the building with gusuku's lightmap charts (TEXCOORD_1), so both tools bake the same
  # texels; its lightmaps are the cross-check of what Cycles converges to. No --force: a second run with the
  # same inputs finds it up to date.
  "$bake" bake "$site_json" -o "$out/$site/bakeset" --samples "$bake_samples" --quiet > /dev/null
  for slot in $slots; do
    dir="$out/$site/$slot"
    mkdir -p "$dir"
    echo "== $site, $slot"
    "$bake" converge "$site_json" --slot "$slot" --export-lighting "$dir/lighting"
    # Cycles first: it writes the texels it bakes (on the shrine's small triangles only those whose centre a
    # triangle covers) as a mask, and gusuku's study measures its error over those texels too (the common_*
    # columns), so that the two errors can be read over the same texels as well as each over its own.
    CYCLES_COVERAGE_MASK="$dir/cycles_texels.pgm" \
      blender -b --factory-startup --python bench/cycles/cycles_lightmap_bake.py -- \
      "$out/$site/bakeset" "$out/sample/site.glb" "$dir/lighting" "$slot" "$reference" $counts 2>&1 |
      grep -E "^CYCLES_(RESULT|AGREEMENT|REFERENCE|COVERAGE)" > "$dir/cycles.txt"
    "$bake" converge "$site_json" --slot "$slot" --max-samples "$max_samples" --reference-samples "$reference" \
      --error-mask "$dir/cycles_texels.pgm" 2>/dev/null > "$dir/gusuku.txt"
    if [[ "$repeat" == 1 ]]; then
      # Errors do not change between runs (fixed seeds): only the timings are repeated, interleaved with the
      # first ones, and the summary keeps the faster of each, which damps the shared machine's drift.
      "$bake" converge "$site_json" --slot "$slot" --max-samples "$max_samples" --reference-samples "$max_samples" \
        2>/dev/null > "$dir/gusuku_repeat.txt"
      blender -b --factory-startup --python bench/cycles/cycles_lightmap_bake.py -- \
        "$out/$site/bakeset" "$out/sample/site.glb" "$dir/lighting" "$slot" 0 $counts 2>&1 |
        grep -E "^CYCLES_TIMING" > "$dir/cycles_repeat.txt"
    fi
    python3 bench/cycles/summarise_comparison.py "$dir" | tee "$dir/summary.txt" || echo "compare_with_cycles: no summary for $site, $slot"
  done
done
echo "== every slot: wall seconds to 2 % relative RMS (reference noise taken out), setup included"
python3 bench/cycles/summarise_comparison.py --table "$out" "$sites" "$slots"
