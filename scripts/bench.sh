#!/usr/bin/env bash
# The whole benchmark in one command (docs/measurements.md, "The benchmark" and "Real-model sites"): the sample's
# bake, gusuku-bench on the sample (every section), the real-model sites (scripts/bench-sites.sh: the sample, the
# shared shrine and the shared house from a visitor's poses) and every goal's reading, all into bench/results; then
# README.md's figures (scripts/readme-figures.py) from what it wrote. No figure there or in bench/results/README.md
# is typed by hand.
#
# Usage: scripts/bench.sh [--quick | --budget] [--driver D] [-o DIR] [BAKESET]
#   (no option)  the full settings: the sample's accuracy at 320x180 with 512-sample truths, the day every 15
#                minutes, 40 timed frames; the sites' accuracy at 1280x720 with 512-sample truths. About an hour
#                for the sample and 85 minutes a real site on 2 shared cores with new truths.
#   --budget     the settings that fit about 45 minutes on 2 shared cores with new truths: gusuku-bench --quick
#                (15 timed frames, the day every 2 hours, weather sweeps 96x54 at 64 samples, the tracer timed up
#                to 4 samples) with the sample's accuracy at 320x180 and 256-sample truths, and the sites' at
#                320x180 with 128-sample truths. The frame-time goals are read at 1280x720 in every setting, at
#                the runtime's default options (RuntimeOptions' own, which gusuku-bench starts from).
#   --quick      the plumbing check: gusuku-bench --quick everywhere (160x90, 128 samples); a few minutes once
#                the bakes are there. Its figures are not for README.md: use it with -o.
#   -o DIR       where the results go (default bench/results); README.md's figures are pasted only for
#                bench/results.
#   BAKESET      the sample's bake set (default: WORK/sample/bakeset, which this script bakes when it is not up
#                to date with this build's sample; its bake's summary is one of README.md's figures).
#   --driver D   the Vulkan driver every tool runs on: lavapipe (the default: whatever the loader picks, lavapipe
#                on the CI kind of machine) or swiftshader (Debian's chromium's SwiftShader through
#                VK_ICD_FILENAMES; GUSUKU_SWIFTSHADER_ICD names another ICD manifest). run.json records the device.
#                Not lavapipe: needs -o DIR (bench/results and README.md's figures are lavapipe's).
# GUSUKU_BENCH, GUSUKU_BAKE: another build's tools (GUSUKU_BENCH_CODE: the commit they were built from).
# WORK (GUSUKU_BENCH_WORK, default out/sites): the bakes, the truth cache (WORK/bench-cache) and the sites' full
# results, outside git's view. Path-traced frames are cached by key, so a rerun traces only what changed.
# Writes in DIR: the sample's results.json, chart.svg, chart.json, day.svg, summary.md, frames/ (gusuku-bench's), bake.txt
# (the sample bake's own figures), sites/SITE/{results.json,summary.md} and sites/summary.md (the sites' table),
# goals.md (every goal's reading), run.json (settings, driver, commit) and README.md's pasted summary.
# Without ../shared/data (GUSUKU_SHARED_DATA) the real-model sites and the photographed skies are skipped, said so.
set -euo pipefail
cd "$(dirname "$0")/.."
setting=full
out=bench/results
bakeset=""
driver=lavapipe
while [[ $# -gt 0 ]]; do
  case "$1" in
    --quick) setting=quick ;;
    --budget) setting=budget ;;
    --driver) driver="$2"; shift ;;
    -o) out="$2"; shift ;;
    -*) echo "scripts/bench.sh: $1: unknown option (see the comment at the top)" >&2; exit 2 ;;
    *) bakeset="$1" ;;
  esac
  shift
