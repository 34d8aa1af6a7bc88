#!/usr/bin/env python3
"""Writes the comparison's second site: the shared shrine (japan_temple_yankobe) on the sample site's terrace,
under the shared photographed skies (rooitou_park: a clear sky with a low sun whose disc the baker measures and
carries to each slot's sun; potsdamer_platz: overcast).

The shared data is named by absolute path, never copied. The terrace and the slots are the sample site's (its
site.json, written by `gusuku-bake sample`); only the building and the skies change. The shrine is about 3 x 4.7 x
4 m, smaller than the sample house: it stands on the terrace where the house stood.

Usage: make_shrine_site.py SAMPLE_SITE_JSON SHARED_DATA_DIR OUT_SITE_JSON
Exit status 1, with a one-line message, when a shared file is missing.
"""
import json
import os
import sys


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: make_shrine_site.py SAMPLE_SITE_JSON SHARED_DATA_DIR OUT_SITE_JSON")
    sample_path, shared, output = sys.argv[1:]
    shared = os.path.abspath(shared)
    building = os.path.join(shared, "building/japan_temple_yankobe/scene.gltf")
    sunny = os.path.join(shared, "env/rooitou_park_1k.hdr")
    overcast = os.path.join(shared, "env/potsdamer_platz_1k.hdr")
    for path in (building, sunny, overcast):
        if not os.path.isfile(path):
            sys.exit(f"make_shrine_site: {path}: not found (the shared data is not there)")
    with open(sample_path) as stream:
        site = json.load(stream)
    base = os.path.dirname(os.path.abspath(sample_path))
    site["sfm_mesh"]["path"] = os.path.join(base, site["sfm_mesh"]["path"])
    site["building"]["path"] = building
    site["skies"] = {
        # Poly Haven gives no north: the image's u = 0 is taken as north (as scripts/bench.sh does).
        "sunny": {"path": sunny, "north_azimuth_in_image_deg": 0.0},
        "overcast": {"path": overcast, "north_azimuth_in_image_deg": 0.0},
    }
    site["site"]["name"] = "shared shrine on the sample terrace, photographed skies"
    os.makedirs(os.path.dirname(os.path.abspath(output)), exist_ok=True)
    with open(output + ".tmp", "w") as stream:
        json.dump(site, stream, indent=2)
    os.replace(output + ".tmp", output)


if __name__ == "__main__":
    main()
