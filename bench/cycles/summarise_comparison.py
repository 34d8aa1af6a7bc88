#!/usr/bin/env python3
"""Puts gusuku's and Cycles' error-against-time curves from one comparison run side by side.

Reads OUT/gusuku.txt (the table `gusuku-bake converge` prints) and OUT/cycles.txt (the CYCLES_* lines of
cycles_lightmap_bake.py), prints the time each baker needs to reach 10, 5, 3 and 2 % relative RMS, and writes
OUT/error_vs_time.svg: relative RMS against seconds on log-log axes, one curve per method.

Cycles runs twice, with every texel taking all its samples (fixed, as gusuku does) and with its default adaptive
sampling. Fairness: Cycles' seconds are whole bake calls (scene sync, BVH and the bake itself); gusuku's trace seconds
exclude its one-off setup (sky tables, charts, BVH, pipelines), so the table shows gusuku both without and with
that setup added. The denoised curve includes the filter's own time where the study printed it.

Python's standard library only, so it runs wherever the comparison runs.
Usage: summarise_comparison.py OUT_DIR
       summarise_comparison.py --table OUT_DIR "SITE..." "SLOT..."   (one line per slot: seconds to 2 %, ratios)

Errors are the columns with each reference's own noise taken out where the inputs have them
(rel_rms_corrected, relative_rms_corrected).
"""
import math
import os
import re
import sys

TARGETS = [0.10, 0.05, 0.03, 0.02]


def read_gusuku(path):
    """Rows of the converge table as dicts keyed by its header, plus the setup seconds (0 when not printed)."""
    rows, header, setup_seconds = [], None, 0.0
    with open(path) as stream:
        for line in stream:
            setup = re.search(r"setup before the first ray ([0-9.]+) s", line)
            if setup:
                setup_seconds = float(setup.group(1))
            fields = line.split()
            if fields and fields[0] == "samples":
                header = fields
            elif header and fields and fields[0].isdigit() and len(fields) == len(header):
                rows.append(dict(zip(header, (float(f) for f in fields))))
    if not rows:
        sys.exit(f"summarise_comparison: {path}: no convergence table found")
    return rows, setup_seconds


def read_cycles(path):
    """{mode: [(samples, seconds, relative_rms), ...]} from the CYCLES_RESULT lines, mode "fixed" or "adaptive";
    the error with the reference's own noise taken out where the line has it."""
    curves = {}
    with open(path) as stream:
        for line in stream:
            match = re.match(r"CYCLES_RESULT mode=(\w+) samples=(\d+) seconds=([0-9.]+) relative_rms=([0-9.]+)"
                             r"(?: relative_rms_corrected=([0-9.]+))?", line)
            if match:
                rms = float(match.group(5) if match.group(5) is not None else match.group(4))
                curves.setdefault(match.group(1), []).append((int(match.group(2)), float(match.group(3)), rms))
    if not curves:
        sys.exit(f"summarise_comparison: {path}: no CYCLES_RESULT lines found")
    return curves


def read_cycles_repeat(path):
    """{(mode, samples): seconds} from a timing-only repeat; empty when there was none."""
    timings = {}
    if os.path.exists(path):
        with open(path) as stream:
            for line in stream:
                match = re.match(r"CYCLES_TIMING mode=(\w+) samples=(\d+) seconds=([0-9.]+)", line)
                if match:
                    timings[(match.group(1), int(match.group(2)))] = float(match.group(3))
    return timings


def faster_of_two_runs(gusuku_rows, setup_seconds, gusuku_repeat_path, cycles_curves, cycles_repeat_path):
    """Each bake's time as the faster of its two timings (the machine drifts; errors are the same both times)."""
    if os.path.exists(gusuku_repeat_path):
        repeat_rows, repeat_setup = read_gusuku(gusuku_repeat_path)
        by_samples = {row["samples"]: row for row in repeat_rows}
        setup_seconds = min(setup_seconds, repeat_setup) if repeat_setup > 0 else setup_seconds
        for row in gusuku_rows:
            again = by_samples.get(row["samples"])
            if again:
                row["trace_s"] = min(row["trace_s"], again["trace_s"])
                if "denoise_s" in row:
                    row["denoise_s"] = min(row["denoise_s"], again["denoise_s"])
    repeat = read_cycles_repeat(cycles_repeat_path)
    curves = {mode: [(seconds if (mode, samples) not in repeat else min(seconds, repeat[(mode, samples)]), rms)
                     for samples, seconds, rms in points]
              for mode, points in cycles_curves.items()}
    return gusuku_rows, setup_seconds, curves, bool(repeat)


