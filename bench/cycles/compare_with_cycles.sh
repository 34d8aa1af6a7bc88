#!/usr/bin/env bash
# gusuku against Blender's Cycles (the tool the paper baked with) on the sample site's overcast slot, on this
# machine, in one run: relative RMS error of the building lightmap against each tool's own converged bake, and
# the time each took to get there (the faster of two interleaved timings of each bake). Takes about 17 minutes
# on 2 cores.
#
# Needs a built gusuku (scripts/build.sh) and Debian's Blender: apt-get install blender python3-numpy.
# Usage: bench/cycles/compare_with_cycles.sh [OUT_DIR]   (default out/cycles-comparison)
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-out/cycles-comparison}
bake=${GUSUKU_BAKE:-./build/baker/gusuku-bake}
command -v blender >/dev/null || { echo "compare_with_cycles: needs Blender (apt-get install blender python3-numpy)" >&2; exit 1; }
mkdir -p "$out"
"$bake" sample "$out/sample" --force > /dev/null
# The bake set supplies the building with gusuku's lightmap charts (TEXCOORD_1), so both tools bake the same
# texels; its overcast lightmap (1024 samples) is the cross-check of what Cycles converges to. No --force: a
# second run with the same inputs finds the bake set up to date and skips it.
"$bake" bake "$out/sample/site.json" -o "$out/bakeset" --samples 1024 --quiet > /dev/null

# This machine is shared: its speed can drift by tens of percent within minutes. The same short gusuku study
# before and after Cycles shows how far it drifted while the two were measured.
drift_check() {
  "$bake" converge "$out/sample/site.json" --slot overcast --max-samples 64 --reference-samples 64 2>/dev/null |
    sed -n 's/^rays per second: //p'
}

echo "== gusuku (lavapipe, $(nproc) cores)"
"$bake" converge "$out/sample/site.json" --slot overcast --max-samples 512 --reference-samples 4096 \
  2>/dev/null | tee "$out/gusuku.txt"

drift_before=$(drift_check)

echo "== Cycles (Blender $(blender --version 2>/dev/null | head -1 | awk '{print $2}'), CPU, 2 threads)"
blender -b --factory-startup --python bench/cycles/cycles_lightmap_bake.py -- \
  "$out/bakeset" "$out/sample/site.glb" "$out/sample/sky_overcast.hdr" 4096 1 2 4 8 16 32 64 128 256 512 2>&1 |
  grep -E "^CYCLES_(RESULT|AGREEMENT)" | tee "$out/cycles.txt"
drift_after=$(drift_check)

# Timings repeated, interleaved (gusuku, Cycles, gusuku, Cycles): errors do not change between runs (fixed
# seeds), and the summary takes the faster of the two timings of each bake, which damps the machine's drift.
echo "== timing repeat (gusuku, then Cycles)"
"$bake" converge "$out/sample/site.json" --slot overcast --max-samples 512 --reference-samples 1 \
  2>/dev/null > "$out/gusuku_repeat.txt"
blender -b --factory-startup --python bench/cycles/cycles_lightmap_bake.py -- \
  "$out/bakeset" "$out/sample/site.glb" "$out/sample/sky_overcast.hdr" 0 1 2 4 8 16 32 64 128 256 512 2>&1 |
  grep -E "^CYCLES_TIMING" > "$out/cycles_repeat.txt"

echo "== drift check (the same 64-sample gusuku study before and after Cycles' first run)"
echo "drift_check_before_cycles_mrays_per_s $drift_before" | tee "$out/drift.txt"
echo "drift_check_after_cycles_mrays_per_s $drift_after" | tee -a "$out/drift.txt"

echo "== side by side"
python3 bench/cycles/summarise_comparison.py "$out"
