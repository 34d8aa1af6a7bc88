#!/usr/bin/env python3
"""README.md's figures, written from the committed benchmark (bench/results, what scripts/bench.sh wrote): the
text between the <!-- figures:begin --> and <!-- figures:end --> markers of README.md's "Figures" section.
scripts/bench.sh runs it after each run; the test readme_figures runs it with --check, so that the README and
bench/results cannot disagree.

Usage: readme-figures.py [--check] [--readme README.md] [--results bench/results]
  (no option)  rewrites the text between the markers
  --check      writes nothing; exit status 1, naming README.md and the first line that differs, when the text
               between the markers is not what bench/results gives
Exit status 1, with one line naming the file and the field, when a results file or a marker is missing.
"""
import argparse
import os
import re
import sys
import textwrap

BEGIN = "<!-- figures:begin: scripts/readme-figures.py writes this from bench/results; do not edit -->"
END = "<!-- figures:end -->"
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_results  # noqa: E402  (beside this script)
from bench_results import SITES, fail, field, load  # noqa: E402

bench_results.TOOL = "readme-figures"


def bake_figures(results_dir):
    """The sample bake's own summary lines (bake.txt: gusuku-bake bake --quiet), as the words of one figure."""
    path = os.path.join(results_dir, "bake.txt")
    try:
        text = open(path).read()
    except FileNotFoundError:
        fail(path + ": not found (scripts/bench.sh copies the sample bake's summary there)")
    lines = dict(re.findall(r"^([a-z ]+):\s*(.*)$", text, re.MULTILINE))
    for key in ("slots", "samples", "rays", "wall time"):
        if key not in lines:
            fail(path + ": " + key + ": missing (not gusuku-bake bake's summary)")
    return lines


def goal_words(held):
    return "held" if held else "not held"


def figures(results_dir):
    results_path = os.path.join(results_dir, "results.json")
    results = load(results_path)
    run = load(os.path.join(results_dir, "run.json"))
    truth = field(results, results_path, ["truth"])
    proposed = field(results, results_path, ["accuracy", "proposed"])
    direct = field(results, results_path, ["accuracy", "direct_only"])
    goals = field(results, results_path, ["goals"])
    frame = goals["frame_time_over_direct_only"]
    error = goals["error_over_direct_only"]
    bake = bake_figures(results_dir)
    lines = [
        f"From `{run['command']}` at {run['code']}, {run['started_utc'][:10]}, on {run['cpu']} ({run['logical_cpus']} "
        f"logical CPUs, shared) with lavapipe: {run['device']}; the settings and every goal's reading are in "
        "[bench/results/README.md](bench/results/README.md):",
        "",
        f"- **The sample bakes in {bake['wall time']}**: {bake['slots']} slots, {bake['samples'].split()[0]} samples a "
        f"texel, {bake['rays'].replace(' traced,', ' rays traced at')} (the bake at "
        f"{bake.get('baked by', 'an unrecorded commit')}).",
        f"- **{error['ratio']:.2f} of direct-only's error**: over the building and its shadow, mean CIEDE2000 against "
        f"a path-traced truth ({truth['size']}, {truth['samples_per_pixel']} spp) is "
        f"{proposed['building_and_shadow']['mean_de00']:.2f} for gusuku and "
        f"{direct['building_and_shadow']['mean_de00']:.2f} for direct-only (goal: below a third, "
        f"{goal_words(error['held'])}), at {proposed['frame_ms_640x360']:.1f} ms against "
        f"{direct['frame_ms_640x360']:.1f} ms a 640 x 360 frame.",
        f"- **{frame['1280x720']:.2f}x direct-only's frame time** at 1280 x 720 (limit {frame['limit']:.2f}, "
        f"{goal_words(frame['held_1280x720'])}).",
    ]
    if run.get("sites_bench_options"):
        sites = []
        for name in SITES[1:]:
            path = os.path.join(results_dir, "sites", name, "results.json")
            site = field(load(path), path, ["site"])
            sites.append((name, site, field(site, path, ["goals"])))
        first = sites[0][1]
        worded = "; ".join(
            f"the {name} ({site['building_triangles']:,} triangles) {goals['baked_error_worst']:.2f} at a baked "
            f"instant and {goals['between_error_worst']:.2f} 1.5 hours from it, {goals['error_ratio_worst']:.2f} of "
            f"direct-only's, its frame {goals['frame_ratio_worst']:.2f}x direct-only's"
            for name, site, goals in sites)
        lines.append(
            f"- **Real models** from a visitor's poses (worst of {len(first['views'])}; accuracy {first['size']}, "
            f"truth {first['truth_samples']} spp; goals within 2 and 3 dE00, below a third, 1.10x): {worded}.")
    # Wrapped as the README's own paragraphs are (120 columns; a bullet's lines continue under its text).
    wrapped = [textwrap.fill(line, width=116, subsequent_indent="  " if line.startswith("- ") else "",
                             break_long_words=False, break_on_hyphens=False) if line else line for line in lines]
    return "\n".join(wrapped) + "\n"


def main():
    parser = argparse.ArgumentParser(description="README.md's figures from bench/results")
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--readme", default="README.md")
    parser.add_argument("--results", default="bench/results")
    options = parser.parse_args()
    try:
        readme = open(options.readme).read()
    except FileNotFoundError:
        fail(options.readme + ": not found")
    if readme.count(BEGIN) != 1 or readme.count(END) != 1 or readme.index(BEGIN) > readme.index(END):
        fail(options.readme + ": figures: the markers " + BEGIN + " and " + END + " must appear once each, in order")
    head, rest = readme.split(BEGIN, 1)
    current, tail = rest.split(END, 1)
    wanted = "\n" + figures(options.results)
    if options.check:
        if current != wanted:
            have, want = current.splitlines(), wanted.splitlines()
            for number, (left, right) in enumerate(zip(have + [""] * len(want), want + [""] * len(have))):
                if left != right:
                    line = head.count("\n") + 1 + number
                    fail(f"{options.readme}: figures: line {line} is not what {options.results} gives "
                         f"(run scripts/readme-figures.py): has {left!r}, wants {right!r}")
        return
    output = head + BEGIN + wanted + END + tail
    with open(options.readme + ".tmp", "w") as stream:
        stream.write(output)
    os.replace(options.readme + ".tmp", options.readme)


if __name__ == "__main__":
    main()