def gusuku_curves(rows, common=False):
    """(raw, denoised) curves of (trace seconds, relative RMS), the reference's noise taken out where the table
    has those columns; the denoised one includes the filter's time. common: the errors over the texels Cycles
    bakes too (the common_* columns of a study run with --error-mask); None when the table has none."""
    if common:
        if "common_rel_rms_corrected" not in rows[0]:
            return None, None
        raw_key, denoised_key = "common_rel_rms_corrected", "common_rel_rms_denoised_corrected"
    else:
        raw_key = "rel_rms_corrected" if "rel_rms_corrected" in rows[0] else "rel_rms"
        denoised_key = "rel_rms_denoised_corrected" if "rel_rms_denoised_corrected" in rows[0] else "rel_rms_denoised"
    raw = [(row["trace_s"], row[raw_key]) for row in rows]
    denoised = [(row["trace_s"] + row.get("denoise_s", 0.0), row[denoised_key]) for row in rows]
    return raw, denoised


def seconds_to_reach_or_extrapolated(curve, target, samples):
    """(seconds, extrapolated): measured as seconds_to_reach, else extended past the last point (marked, so a
    table shows which figures were not measured). `samples`: each point's sample count. The error is extended
    by its last power law in samples, and the time linearly in samples from the last two points (a bake's time
    is a fixed cost plus a cost per sample): extending the time on the log-log error-time axes instead would
    count a fixed cost (Cycles' scene sync, about 1.1 s a bake call) as if it grew with the samples, and so
    shorten the extended time of the baker that has one."""
    seconds = seconds_to_reach(curve, target)
    if seconds is not None:
        return seconds, False
    points = [(n, s, r) for n, (s, r) in zip(samples, curve) if n > 0 and s > 0 and r > 0]
    if len(points) < 2:
        return None, False
    (n0, s0, r0), (n1, s1, r1) = points[-2], points[-1]
    if r1 >= r0 or n1 <= n0:
        return None, False
    slope = (math.log(r1) - math.log(r0)) / (math.log(n1) - math.log(n0))
    samples_needed = n1 * math.exp((math.log(target) - math.log(r1)) / slope)
    seconds_per_sample = max(s1 - s0, 0.0) / (n1 - n0)
    return s1 + (samples_needed - n1) * seconds_per_sample, True


