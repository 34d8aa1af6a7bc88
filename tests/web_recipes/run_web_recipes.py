#!/usr/bin/env python3
"""docs/export.md's three.js and Babylon.js recipes, run in headless Chromium on the sample's export.

usage: run_web_recipes.py export --bake GUSUKU_BAKE --work DIR
       run_web_recipes.py RECIPE --work DIR --docs docs/export.md --node-modules DIR [--chromium PATH]
       (RECIPE: three, babylon, or babylon-srgb: the Babylon recipe with nonColorData taken out, which must fail)

`export` writes the sample site, bakes it at 4 samples and exports sunny_1200 (WORK/model.glb), with the
lightmap's bytes decoded here from the glb's PNG (WORK/lightmap.json). A recipe run serves a folder of its page
(three.html or babylon.html beside this script), measure.js, the recipe's code block cut from export.md (recipe.js), the glb, the
lightmap and the npm packages on 127.0.0.1 only, loads the page in `chromium --headless` on SwiftShader, and reads
the result the page posts back to the server: per channel of every covered pixel, the irradiance the engine applied
(pi * lit / albedo) over the lightmap's value there. As export.md documents it, that ratio is 1 less the share
the engine gives its specular: its median must lie in [0.95, 1.02], its 10th and 90th percentiles in [0.88, 1.10]. Exit 0 pass, 1 fail, 77 skipped (no chromium, or the npm
packages not installed: scripts/install-deps.sh installs both).
"""
import argparse
import functools
import http.server
import json
import os
import pathlib
import re
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import threading
import zlib

HERE = pathlib.Path(__file__).resolve().parent
SKIP = 77
PACKAGES = {"three": "three/build/three.module.js", "babylon": "babylonjs/babylon.js",
            "babylon-srgb": "babylonjs/babylon.js"}
RECIPE_MARKER = {"three": "// three.js recipe", "babylon": "// Babylon.js recipe", "babylon-srgb": "// Babylon.js recipe"}


def glb_json_and_bin(path):
    data = path.read_bytes()
    json_length = struct.unpack_from("<I", data, 12)[0]
    document = json.loads(data[20:20 + json_length])
    bin_start = 20 + json_length + 8
    return document, data[bin_start:]


