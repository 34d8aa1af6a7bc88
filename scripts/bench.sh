#!/usr/bin/env bash
# Regenerates every figure and chart of the benchmark (docs/measurements.md, "The benchmark") from one gusuku-bench
# run, and pastes the run's summary (bench/results/summary.md, written by the bench itself) between the
# <!-- bench:begin --> and <!-- bench:end --> markers of bench/results/README.md: no figure there is typed by hand.
#
# Usage: scripts/bench.sh [--quick] [BAKESET]   (default BAKESET: out/bakeset). Results: bench/results/
# (results.json, chart.svg, chart.json, day.svg, summary.md, frames/, and README.md's pasted summary). The full
# run takes about an hour on 2 shared cores (most of it the day's truths); --quick one to two minutes.
# Path-traced frames are cached in out/bench-cache/ by key, so a rerun traces only what changed.
set -euo pipefail
cd "$(dirname "$0")/.."
quick=""
if [[ "${1:-}" == "--quick" ]]; then quick="--quick"; shift; fi
bakeset="${1:-out/bakeset}"
bench="${GUSUKU_BENCH:-./build/bench/gusuku-bench}"  # GUSUKU_BENCH: another build's gusuku-bench
bake="${GUSUKU_BAKE:-./build/baker/gusuku-bake}"
# The code the figures come from (the working tree as the run starts), for the summary's last line.
code="$(git rev-parse --short HEAD 2>/dev/null || echo 'not a git checkout')$(git diff --quiet HEAD 2>/dev/null || echo ' with uncommitted changes')"
# The photographed skies: the same site baked under ../shared/data/env's clear sky and
# overcast sky, when those files are there (they are never copied into the repository). Not in the quick run.
photographed=()
env_dir="../shared/data/env"
if [[ -z "$quick" ]]; then
  if [[ -f "$env_dir/rooitou_park_1k.hdr" && -f "$env_dir/potsdamer_platz_1k.hdr" ]]; then
    # The site the bake set was baked from (its manifest's "site" input: relative to where the bake ran, or to
    # the bake set's folder), under the photographed skies instead of its own.
    site_json="$(python3 - "$bakeset" <<'PY'
import json, os, sys
folder = sys.argv[1]
for entry in json.load(open(os.path.join(folder, "manifest.json")))["inputs"]:
    if entry["role"] == "site":
        path = entry["path"]
        for candidate in (path, os.path.join(folder, path)):
            if os.path.isfile(candidate):
                print(candidate)
                break
PY
)"
    if [[ -z "$site_json" ]]; then echo "scripts/bench.sh: $bakeset/manifest.json: inputs: its site.json is not found" >&2; exit 1; fi
    mkdir -p out/photographed
    python3 - "$site_json" "$env_dir" out/photographed/site.json <<'PY'
import json, os, sys
site_path, env_dir, output = sys.argv[1:]
site = json.load(open(site_path))
base = os.path.dirname(os.path.abspath(site_path))
for key in ("sfm_mesh", "building"):
    if key in site:
        site[key]["path"] = os.path.join(base, site[key]["path"])
# rooitou_park: clear sky, low sun (about 10 deg) whose disc the baker measures and carries to each slot's sun;
# potsdamer_platz: overcast. Their north is unknown (Poly Haven gives none): the image's u = 0 is taken as north.
site["skies"] = {
    "sunny": {"path": os.path.abspath(os.path.join(env_dir, "rooitou_park_1k.hdr")), "north_azimuth_in_image_deg": 0.0},
    "overcast": {"path": os.path.abspath(os.path.join(env_dir, "potsdamer_platz_1k.hdr")), "north_azimuth_in_image_deg": 0.0},
}
site["site"]["name"] = site["site"].get("name", "site") + ", photographed skies"
tmp = output + ".tmp"
json.dump(site, open(tmp, "w"), indent=2)
os.replace(tmp, output)
PY
    "$bake" bake out/photographed/site.json -o out/bakeset-photographed
    photographed=(--photographed-skies out/bakeset-photographed)
  else
    echo "scripts/bench.sh: skipping the photographed skies: $env_dir/rooitou_park_1k.hdr or potsdamer_platz_1k.hdr not found"
  fi
fi
# The previous run's results go, all but bench/results/README.md (its text around the markers is kept).
mkdir -p bench/results
find bench/results -mindepth 1 -maxdepth 1 ! -name README.md -exec rm -rf {} +
"$bench" "$bakeset" -o bench/results --cache out/bench-cache $quick "${photographed[@]}"
# The code the figures come from, as the summary's last line.
printf '\ncode: %s\n' "$code" >> bench/results/summary.md
python3 - <<'PY'
import os
path = "bench/results/README.md"
readme = open(path).read()
summary = open("bench/results/summary.md").read()
begin, end = "<!-- bench:begin -->", "<!-- bench:end -->"
if begin not in readme or end not in readme:
    raise SystemExit("scripts/bench.sh: " + path + ": the <!-- bench:begin --> / <!-- bench:end --> markers are missing")
head, rest = readme.split(begin, 1)
_, tail = rest.split(end, 1)
open(path + ".tmp", "w").write(head + begin + "\n" + summary + end + tail)
os.replace(path + ".tmp", path)
PY
echo "scripts/bench.sh: bench/results/README.md's figures now from bench/results/results.json"
