#!/usr/bin/env bash
# The main job on the bundled sample site: install, build, generate the sample site, bake it, render its
# composites with the runtime, and print the benchmark's summary (a short run).
# Outputs land in out/sample (the site), out/bakeset (the bake set), out/composites and out/bench-quick.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/baker/gusuku-bake sample out/sample --force
./build/baker/gusuku-bake sun --lat 26.2856 --lon 127.8008 --height 160 --time 2026-06-21T09:00:00+09:00
./build/baker/gusuku-bake bake out/sample/site.json -o out/bakeset --force
# Composites of the sample at 09:00, 12:00, 15:00, 16:30 and overcast, each beside direct-only, into out/composites.
bash scripts/render-composites.sh out/bakeset out/composites 480x270 32
# The benchmark's short run: frame time against accuracy to a path-traced truth (docs/measurements.md, "The benchmark").
./build/bench/gusuku-bench out/bakeset -o out/bench-quick --cache out/bench-cache --quick
