#!/usr/bin/env python3
"""Writes a real-model site for the benchmark (scripts/bench-sites.sh): the sample terrace (the site.json that
`gusuku-bake sample DIR` writes) with another building and the shared photographed skies, and bake settings chosen
for a bake of a few minutes on 2 cores.

The shared data is named by absolute path, never copied: the written site.json points into SHARED_DATA_DIR.

Usage: write-bench-site.py SAMPLE_SITE_JSON SHARED_DATA_DIR SITE OUT_SITE_JSON
  SITE: shrine | house (the table SITES below). Exit status 1, with one line naming the file, when the shared
  data or the sample site is missing or the sample site is not what `gusuku-bake sample` writes; 2 on bad usage.
"""
import json
import os
import sys

# Each real-model site: its glTF under SHARED_DATA_DIR/building, its placement on the terrace (the sample house
# stands with its origin at ENU (2, 4, 1.5) m, on the terrace's top at 1.5 m), and its bake settings.
SITES = {
    # "Japan Temple" by yankobe, CC-BY-4.0: about 3.0 x 4.0 x 4.7 m at scale 1; 12,418 triangles. At 16 texels a
    # metre (6 cm texels: its beams and pillars are a texel or two wide at 8) it has about 44k texels.
    "shrine": {
        "building": "building/japan_temple_yankobe/scene.gltf",
        "name": "shared shrine on the sample terrace, photographed skies",
        "scale": 1.0,
        "heading_deg": 12.0,
        "texels_per_metre": 16.0,
        "samples_per_texel": 192,
    },
    # The house diorama (house, car, tree on a round base), CC-BY-4.0: 0.5 x 0.19 x 0.5 units; at scale 16 it is
    # 8 x 3 x 8 m, about the sample house's footprint. 10,497 triangles, its own lightmap UVs (TEXCOORD_1).
    "house": {
        "building": "building/playcanvas_house_lightmapUV/house.glb",
        "name": "shared house on the sample terrace, photographed skies",
        "scale": 16.0,
        "heading_deg": 12.0,
        "texels_per_metre": 12.0,
        "samples_per_texel": 192,
    },
}
# rooitou_park: a clear sky with a low sun (about 10 deg) whose disc the baker measures and carries to each slot's
# sun; potsdamer_platz: overcast. Poly Haven gives no north: the image's u = 0 is taken as north.
SKIES = {"sunny": "env/rooitou_park_1k.hdr", "overcast": "env/potsdamer_platz_1k.hdr"}


def fail(message):
    print("write-bench-site: " + message, file=sys.stderr)
    sys.exit(1)


def site_for(sample, sample_path, shared, name):
    spec = SITES[name]
    files = {"building": os.path.join(shared, spec["building"])}
    files.update({sky: os.path.join(shared, path) for sky, path in SKIES.items()})
    for path in files.values():
        if not os.path.isfile(path):
            fail(path + ": not found (the shared data is not there)")
    for field in ("sfm_mesh", "building", "bake", "site"):
        if not isinstance(sample.get(field), dict):
            fail(sample_path + ": /" + field + ": missing; not a site.json written by gusuku-bake sample")
    site = json.loads(json.dumps(sample))
    base = os.path.dirname(os.path.abspath(sample_path))
    site["sfm_mesh"]["path"] = os.path.join(base, site["sfm_mesh"]["path"])
    # The sample house's placement (enu_offset_m) is kept: the building stands where it stood.
    site["building"]["path"] = files["building"]
    site["building"]["scale"] = spec["scale"]
    site["building"]["heading_deg"] = spec["heading_deg"]
    site["skies"] = {sky: {"path": files[sky], "north_azimuth_in_image_deg": 0.0} for sky in SKIES}
    site["site"]["name"] = spec["name"]
    site["bake"]["texels_per_metre"] = spec["texels_per_metre"]
    site["bake"]["samples_per_texel"] = spec["samples_per_texel"]
    return site


def main():
    if len(sys.argv) != 5 or sys.argv[3] not in SITES:
        print("usage: write-bench-site.py SAMPLE_SITE_JSON SHARED_DATA_DIR " + "|".join(SITES) + " OUT_SITE_JSON",
              file=sys.stderr)
        sys.exit(2)
    sample_path, shared, name, output = sys.argv[1:]
    try:
        with open(sample_path) as stream:
            sample = json.load(stream)
    except FileNotFoundError:
        fail(sample_path + ": not found (write it with gusuku-bake sample DIR)")
    except json.JSONDecodeError as error:
        fail(sample_path + ": invalid JSON: " + str(error))
    site = site_for(sample, sample_path, os.path.abspath(shared), name)
    os.makedirs(os.path.dirname(os.path.abspath(output)), exist_ok=True)
    with open(output + ".tmp", "w") as stream:
        json.dump(site, stream, indent=2)
        stream.write("\n")
    os.replace(output + ".tmp", output)


if __name__ == "__main__":
    main()