done
case "$driver" in
  lavapipe) ;;
  swiftshader)
    icd="${GUSUKU_SWIFTSHADER_ICD:-/usr/lib/chromium/vk_swiftshader_icd.json}"
    [[ -f "$icd" ]] || { echo "scripts/bench.sh: --driver swiftshader: $icd is missing (Debian's chromium package" \
                              "provides it; scripts/install-deps.sh installs it)" >&2; exit 2; }
    [[ "$out" != bench/results ]] || { echo "scripts/bench.sh: --driver swiftshader: give -o DIR" \
                                            "(bench/results holds lavapipe's figures)" >&2; exit 2; }
    export VK_ICD_FILENAMES="$icd"
    unset VK_DRIVER_FILES VK_ADD_DRIVER_FILES ;;
  *) echo "scripts/bench.sh: --driver $driver: lavapipe or swiftshader" >&2; exit 2 ;;
esac
# sites_quick goes before bench-sites.sh's WORK_DIR, sites_options after it (to every gusuku-bench run there).
case "$setting" in
  full)   sample_options=();                                                    sites_quick=();        sites_options=(--accuracy-size 1280x720 --truth-samples 512) ;;
  budget) sample_options=(--quick --accuracy-size 320x180 --truth-samples 256); sites_quick=(--quick); sites_options=(--accuracy-size 320x180 --truth-samples 128) ;;
  quick)  sample_options=(--quick);                                             sites_quick=(--quick); sites_options=() ;;
esac
bench="${GUSUKU_BENCH:-./build/bench/gusuku-bench}"  # GUSUKU_BENCH, GUSUKU_BAKE: another build's tools
bake="${GUSUKU_BAKE:-./build/baker/gusuku-bake}"
export GUSUKU_BENCH="$bench" GUSUKU_BAKE="$bake"
work="${GUSUKU_BENCH_WORK:-out/sites}"
shared="${GUSUKU_SHARED_DATA:-../shared/data}"
started_utc="$(date -u +%Y-%m-%dT%H:%M:%SZ)"
start_seconds=$SECONDS
# The code the figures come from: the working tree as the run starts, or GUSUKU_BENCH_CODE (the commit that
# GUSUKU_BENCH and GUSUKU_BAKE were built from, when they are copies of another build's tools).
code="${GUSUKU_BENCH_CODE:-$(git rev-parse --short HEAD 2>/dev/null || echo 'not a git checkout')$(git diff --quiet HEAD 2>/dev/null || echo ' with uncommitted changes')}"
command_line="scripts/bench.sh"
[[ "$setting" != full ]] && command_line+=" --$setting"
[[ "$out" != bench/results ]] && command_line+=" -o $out"
[[ "$driver" != lavapipe ]] && command_line+=" --driver $driver"

mkdir -p "$work"
if [[ -z "$bakeset" ]]; then
  # The sample as this build writes it (its files replaced), baked unless its bake set is up to date; bench-sites.sh
  # then finds it up to date. The bake's summary (WORK/sample/bake.txt, with the code that baked it) is one of
  # README.md's figures: a bake set that was up to date keeps the summary of the bake that made it.
  "$bake" sample "$work/sample" --force > /dev/null
  "$bake" bake "$work/sample/site.json" -o "$work/sample/bakeset" --quiet > "$work/sample/bake.tmp"
  if grep -q '^wall time:' "$work/sample/bake.tmp"; then
    printf 'baked by: %s\n' "$code" >> "$work/sample/bake.tmp"
    mv "$work/sample/bake.tmp" "$work/sample/bake.txt"
  else
    rm -f "$work/sample/bake.tmp"
  fi
  bakeset="$work/sample/bakeset"
  bake_log="$work/sample/bake.txt"
else
  bake_log=""
fi

# The photographed skies: the same site baked under ../shared/data/env's clear sky and overcast sky, when those
# files are there (they are never copied into the repository). Not in the quick run.
photographed=()
env_dir="$shared/env"
if [[ "$setting" != quick ]]; then
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
    mkdir -p "$work/photographed"
    python3 - "$site_json" "$env_dir" "$work/photographed/site.json" <<'PY'
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
    "$bake" bake "$work/photographed/site.json" -o "$work/photographed/bakeset" --quiet > /dev/null
    photographed=(--photographed-skies "$work/photographed/bakeset")
  else
    echo "scripts/bench.sh: skipping the photographed skies: $env_dir/rooitou_park_1k.hdr or potsdamer_platz_1k.hdr not found"
  fi
fi

