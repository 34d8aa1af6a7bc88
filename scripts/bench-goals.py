#!/usr/bin/env python3
"""Every goal's reading from one scripts/bench.sh run, as markdown: the sample's goals (gusuku-bench's main section,
DIR/results.json) and each real-model site's (its site section, DIR/sites/SITE/results.json), with the run's
settings and driver (DIR/run.json).

Usage: bench-goals.py DIR   (prints markdown; scripts/bench.sh writes it to DIR/goals.md)
Exit status 1, with one line naming the file and the field, when a file or a field is missing.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_results  # noqa: E402  (beside this script)
from bench_results import SITES, fail, field, load  # noqa: E402

bench_results.TOOL = "bench-goals"


def held(value):
    return "n/a" if value is None else ("held" if value else "**NOT held**")


def fixed(value, digits):
    return "n/a" if value is None else f"{value:.{digits}f}"


def runtime_settings(out):
    """The runtime options the sample's frames were timed at, as its results.json records them (the bench's
    defaults are RuntimeOptions' own, never restated: tests/test_bench_tool_defaults.cpp)."""
    path = os.path.join(out, "results.json")
    runtime = field(load(path), path, ["run", "runtime"])
    return f"msaa {runtime['msaa_samples']}, anisotropy {runtime['max_anisotropy']:g}"


def sample_rows(out):
    path = os.path.join(out, "results.json")
    results = load(path)
    frame = field(results, path, ["goals", "frame_time_over_direct_only"])
    error = field(results, path, ["goals", "error_over_direct_only"])
    tracer = field(results, path, ["goals", "tracer_time_to_reach_proposed_error"])
    truth = field(results, path, ["truth"])
    where = f"sample, default view (accuracy {truth['size']}, truth {truth['samples_per_pixel']} spp)"
    reached = "" if tracer["reached_by"] is None else f" ({tracer['reached_by']})"
    return [
        (where, "frame time, proposed over direct-only, 1280x720", fixed(frame["1280x720"], 3),
         f"at most {frame['limit']:.2f} (goal {frame['goal']:.2f})", held(frame["held_1280x720"])),
        (where, "frame time, proposed over direct-only, 640x360", fixed(frame["640x360"], 3),
         f"at most {frame['limit']:.2f} (goal {frame['goal']:.2f})", held(frame["held_640x360"])),
        (where, "error over direct-only's (building and shadow, mean dE00)", fixed(error["ratio"], 3),
         f"below {error['goal_below']:.3f}", held(error["held"])),
        (where, "path tracer's time to the proposed error, over the proposed frame's",
         f"{tracer['ratio_over_proposed']:.0f}x{reached}" + (" (lower bound)" if tracer["is_lower_bound"] else ""),
         f"at least {tracer['goal_at_least']:.0f}x", held(tracer["held"])),
    ]


def site_rows(out, name):
    path = os.path.join(out, "sites", name, "results.json")
    site = field(load(path), path, ["site"])
    goals = field(site, path, ["goals"]) if isinstance(site, dict) else None
    marks = goals["held"]
    where = (f"{name} ({site['building_triangles']} triangles), worst of {len(site['views'])} poses "
             f"(accuracy {site['size']}, truth {site['truth_samples']} spp)")
    over_sample_limit = "n/a (the reference)" if goals["over_sample_worst"] is None else \
        f"at most {goals['over_sample_limit']:.0f}x"
    return [
        (where, "mean dE00 at the baked instant", fixed(goals["baked_error_worst"], 2),
         f"at most {goals['baked_error_goal']:.0f}", held(marks["baked_error"])),
        (where, "mean dE00 1.5 hours from it", fixed(goals["between_error_worst"], 2),
         f"at most {goals['between_error_goal']:.0f}", held(marks["between_error"])),
        (where, "error over direct-only's", fixed(goals["error_ratio_worst"], 3),
         f"below {goals['error_ratio_goal_below']:.3f}", held(marks["error_ratio"])),
        (where, "frame time, proposed over direct-only, 1280x720", fixed(goals["frame_ratio_worst"], 3),
         f"at most {goals['frame_ratio_limit']:.2f} (goal {goals['frame_ratio_goal']:.2f})", held(marks["frame_ratio"])),
        (where, "frame over the sample's from the same pose", fixed(goals["over_sample_worst"], 2),
         over_sample_limit, held(marks["over_sample"])),
    ]


def main():
    if len(sys.argv) != 2:
        print("usage: bench-goals.py DIR", file=sys.stderr)
        sys.exit(2)
    out = sys.argv[1]
    run_path = os.path.join(out, "run.json")
    run = load(run_path)
    print(f"**Every goal's reading** (`{run['command']}` at {run['code']}, {run['started_utc']}, {run['seconds']} s; "
          f"{run['cpu']}, {run['logical_cpus']} logical CPUs; {run['device']})")
    print()
    print(f"settings: the sample `gusuku-bench {run['sample_bench_options']}`; the sites "
          + (f"`gusuku-bench {run['sites_bench_options']}`" if run["sites_bench_options"] else "not run")
          + "; frame times at 1280x720 at " + runtime_settings(out))
    print()
    print("| where | goal | reading | limit | held |")
    print("| --- | --- | --- | --- | --- |")
    rows = sample_rows(out)
    if run["sites_bench_options"]:
        for name in SITES:
            rows += site_rows(out, name)
    for row in rows:
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
