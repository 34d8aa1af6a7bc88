#!/usr/bin/env bash
# The tracer's speed, one kernel against another in one run: bakes the same site with two gusuku-bake
# binaries (say today's from git HEAD, and a changed one), interleaved A B B A per round so that drift in a
# shared machine's speed falls on both, and reports each bake's rays per second (wall clock, as the bake
# prints it) and rays per CPU second (user + system time of the bake process: less sensitive to other load),
# their medians and the ratios new / base. Then checks that the two bakes wrote the same bytes (every EXR of
# the bake set), which holds when the change leaves the sampling alone.
#
# usage: bench/tracer_speed.sh BASE_BAKE NEW_BAKE [ROUNDS=3] [SAMPLES=32] [SITE_JSON]
#   SITE_JSON defaults to the sample site, written once into $TMPDIR by BASE_BAKE sample.
#   NEW_BAKE_FLAGS (environment): extra options for NEW_BAKE's bakes only, e.g. --uniform-sampling to compare
#   a binary with adaptive sampling against one from before it, where the bytes should then match.
# Only ratios within one run mean anything on a shared machine; the load average is printed before and after.
set -euo pipefail

if [[ $# -lt 2 ]]; then
    sed -n '2,12p' "$0" >&2
    exit 2
fi
base_bake=$(realpath "$1")
new_bake=$(realpath "$2")
rounds=${3:-3}
samples=${4:-32}
work=$(mktemp -d "${TMPDIR:-/tmp}/tracer_speed.XXXXXX")
trap 'rm -rf "$work"' EXIT

site_json=${5:-}
if [[ -z "$site_json" ]]; then
    "$base_bake" sample "$work/site" --force >/dev/null
    site_json="$work/site/site.json"
fi

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)  ($(nproc) cores)"
echo "site: $site_json, $samples samples, $rounds rounds (A B B A)"
printf '%-5s %-4s %12s %10s %10s %14s\n' round bake rays "Mrays/s" "cpu s" "Mrays/cpu-s"

# One bake; appends "wall_mrays cpu_mrays" to $work/NAME.txt and keeps its output in $work/out-NAME.
bake() {
    local name=$1 binary=$2 round=$3
    local out="$work/out-$name"
    local flags=""
    [[ "$name" == new ]] && flags=${NEW_BAKE_FLAGS:-}
    /usr/bin/time -f '%U %S' -o "$work/time.txt" \
        "$binary" bake "$site_json" -o "$out" --samples "$samples" --force --quiet $flags >"$work/log.txt" 2>&1 || {
        cat "$work/log.txt" >&2
        exit 1
    }
    local rays wall cpu
    rays=$(sed -n 's/^rays: *\([0-9.e+]*\) traced.*/\1/p' "$work/log.txt")
    wall=$(sed -n 's/^rays:.* \([0-9.]*\) Mrays\/s.*/\1/p' "$work/log.txt")
    cpu=$(awk '{print $1 + $2}' "$work/time.txt")
    local cpu_mrays
    cpu_mrays=$(awk -v r="$rays" -v c="$cpu" 'BEGIN {printf "%.3f", r / c / 1e6}')
    printf '%-5s %-4s %12s %10s %10s %14s\n' "$round" "$name" "$rays" "$wall" "$cpu" "$cpu_mrays"
    echo "$wall $cpu_mrays" >>"$work/$name.txt"
}

for ((round = 1; round <= rounds; ++round)); do
    bake base "$base_bake" "$round"
    bake new "$new_bake" "$round"
    bake new "$new_bake" "$round"
    bake base "$base_bake" "$round"
done

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
base_wall=$(cut -d' ' -f1 "$work/base.txt" | median)
new_wall=$(cut -d' ' -f1 "$work/new.txt" | median)
base_cpu=$(cut -d' ' -f2 "$work/base.txt" | median)
new_cpu=$(cut -d' ' -f2 "$work/new.txt" | median)
echo "median Mrays/s (wall):  base $base_wall  new $new_wall  ratio $(awk -v a="$new_wall" -v b="$base_wall" 'BEGIN {printf "%.2f", a / b}')"
echo "median Mrays/cpu-s:     base $base_cpu  new $new_cpu  ratio $(awk -v a="$new_cpu" -v b="$base_cpu" 'BEGIN {printf "%.2f", a / b}')"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

different=0
for exr in "$work"/out-base/*.exr; do
    if ! cmp -s "$exr" "$work/out-new/$(basename "$exr")"; then
        echo "differs: $(basename "$exr")"
        different=1
    fi
done
if [[ $different == 0 ]]; then
    echo "outputs: every EXR of the two bake sets is byte-identical"
fi
exit $different