# The previous run's results go, all but DIR/README.md (its text around the markers is kept).
mkdir -p "$out"
find "$out" -mindepth 1 -maxdepth 1 ! -name README.md -exec rm -rf {} +
"$bench" "$bakeset" -o "$out" --cache "$work/bench-cache" "${sample_options[@]}" "${photographed[@]}" > "$work/sample-bench.log"
if [[ -n "$bake_log" ]]; then cp "$bake_log" "$out/bake.txt"; fi
echo "scripts/bench.sh: the sample benched ($out/summary.md)"

# The real-model sites, with the sample from the same poses (its bake set is the one above, up to date).
sites_ran=no
GUSUKU_SHARED_DATA="$shared" bash scripts/bench-sites.sh "${sites_quick[@]}" "$work" "${sites_options[@]}" \
  > "$work/bench-sites.log" 2>&1 || { cat "$work/bench-sites.log" >&2; exit 1; }
if [[ -f "$work/summary.md" && "$work/summary.md" -nt "$work/sample-bench.log" ]]; then
  for site in sample shrine house; do
    mkdir -p "$out/sites/$site"
    cp "$work/$site/bench/results.json" "$work/$site/bench/summary.md" "$out/sites/$site/"
  done
  cp "$work/summary.md" "$out/sites/summary.md"
  sites_ran=yes
else
  tail -n 3 "$work/bench-sites.log"
fi

# What ran, for the README's "which driver and settings gave each figure".
python3 - "$out" "$setting" "$command_line" "$code" "$started_utc" "$((SECONDS - start_seconds))" "$sites_ran" \
  "${sample_options[*]:-(defaults)}" "${sites_quick[*]} ${sites_options[*]}" <<'PY'
import json, os, sys
out, setting, command, code, started, seconds, sites_ran, sample_options, sites_options = sys.argv[1:]
sample = json.load(open(os.path.join(out, "results.json")))["run"]
run = {"command": command, "setting": setting, "code": code, "started_utc": started, "seconds": int(seconds),
       "device": sample["device"], "cpu": sample["cpu"], "logical_cpus": sample["logical_cpus"],
       "sample_bench_options": sample_options,
       "sites_bench_options": (sites_options.strip() + " --only site --views ... (scripts/bench-sites.sh)").strip()
                              if sites_ran == "yes" else None}
tmp = os.path.join(out, "run.json.tmp")
json.dump(run, open(tmp, "w"), indent=2)
os.replace(tmp, os.path.join(out, "run.json"))
PY
python3 scripts/bench-goals.py "$out" > "$out/goals.md"
printf '\ncode: %s; command: %s\n' "$code" "$command_line" >> "$out/summary.md"

# The summary, the sites' table and the goals between the <!-- bench:begin --> and <!-- bench:end --> markers of
# DIR/README.md (bench/results/README.md's text around them is kept).
if [[ -f "$out/README.md" ]]; then
  python3 - "$out" <<'PY'
import os, sys
out = sys.argv[1]
path = os.path.join(out, "README.md")
readme = open(path).read()
pasted = open(os.path.join(out, "goals.md")).read() + "\n" + open(os.path.join(out, "summary.md")).read()
if os.path.isfile(os.path.join(out, "sites", "summary.md")):
    pasted += "\n" + open(os.path.join(out, "sites", "summary.md")).read()
begin, end = "<!-- bench:begin -->", "<!-- bench:end -->"
if begin not in readme or end not in readme:
    raise SystemExit("scripts/bench.sh: " + path + ": the <!-- bench:begin --> / <!-- bench:end --> markers are missing")
head, rest = readme.split(begin, 1)
_, tail = rest.split(end, 1)
open(path + ".tmp", "w").write(head + begin + "\n" + pasted + end + tail)
os.replace(path + ".tmp", path)
PY
fi
if [[ "$out" == bench/results ]]; then
  python3 scripts/readme-figures.py
  echo "scripts/bench.sh: README.md's figures and bench/results/README.md now from this run ($((SECONDS - start_seconds)) s)"
else
  echo "scripts/bench.sh: results in $out ($((SECONDS - start_seconds)) s); README.md left as it is"
fi