def table(out, sites, slots, target=0.02):
    """One line per (site, slot): wall seconds to `target` for gusuku (denoised and raw, setup included) and
    Cycles (its faster mode), and the ratio Cycles / gusuku; then gusuku's ratios with its error measured over
    the texels Cycles bakes too (where the study had the mask). '*' marks a time extrapolated past the last
    point."""
    print(f"{'site':8s} {'slot':11s} {'gusuku den.':>12s} {'gusuku raw':>12s} {'Cycles':>10s} "
          f"{'Cycles/den.':>12s} {'Cycles/raw':>11s} | {'same texels: den.':>18s} {'raw':>8s} "
          f"{'Cycles/den.':>12s} {'Cycles/raw':>11s}")
    for site in sites:
        for slot in slots:
            folder = os.path.join(out, site, slot)
            if not (os.path.exists(folder + "/gusuku.txt") and os.path.exists(folder + "/cycles.txt")):
                print(f"{site:8s} {slot:11s} (not run)")
                continue
            rows, setup = read_gusuku(folder + "/gusuku.txt")
            cycles_points = read_cycles(folder + "/cycles.txt")
            rows, setup, cycles_curves, _ = faster_of_two_runs(rows, setup, folder + "/gusuku_repeat.txt",
                                                               cycles_points, folder + "/cycles_repeat.txt")
            gusuku_samples = [row["samples"] for row in rows]
            found = [seconds_to_reach_or_extrapolated(c, target, [n for n, _, _ in cycles_points[mode]])
                     for mode, c in cycles_curves.items()]
            found = [f for f in found if f[0] is not None]
            cycles = min(found) if found else (None, False)

            def cells_of(curves):
                cells = []
                for curve in curves:
                    if curve is None:
                        cells.append((None, False))
                        continue
                    seconds, extrapolated = seconds_to_reach_or_extrapolated(curve, target, gusuku_samples)
                    cells.append((seconds + setup if seconds is not None else None, extrapolated))
                return cells

            def show(value, width):
                seconds, extrapolated = value
                return f"{'-' if seconds is None else f'{seconds:.1f}' + ('*' if extrapolated else ''):>{width}s}"

            def ratio(gusuku, width):
                if gusuku[0] is None or cycles[0] is None:
                    return f"{'-':>{width}s}"
                mark = "*" if gusuku[1] or cycles[1] else ""
                return f"{f'{cycles[0] / gusuku[0]:.2f}{mark}':>{width}s}"

            raw, denoised = gusuku_curves(rows)
            cells = cells_of((denoised, raw))
            common_raw, common_denoised = gusuku_curves(rows, common=True)
            common = cells_of((common_denoised, common_raw))
            print(f"{site:8s} {slot:11s} {show(cells[0], 12)} {show(cells[1], 12)} {show(cycles, 10)} "
                  f"{ratio(cells[0], 12)} {ratio(cells[1], 11)} | {show(common[0], 18)} {show(common[1], 8)} "
                  f"{ratio(common[0], 12)} {ratio(common[1], 11)}")
    print("seconds of wall time to 2 % relative RMS, each against its own converged bake with that bake's own noise "
          "taken out; gusuku's setup included; * extrapolated past the last measured point: the error by its last "
          "power law in samples, the time linearly in samples. Left: each baker's error over the texels it bakes "
          "(gusuku: every valid texel; Cycles: those of them it bakes, on small triangles only those whose centre a "
          "triangle covers). Right of |: gusuku's error over Cycles' texels, the same texels for both")


def seconds_to_reach(curve, target):
    """Seconds at which the (seconds, rms) curve first reaches target, interpolated on log-log axes."""
    for i, (seconds, rms) in enumerate(curve):
        if rms > target:
            continue
        if i == 0:
            return seconds
        seconds_before, rms_before = curve[i - 1]
        fraction = (math.log(rms_before) - math.log(target)) / (math.log(rms_before) - math.log(rms))
        return math.exp(math.log(seconds_before) + fraction * (math.log(seconds) - math.log(seconds_before)))
    return None


def write_svg(path, curves):
    width, height, margin = 640, 420, 60
    all_points = [p for _, _, points in curves for p in points if p[0] > 0 and p[1] > 0]
    x_min = 10 ** math.floor(math.log10(min(p[0] for p in all_points)))
    x_max = 10 ** math.ceil(math.log10(max(p[0] for p in all_points)))
    y_min = 10 ** math.floor(math.log10(min(p[1] for p in all_points)))
    y_max = 10 ** math.ceil(math.log10(max(p[1] for p in all_points)))

    def to_x(seconds):
        return margin + (width - 2 * margin) * (math.log10(seconds) - math.log10(x_min)) / math.log10(x_max / x_min)

    def to_y(rms):
        return height - margin - (height - 2 * margin) * (math.log10(rms) - math.log10(y_min)) / math.log10(y_max / y_min)

    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" '
             f'font-size="12"><rect width="100%" height="100%" fill="white"/>']
    def decades(low, high):
        decade = low
        while decade <= high:
            yield decade
            decade *= 10

    for decade in decades(x_min, x_max):
        x = to_x(decade)
        parts.append(f'<line x1="{x:.1f}" y1="{margin}" x2="{x:.1f}" y2="{height - margin}" stroke="#ddd"/>'
                     f'<text x="{x:.1f}" y="{height - margin + 16}" text-anchor="middle">{decade:g}</text>')
    for decade in decades(y_min, y_max):
        y = to_y(decade)
        parts.append(f'<line x1="{margin}" y1="{y:.1f}" x2="{width - margin}" y2="{y:.1f}" stroke="#ddd"/>'
                     f'<text x="{margin - 6}" y="{y + 4:.1f}" text-anchor="end">{decade * 100:g} %</text>')
    parts.append(f'<text x="{width / 2}" y="{height - 18}" text-anchor="middle">seconds (2 cores)</text>'
                 f'<text x="16" y="{height / 2}" transform="rotate(-90 16 {height / 2})" text-anchor="middle">'
                 f'relative RMS error of the lightmap</text>')
    for index, (label, colour, points) in enumerate(curves):
        path_points = " ".join(f"{to_x(s):.1f},{to_y(r):.1f}" for s, r in points if s > 0 and r > 0)
        parts.append(f'<polyline points="{path_points}" fill="none" stroke="{colour}" stroke-width="2"/>')
        parts.append(f'<text x="{width - margin - 4}" y="{margin + 16 + 16 * index}" text-anchor="end" '
                     f'fill="{colour}">{label}</text>')
    parts.append("</svg>\n")
    with open(path + ".tmp", "w") as stream:
        stream.write("".join(parts))
    os.replace(path + ".tmp", path)


