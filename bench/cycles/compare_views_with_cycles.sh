#!/usr/bin/env bash
# The bench's truth against an independent one (issue 20 item 6): Blender's Cycles renders gusuku-bench's visitor
# poses (cycles_view_render.py, from the site's own model files, lit by the baked slot's exported lighting), then
# gusuku-bench's site section reads them (--cycles-truth) and reports, per pose, its path tracer's difference from
# Cycles beside the tracer's own seed-to-seed noise, a verdict line, and the building's mean colour per material
# in the runtime's composite, the tracer's truth and Cycles' (item 9).
#
# Needs a built gusuku (gusuku-bake, gusuku-bench) and Debian's Blender: apt-get install blender python3-numpy.
# Usage: bench/cycles/compare_views_with_cycles.sh BAKESET SITE_JSON OUT_DIR
#   BAKESET: the site's bake set; SITE_JSON: the site it was baked from; OUT_DIR: lighting/, cycles/, bench/ (the
#   bench's results.json, summary.md, frames/) and bench-cache/ are written there.
# Settings (environment): VIEWS (default scripts/bench-sites.sh's two poses), SLOT (default sunny_1200: the slot
# the site section's baked instant falls on, the sunny slot nearest 12:00), CYCLES_SAMPLES (default 512: each of
# Cycles' two seeds), QUICK (default 1: the bench's --quick, 160x90 and 128 tracer samples; 0: 320x180, 512).
# The sample or the shrine at the defaults: 4 to 7 minutes each on 2 shared cores.
set -euo pipefail
cd "$(dirname "$0")/../.."
if [[ $# -ne 3 ]]; then
  echo "usage: bench/cycles/compare_views_with_cycles.sh BAKESET SITE_JSON OUT_DIR" >&2
  exit 2
fi
bakeset=$1 site_json=$2 out=$3
bake=${GUSUKU_BAKE:-./build/baker/gusuku-bake}
bench=${GUSUKU_BENCH:-./build/bench/gusuku-bench}
views=${VIEWS:-front:2,-5,3.2:2,3.5,3;corner:-5,-2.5,3.2:2,3.5,2.8}
slot=${SLOT:-sunny_1200}
samples=${CYCLES_SAMPLES:-512}
quick=${QUICK:-1}
command -v blender >/dev/null || { echo "compare_views_with_cycles: needs Blender (apt-get install blender python3-numpy)" >&2; exit 1; }
[[ -f "$bakeset/manifest.json" ]] || { echo "compare_views_with_cycles: $bakeset/manifest.json: not a bake set" >&2; exit 1; }
[[ -f "$site_json" ]] || { echo "compare_views_with_cycles: $site_json: not found" >&2; exit 1; }
quick_flag=() width=320 height=180
if [[ "$quick" == 1 ]]; then quick_flag=(--quick) width=160 height=90; fi
mkdir -p "$out"

"$bake" converge "$site_json" --slot "$slot" --export-lighting "$out/lighting"
start=$SECONDS
blender -b --factory-startup --python bench/cycles/cycles_view_render.py -- \
  "$site_json" "$out/lighting" "$slot" "$out/cycles" "$width" "$height" "$samples" "$views" > "$out/cycles.log" 2>&1 ||
  { tail -20 "$out/cycles.log" >&2; echo "compare_views_with_cycles: Blender failed (log: $out/cycles.log)" >&2; exit 1; }
echo "== $(blender --version 2>/dev/null | head -1): $width x $height, 2 x $samples samples a pixel, $((SECONDS - start)) s"
"$bench" "$bakeset" -o "$out/bench" --cache "$out/bench-cache" --site "$site_json" --only site --views "$views" \
  "${quick_flag[@]}" --cycles-truth "$out/cycles" > "$out/bench.log"
# The Cycles table and its verdict line, from the bench's summary.
sed -n '/^\*\*The truth against Blender Cycles/,/^cycles truth:/p' "$out/bench/summary.md"