def decode_png_rgb8(png):
    """An 8-bit RGB or RGBA, non-interlaced PNG's RGB bytes, row 0 first (the export writes RGB 8-bit)."""
    assert png[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    position, idat, header = 8, b"", None
    while position < len(png):
        length, kind = struct.unpack_from(">I4s", png, position)
        body = png[position + 8:position + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        position += 12 + length
    width, height, depth, colour, _, _, interlace = header
    channels = {2: 3, 6: 4}[colour]
    assert depth == 8 and interlace == 0, "only 8-bit non-interlaced PNGs"
    raw, stride = zlib.decompress(idat), width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            left = line[x - channels] if x >= channels else 0
            up, up_left = previous[x], previous[x - channels] if x >= channels else 0
            if kind == 1:
                line[x] = (line[x] + left) & 255
            elif kind == 2:
                line[x] = (line[x] + up) & 255
            elif kind == 3:
                line[x] = (line[x] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - up_left
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - up_left)
                line[x] = (line[x] + (left if pa <= pb and pa <= pc else up if pb <= pc else up_left)) & 255
        rows.append(line)
        previous = line
    rgb = []
    for line in rows:
        for x in range(width):
            rgb.extend(line[x * channels:x * channels + 3])
    return width, height, rgb


def make_export(bake, work):
    work.mkdir(parents=True, exist_ok=True)
    for name in ("site", "bakeset"):
        shutil.rmtree(work / name, ignore_errors=True)
    steps = [[bake, "sample", str(work / "site")],
             [bake, "bake", str(work / "site" / "site.json"), "-o", str(work / "bakeset"), "--samples", "4", "--quiet"],
             [bake, "export", str(work / "bakeset"), "--slot", "sunny_1200", "-o", str(work / "model.glb")]]
    for step in steps:
        result = subprocess.run(step, capture_output=True, text=True)
        if result.returncode != 0:
            sys.exit(f"{' '.join(step)}: exit {result.returncode}: {result.stderr.strip()}")
    document, binary = glb_json_and_bin(work / "model.glb")
    material = document["materials"][0]["extensions"]["MOZ_lightmap"]
    image = document["images"][document["textures"][material["index"]]["source"]]
    view = document["bufferViews"][image["bufferView"]]
    png = binary[view.get("byteOffset", 0):view.get("byteOffset", 0) + view["byteLength"]]
    width, height, rgb = decode_png_rgb8(png)
    (work / "lightmap.json").write_text(json.dumps(
        {"width": width, "height": height, "intensity": material["intensity"], "rgb": rgb}))
    print(f"export: {work / 'model.glb'}, lightmap {width}x{height}, intensity {material['intensity']:.4f}")
    return 0


def recipe_code(docs, recipe):
    """The ```js block of export.md whose first line is the recipe's marker."""
    blocks = re.findall(r"```js\n(.*?)```", docs.read_text(encoding="utf-8"), re.S)
    found = [block for block in blocks if block.startswith(RECIPE_MARKER[recipe])]
    if len(found) != 1:
        sys.exit(f"{docs}: {len(found)} js blocks start with '{RECIPE_MARKER[recipe]}'; expected one")
    code = found[0]
    if recipe == "babylon-srgb":
        # The recipe's mistake export.md warns of: without nonColorData the loader makes an sRGB texture.
        assert "nonColorData: true" in code, "the Babylon recipe no longer marks its lightmap nonColorData"
        code = code.replace("nonColorData: true", "nonColorData: false")
    return code


def find_chromium(given):
    for candidate in [given, "chromium", "chromium-browser", "google-chrome"]:
        if candidate and shutil.which(candidate):
            return shutil.which(candidate)
    return None


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map, ".js": "text/javascript",
                      ".mjs": "text/javascript", ".glb": "model/gltf-binary", ".json": "application/json"}

    def log_message(self, *arguments):
        pass

    def do_POST(self):
        """The page's result (measure.js report()): kept on the server, and the runner woken."""
        body = self.rfile.read(int(self.headers.get("Content-Length", 0)))
        if self.path == "/result":
            self.server.page_result = body.decode("utf-8", "replace")
            self.server.result_arrived.set()
        self.send_response(204)
        self.end_headers()


def run_recipe(arguments):
    chromium = find_chromium(arguments.chromium)
    modules = pathlib.Path(arguments.node_modules)
    if not chromium:
        print("SKIP: no chromium (scripts/install-deps.sh installs Debian's)")
        return SKIP
    if not (modules / PACKAGES[arguments.recipe]).exists():
        print(f"SKIP: {modules / PACKAGES[arguments.recipe]} missing (scripts/install-deps.sh installs the "
              "pinned npm packages)")
        return SKIP
    work = pathlib.Path(arguments.work).resolve()
    with tempfile.TemporaryDirectory(prefix=f"gusuku-web-{arguments.recipe}-") as folder:
        root = pathlib.Path(folder)
        page = "babylon" if arguments.recipe.startswith("babylon") else "three"
        shutil.copy(HERE / f"{page}.html", root / "index.html")
        shutil.copy(HERE / "measure.js", root / "measure.js")
        (root / "recipe.js").write_text(recipe_code(pathlib.Path(arguments.docs), arguments.recipe))
        for name in ("model.glb", "lightmap.json"):
            os.symlink(work / name, root / name)
        os.symlink(modules.resolve(), root / "node_modules")
        server = http.server.ThreadingHTTPServer(("127.0.0.1", 0),
                                                 functools.partial(QuietHandler, directory=str(root)))
        server.page_result, server.result_arrived = None, threading.Event()
        threading.Thread(target=server.serve_forever, daemon=True).start()
        url = f"http://127.0.0.1:{server.server_address[1]}/index.html"
        profile = root / "profile"
        # Chromium stays up with the page open until the page posts its result (or the time runs out): real time,
        # not a virtual-time budget with a DOM dump, whose end raced the page's awaits.
        command = [chromium, "--headless", "--no-sandbox", "--disable-gpu-sandbox", "--use-angle=swiftshader",
                   "--enable-unsafe-swiftshader", "--disable-dev-shm-usage", "--no-first-run",
                   f"--user-data-dir={profile}", url]
        log = root / "chromium.log"
        with open(log, "w") as log_file:
            browser = subprocess.Popen(command, stdout=log_file, stderr=subprocess.STDOUT, start_new_session=True)
            try:
                waited = 0.0
                while not server.result_arrived.wait(0.5) and browser.poll() is None and waited < arguments.timeout:
                    waited += 0.5
            finally:
                if browser.poll() is None:
                    os.killpg(browser.pid, signal.SIGTERM)
                    try:
                        browser.wait(10)
                    except subprocess.TimeoutExpired:
                        os.killpg(browser.pid, signal.SIGKILL)
                        browser.wait()
                server.shutdown()
        said = log.read_text(errors="replace")
        page_result = server.page_result
    if page_result is None:
        print(f"no result from the page in {arguments.timeout:.0f} s (chromium "
              f"{'exited ' + str(browser.returncode) if browser.returncode is not None else 'still running'}); "
              f"chromium said:\n{said[-3000:]}")
        return 1
    measured = json.loads(page_result)
    print(f"{arguments.recipe}: {json.dumps(measured)}")
    if "error" in measured:
        return 1
    median, low, high = measured["ratio_median"], measured["ratio_p10"], measured["ratio_p90"]
    # Both engines take the specular's share out of the diffuse albedo (three.js about 2 %, Babylon.js 4 %, its
    # dielectric F0), as they do for their own lights: the median may lie up to 5 % under 1, not above.
    holds = (measured["compared_channels"] >= 1000 and median is not None and 0.95 <= median <= 1.02
             and low >= 0.88 and high <= 1.10)
    if arguments.recipe == "babylon-srgb":
        # The control: an sRGB decode of the linear bytes darkens every mid-grey texel, by 0.46x at byte 128.
        dark = median is not None and median < 0.8
        print("babylon-srgb: without nonColorData the lightmap is read as sRGB, median ratio "
              f"{median:.3f} (the docs: about half as bright)" if dark else "babylon-srgb: the control did not darken")
        return 0 if dark else 1
    print(f"{arguments.recipe}: applied irradiance over the lightmap's value: median {median:.4f}, "
          f"p10 {low:.4f}, p90 {high:.4f} over {measured['compared_channels']} channels "
          f"({measured['covered_pixels']} pixels): {'as documented' if holds else 'NOT as documented'}")
    return 0 if holds else 1


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("recipe", choices=["export", "three", "babylon", "babylon-srgb"])
    parser.add_argument("--bake")
    parser.add_argument("--work", required=True)
    parser.add_argument("--docs")
    parser.add_argument("--node-modules")
    parser.add_argument("--chromium")
    parser.add_argument("--timeout", type=float, default=100)  # seconds for chromium, under ctest's 120
    arguments = parser.parse_args()
    if arguments.recipe == "export":
        return make_export(arguments.bake, pathlib.Path(arguments.work))
    return run_recipe(arguments)


if __name__ == "__main__":
    sys.exit(main())