def main():
    if len(sys.argv) == 5 and sys.argv[1] == "--table":
        table(sys.argv[2], sys.argv[3].split(), sys.argv[4].split())
        return
    if len(sys.argv) != 2:
        sys.exit("usage: summarise_comparison.py OUT_DIR | --table OUT_DIR 'SITES' 'SLOTS'")
    out = sys.argv[1]
    gusuku_rows, setup_seconds = read_gusuku(out + "/gusuku.txt")
    gusuku_rows, setup_seconds, cycles_curves, repeated = faster_of_two_runs(
        gusuku_rows, setup_seconds, out + "/gusuku_repeat.txt", read_cycles(out + "/cycles.txt"),
        out + "/cycles_repeat.txt")
    raw, denoised = gusuku_curves(gusuku_rows)
    common_raw, common_denoised = gusuku_curves(gusuku_rows, common=True)
    methods = [
        ("gusuku raw", raw, 0.0),
        ("gusuku denoised", denoised, 0.0),
        ("gusuku raw + setup", raw, setup_seconds),
        ("gusuku denoised + setup", denoised, setup_seconds),
    ] + ([("raw + setup, Cycles' texels", common_raw, setup_seconds),
          ("den. + setup, Cycles' texels", common_denoised, setup_seconds)] if common_raw else []) + [(f"Cycles {mode}", curve, 0.0) for mode, curve in sorted(cycles_curves.items())]
    print(f"seconds to reach a relative RMS error (gusuku setup before the first ray: {setup_seconds:.2f} s"
          + ("; each bake the faster of two interleaved timings)" if repeated else ")"))
    print(f"{'method':29s}" + "".join(f"{f'{t * 100:g} %':>10s}" for t in TARGETS))
    for label, curve, offset in methods:
        cells = []
        for target in TARGETS:
            seconds = seconds_to_reach(curve, target)
            cells.append(f"{'-' if seconds is None else f'{seconds + offset:.2f}':>10s}")
        print(f"{label:29s}" + "".join(cells))
    # Cycles at its best (the faster of its two modes) against gusuku with its setup paid, raw and denoised.
    for target in TARGETS:
        cycles_best = min((s for s in (seconds_to_reach(c, target) for c in cycles_curves.values()) if s), default=None)
        if cycles_best is None:
            continue
        ratios = []
        for label, curve in (("raw", raw), ("denoised", denoised)):
            seconds = seconds_to_reach(curve, target)
            ratios.append(f"{cycles_best / (seconds + setup_seconds):.2f} x gusuku {label}" if seconds else
                          f"gusuku {label} not reached")
        print(f"at {target * 100:g} %: the faster Cycles mode takes " + ", ".join(ratios) + " (wall time, setup included)")
    colours = {"fixed": "#d62728", "adaptive": "#ff7f0e"}
    write_svg(out + "/error_vs_time.svg", [("gusuku raw", "#1f77b4", raw), ("gusuku denoised", "#2ca02c", denoised)] +
              [(f"Cycles {mode}", colours.get(mode, "#7f7f7f"), curve) for mode, curve in sorted(cycles_curves.items())])
    print(f"chart: {out}/error_vs_time.svg")
    try:
        with open(out + "/drift.txt") as stream:
            speeds = [float(line.split()[1]) for line in stream if len(line.split()) == 3]
        if len(speeds) == 2 and min(speeds) > 0:
            print(f"machine drift while measuring: gusuku's rays per second changed by "
                  f"{100 * (speeds[1] / speeds[0] - 1):+.0f} % from before Cycles to after; ratios are good to about that")
    except (OSError, ValueError, IndexError):
        pass


if __name__ == "__main__":
    main()
