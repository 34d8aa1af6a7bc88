#!/usr/bin/env python3
"""gusuku-view as a user drives it, under Xvfb (ctest view_window; issue 45 item 4).

  check_view_window.py bake   --bake GUSUKU_BAKE --work DIR
      the sample site baked at 1 sample a texel into DIR/bakeset (the fixture the window test reads)
  check_view_window.py window --view GUSUKU_VIEW --render GUSUKU_RENDER --work DIR
      opens the viewer on DIR/bakeset in a virtual X server (xvfb-run), drives it with scripted input (orbit 30
      degrees, the hour to 15:00, a screenshot, a resize to 400x300, a screenshot), and checks:
        - the first screenshot against gusuku-render's headless composite of the same pose and instant (the
          orbit's position computed here, independently of the viewer): every byte within TOLERANCE_CODES
          (measured: identical bytes on lavapipe);
        - the swapchain was made again at 400x300, and the second screenshot is that size: the frame fitted
          and letterboxed (bars black, the picture's mean within 1.5 codes of the composite's per channel);
        - no Vulkan validation message (GUSUKU_VALIDATION=1 from ctest) and exit status 0;
        - a missing bake set: the tools' one line (FILE: PROBLEM) and exit 1.
Exit 0 on success, 1 on a failed check, 77 (skipped) without xvfb-run or a display-less GLFW.
"""
import argparse
import math
import os
import shutil
import struct
import subprocess
import sys
import zlib

SIZE = (256, 144)
SAMPLES = "2"
EXPOSURE = "1"
POSITION, LOOK_AT = (0.0, -25.0, 6.0), (0.0, 0.0, 2.0)
ORBIT_DEG = 30.0
TOLERANCE_CODES = 2
RESIZED = (400, 300)

def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour in (2, 6) and interlace == 0, (depth, colour, interlace)
            channels = 4 if colour == 6 else 3
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - channels] if x >= channels else 0
            b = previous[x]
            c = previous[x - channels] if x >= channels else 0
            if kind == 1: line[x] = (line[x] + a) & 255
            elif kind == 2: line[x] = (line[x] + b) & 255
            elif kind == 3: line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        previous = line
    rgb = bytearray()
    for line in rows:
        for x in range(width):
            rgb += line[x * channels:x * channels + 3]
    return width, height, bytes(rgb)


def run(command, **kwargs):
    result = subprocess.run(command, capture_output=True, text=True, timeout=120, **kwargs)
    output = result.stdout + result.stderr
    return result.returncode, output


def start(command):
    return subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def finish(process):
    output, _ = process.communicate(timeout=120)
    return process.returncode, output


def bake(arguments):
    site = os.path.join(arguments.work, "sample")
    bakeset = os.path.join(arguments.work, "bakeset")
    shutil.rmtree(arguments.work, ignore_errors=True)
    for command in ([arguments.bake, "sample", site],
                    [arguments.bake, "bake", os.path.join(site, "site.json"), "-o", bakeset, "--samples", "1",
                     "--quiet"]):
        code, output = run(command)
        if code != 0:
            print(f"{' '.join(command)}: exit {code}\n{output}")
            return 1
    print(f"sample bake set: {bakeset}")
    return 0


def orbited(position, centre, degrees):
    """position turned about the vertical through centre, counter-clockwise seen from above."""
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    dx, dy = position[0] - centre[0], position[1] - centre[1]
    return (centre[0] + c * dx - s * dy, centre[1] + s * dx + c * dy, position[2])


def bake_date_at(bakeset, hour):
    """ISO 8601 of `hour`:00 on the bake date, site clock (the manifest's first sunny slot and UTC offset)."""
    import json
    import datetime
    manifest = json.load(open(os.path.join(bakeset, "manifest.json")))
    offset = datetime.timedelta(minutes=manifest["site"]["utc_offset_minutes"])
    utc = next(slot["utc"] for slot in manifest["slots"] if slot.get("utc"))
    local = datetime.datetime.fromisoformat(utc.replace("Z", "+00:00")).astimezone(datetime.timezone(offset))
    return local.replace(hour=hour, minute=0, second=0).isoformat()


def channel_means(rgb, width, box):
    x0, y0, x1, y1 = box
    sums, count = [0, 0, 0], 0
    for y in range(y0, y1):
        row = rgb[(y * width + x0) * 3:(y * width + x1) * 3]
        for channel in range(3):
            sums[channel] += sum(row[channel::3])
        count += x1 - x0
    return [value / count for value in sums]


