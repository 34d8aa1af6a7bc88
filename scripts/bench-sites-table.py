#!/usr/bin/env python3
"""The per-site table of scripts/bench-sites.sh, from each site's gusuku-bench results.json (its site section).

Usage: bench-sites-table.py WORK_DIR SITE...   (reads WORK_DIR/SITE/bench/results.json; prints markdown)
Exit status 1, with one line naming the file and the field, when a results.json is missing or has no site section.
"""
import json
import os
import sys


def fail(message):
    print("bench-sites-table: " + message, file=sys.stderr)
    sys.exit(1)


def site_section(path):
    try:
        with open(path) as stream:
            results = json.load(stream)
    except FileNotFoundError:
        fail(path + ": not found (did gusuku-bench run?)")
    except json.JSONDecodeError as error:
        fail(path + ": invalid JSON: " + str(error))
    if not isinstance(results.get("site"), dict) or not results["site"].get("views"):
        fail(path + ": /site/views: missing (a run without --views)")
    return results["site"]


def fixed(value, digits=2):
    return "n/a" if value is None else f"{value:.{digits}f}"


def held(value):
    return "n/a" if value is None else ("held" if value else "NOT held")


def main():
    if len(sys.argv) < 3:
        print("usage: bench-sites-table.py WORK_DIR SITE...", file=sys.stderr)
        sys.exit(2)
    work, names = sys.argv[1], sys.argv[2:]
    sites = [(name, site_section(os.path.join(work, name, "bench", "results.json"))) for name in names]
    first = sites[0][1]
    print(f"**Real-model sites: the goals from each pose** (accuracy {first['size']}, truth {first['truth_samples']} "
          "spp, sunny; mean dE00 over the building and its shadow, baked instant / 1.5 h from it; frames 1280x720, "
          "median ms)")
    print()
    print("| site | triangles | pose | truth noise | proposed | direct-only | proposed / direct-only | "
          "frame proposed / direct-only | frame ratio | over the sample's |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for name, site in sites:
        for view in site["views"]:
            rows = {row["instant"]: row for row in view["accuracy"]}
            def both(key):
                return " / ".join(fixed(rows[i][key]["building_and_shadow"]["mean_de00"]) for i in ("baked", "between"))
            ratio = " / ".join(fixed(rows[i]["proposed_over_direct_only"], 3) for i in ("baked", "between"))
            frame = view["frame_1280x720"]
            print(f"| {name} | {site['building_triangles']} | {view['name']} | {both('truth_noise')} | "
                  f"{both('proposed')} | {both('direct_only')} | {ratio} | {fixed(frame['proposed_ms'], 1)} / "
                  f"{fixed(frame['direct_only_ms'], 1)} | {fixed(frame['proposed_over_direct_only'], 3)} | "
                  f"{fixed(frame['over_sample'])} |")
    print()
    print("| site | within 2 at the baked instant | within 3 1.5 h from it | below a third of direct-only's | "
          "frame within 1.10x of direct-only's | frame at most 2x the sample's |")
    print("| --- | --- | --- | --- | --- | --- |")
    for name, site in sites:
        goals = site["goals"]
        marks = goals["held"]
        print(f"| {name} | {fixed(goals['baked_error_worst'])} {held(marks['baked_error'])} | "
              f"{fixed(goals['between_error_worst'])} {held(marks['between_error'])} | "
              f"{fixed(goals['error_ratio_worst'], 3)} {held(marks['error_ratio'])} | "
              f"{fixed(goals['frame_ratio_worst'], 3)} {held(marks['frame_ratio'])} | "
              f"{fixed(goals['over_sample_worst'])} {held(marks['over_sample'])} |")
    print()
    print("(worst pose per goal; the sample is the reference of the last column)")


if __name__ == "__main__":
    main()
