#!/usr/bin/env bash
# Regenerates every figure and chart README.md's "Benchmark" section quotes, from one gusuku-bench run, and
# pastes the run's summary (bench-results/summary.md, written by the bench itself) between the README's
# <!-- bench:begin --> and <!-- bench:end --> markers: no figure there is typed by hand.
#
# Usage: scripts/bench.sh [--quick] [BAKESET]   (default BAKESET: out/bakeset). Results: bench/results/
# (results.json, chart.svg, chart.json, day.svg, summary.md, frames/), the README's section from them. The full
# run takes about an hour on 2 shared cores (most of it the day's truths); --quick one to two minutes.
# Path-traced frames are cached in out/bench-cache/ by key, so a rerun traces only what changed.
set -euo pipefail
cd "$(dirname "$0")/.."
quick=""
if [[ "${1:-}" == "--quick" ]]; then quick="--quick"; shift; fi
bakeset="${1:-out/bakeset}"
bench="${GUSUKU_BENCH:-./build/bench/gusuku-bench}"  # GUSUKU_BENCH: another build's gusuku-bench
rm -rf bench/results
"$bench" "$bakeset" -o bench/results --cache out/bench-cache $quick
python3 - <<'PY'
import re
readme = open("README.md").read()
summary = open("bench/results/summary.md").read()
begin, end = "<!-- bench:begin -->", "<!-- bench:end -->"
if begin not in readme or end not in readme:
    raise SystemExit("scripts/bench.sh: README.md: the <!-- bench:begin --> / <!-- bench:end --> markers are missing")
head, rest = readme.split(begin, 1)
_, tail = rest.split(end, 1)
open("README.md.tmp", "w").write(head + begin + "\n" + summary + end + tail)
PY
mv README.md.tmp README.md
echo "scripts/bench.sh: README.md's Benchmark figures now from bench/results/results.json"