def window(arguments):
    if not shutil.which("xvfb-run"):
        print("SKIP: xvfb-run is not installed (Debian package xvfb; scripts/install-deps.sh installs it)")
        return 77
    bakeset = os.path.join(arguments.work, "bakeset")
    out = os.path.join(arguments.work, "window")
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    first, resized, composite = (os.path.join(out, name) for name in ("orbit.png", "resized.png", "render.png"))
    size = f"{SIZE[0]}x{SIZE[1]}"
    actions = (f"orbit {ORBIT_DEG:g};hour 15;screenshot {first};resize {RESIZED[0]}x{RESIZED[1]};"
               f"screenshot {resized};quit")
    position = orbited(POSITION, LOOK_AT, ORBIT_DEG)
    # Both at once (the machine's two cores): the viewer in its virtual X server, gusuku-render headless.
    viewer = start(["xvfb-run", "-a", "-s", "-screen 0 1024x768x24", arguments.view, bakeset, "--size", size,
                    "--samples", SAMPLES, "--exposure", EXPOSURE, "--actions", actions])
    render = start([arguments.render, bakeset, "-o", composite, "--size", size, "--samples", SAMPLES,
                    "--exposure", EXPOSURE, "--frames", "1", "--time", bake_date_at(bakeset, 15),
                    "--position", ",".join(f"{value:.15g}" for value in position),
                    "--look-at", ",".join(f"{value:g}" for value in LOOK_AT)])
    code, view_output = finish(viewer)
    print(view_output)
    if code != 0:
        print(f"gusuku-view: exit {code}")
        return 1
    code, render_output = finish(render)
    if code != 0:
        print(f"gusuku-render: exit {code}\n{render_output}")
        return 1
    problems = []
    if "Vulkan validation" in view_output + render_output:
        problems.append("a Vulkan validation message (above)")
    width, height, shot = read_png(first)
    render_width, render_height, expected = read_png(composite)
    if (width, height) != (render_width, render_height):
        problems.append(f"screenshot {width}x{height}, composite {render_width}x{render_height}")
    else:
        differences = [abs(a - b) for a, b in zip(shot, expected)]
        worst, mean = max(differences), sum(differences) / len(differences)
        print(f"orbit 30, 15:00: screenshot against gusuku-render: mean {mean:.3f}, max {worst} codes "
              f"({sum(1 for d in differences if d)} of {len(differences)} bytes differ)")
        if worst > TOLERANCE_CODES:
            problems.append(f"the screenshot is {worst} codes from gusuku-render's composite (> {TOLERANCE_CODES})")
    if f"swapchain {RESIZED[0]}x{RESIZED[1]}" not in view_output:
        problems.append(f"no swapchain made again at {RESIZED[0]}x{RESIZED[1]}")
    width, height, shot = read_png(resized)
    if (width, height) != RESIZED:
        problems.append(f"the resized screenshot is {width}x{height}, not {RESIZED[0]}x{RESIZED[1]}")
    else:
        fitted_height = RESIZED[0] * SIZE[1] // SIZE[0]
        top = (RESIZED[1] - fitted_height) // 2
        bars = channel_means(shot, width, (0, 0, width, top)) + channel_means(shot, width, (0, top + fitted_height,
                                                                                             width, height))
        picture = channel_means(shot, width, (0, top + 1, width, top + fitted_height - 1))
        reference = channel_means(expected, render_width, (0, 0, render_width, render_height))
        print(f"resized: bars {max(bars):.2f}, picture mean {[round(v, 2) for v in picture]} against the composite's "
              f"{[round(v, 2) for v in reference]}")
        if max(bars) != 0:
            problems.append("the letterbox bars are not black")
        if max(abs(a - b) for a, b in zip(picture, reference)) > 1.5:
            problems.append("the resized picture's mean is more than 1.5 codes from the composite's")
    # Bad input: the tools' one line and exit 1, before any window opens.
    missing = os.path.join(out, "missing")
    code, output = run([arguments.view, missing])
    lines = [line for line in output.splitlines() if "Vulkan loader" not in line]
    if code != 1 or lines != [f"gusuku-view: error: {missing}/manifest.json: file not found: not a bake set folder, "
                              "or its bake has not finished (the manifest is written last)"]:
        problems.append(f"a missing bake set gave exit {code} and {lines}")
    for problem in problems:
        print(f"FAIL: {problem}")
    return 1 if problems else 0


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("step", choices=["bake", "window"])
    parser.add_argument("--bake")
    parser.add_argument("--view")
    parser.add_argument("--render")
    parser.add_argument("--work", required=True)
    arguments = parser.parse_args()
    return bake(arguments) if arguments.step == "bake" else window(arguments)


if __name__ == "__main__":
    sys.exit(main())
