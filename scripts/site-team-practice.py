#!/usr/bin/env python3
"""A practice survey for docs/site-team.md: the sample site's terrain (`gusuku-bake sample DIR` writes it as
DIR/site.glb, in the site's east-north-up metres) re-expressed as photogrammetry hands it over, and the ground
control points a surveyor would measure on it. Writes, into DIR:

  survey.ply  binary PLY with vertex colours, in the mesh's own axes: Z down, turned 30 degrees, in units of
              0.4 m and shifted, as an OpenMVS reconstruction without georeferencing comes (ENU = s R p + t with
              s = 2.5, R = 30 degrees about up after a half turn about east, t = (3, -2, 0.5) m)
  gcps.csv    five marked points: their position in survey.ply and their WGS84 latitude, longitude and ellipsoid
              height from the sample's reference point (26.2856 N, 127.8008 E, 160 m), with up to 1 cm of
              survey noise, as `gusuku-bake georef` reads them

So `gusuku-bake georef DIR/gcps.csv --origin 26.2856,127.8008,160` has a known answer to find.

usage: site-team-practice.py DIR      (after `gusuku-bake sample DIR`)
Exit status 1 with `FILE: PROBLEM` when DIR/site.glb is missing or not the sample's.
"""
import json
import math
import pathlib
import struct
import sys

ORIGIN = (26.2856, 127.8008, 160.0)  # the sample's reference point, WGS84 degrees and metres
SCALE = 2.5                          # metres per survey unit
TURN_DEG = 30.0                      # about up, after the half turn about east (Z down)
SHIFT_ENU = (3.0, -2.0, 0.5)
# Where the surveyor marked the points (ENU metres; the nearest terrain vertex is taken) and their noise (m).
MARKS = [((-15.0, -15.0), (0.004, -0.006, 0.008)), ((15.0, -15.0), (-0.007, 0.003, -0.005)),
         ((15.0, 15.0), (0.006, 0.008, 0.002)), ((-15.0, 15.0), (-0.003, -0.005, -0.009)),
         ((0.0, -8.0), (0.002, 0.006, 0.004))]
WGS84_A, WGS84_F = 6378137.0, 1.0 / 298.257223563


def fail(file, problem):
    sys.exit(f"{file}: {problem}")


def read_glb_triangles(path):
    """ENU positions and triangles of every primitive of the sample's site.glb (float positions, uint indices)."""
    data = path.read_bytes() if path.is_file() else fail(path, "file not found (run `gusuku-bake sample DIR` first)")
    if data[:4] != b"glTF":
        fail(path, "is not a binary glTF")
    json_length = struct.unpack_from("<I", data, 12)[0]
    gltf = json.loads(data[20:20 + json_length])
    binary = data[20 + json_length + 8:]
    views, accessors = gltf["bufferViews"], gltf["accessors"]

    def accessor(index, fmt, width):
        a = accessors[index]
        view = views[a["bufferView"]]
        offset = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        values = struct.unpack_from(f"<{a['count'] * width}{fmt}", binary, offset)
        return [values[i:i + width] for i in range(0, len(values), width)]

    positions, triangles = [], []
    for mesh in gltf["meshes"]:
        for primitive in mesh["primitives"]:
            base = len(positions)
            # glTF is Y-up: (x, y, z) -> ENU (x, -z, y).
            positions += [(x, -z, y) for x, y, z in accessor(primitive["attributes"]["POSITION"], "f", 3)]
            kind = {5125: "I", 5123: "H"}[accessors[primitive["indices"]]["componentType"]]
            flat = [i[0] for i in accessor(primitive["indices"], kind, 1)]
            triangles += [(base + flat[i], base + flat[i + 1], base + flat[i + 2]) for i in range(0, len(flat), 3)]
    return positions, triangles


def rotation():
    """R of ENU = s R p + t: a half turn about east (the mesh's Z points down), then TURN_DEG about up."""
    c, s = math.cos(math.radians(TURN_DEG)), math.sin(math.radians(TURN_DEG))
    about_up = [[c, -s, 0], [s, c, 0], [0, 0, 1]]
    half_turn = [[1, 0, 0], [0, -1, 0], [0, 0, -1]]
    return [[sum(about_up[i][k] * half_turn[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def survey_from_enu(p, r):
    d = [(p[i] - SHIFT_ENU[i]) / SCALE for i in range(3)]
    return tuple(sum(r[k][i] * d[k] for k in range(3)) for i in range(3))  # R^T d


def geodetic_from_enu(enu):
    """WGS84 latitude, longitude (degrees) and ellipsoid height (m) of an ENU point about ORIGIN."""
    lat0, lon0 = math.radians(ORIGIN[0]), math.radians(ORIGIN[1])
    e2 = WGS84_F * (2 - WGS84_F)

    def ecef(lat, lon, h):
        n = WGS84_A / math.sqrt(1 - e2 * math.sin(lat) ** 2)
        return ((n + h) * math.cos(lat) * math.cos(lon), (n + h) * math.cos(lat) * math.sin(lon),
                (n * (1 - e2) + h) * math.sin(lat))

    x0, y0, z0 = ecef(lat0, lon0, ORIGIN[2])
    e, n, u = enu
    sl, cl, sp, cp = math.sin(lon0), math.cos(lon0), math.sin(lat0), math.cos(lat0)
    x = x0 - sl * e - sp * cl * n + cp * cl * u
    y = y0 + cl * e - sp * sl * n + cp * sl * u
    z = z0 + cp * n + sp * u
    lon, p = math.atan2(y, x), math.hypot(x, y)
    lat = math.atan2(z, p * (1 - e2))
    for _ in range(10):  # fixed point on the latitude; converges to far below a millimetre
        n_radius = WGS84_A / math.sqrt(1 - e2 * math.sin(lat) ** 2)
        h = p / math.cos(lat) - n_radius
        lat = math.atan2(z, p * (1 - e2 * n_radius / (n_radius + h)))
    return math.degrees(lat), math.degrees(lon), h


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    folder = pathlib.Path(sys.argv[1])
    positions, triangles = read_glb_triangles(folder / "site.glb")
    r = rotation()
    survey = [survey_from_enu(p, r) for p in positions]
    # Colours: the terrace's stone grey, greener where lower (the lawn), as a photogrammetry mesh carries them.
    heights = [p[2] for p in positions]
    low, high = min(heights), max(heights)
    colours = []
    for h in heights:
        t = (h - low) / max(high - low, 1e-6)
        colours.append((int(110 + 60 * t), int(130 + 30 * t), int(90 + 60 * t)))
    header = ("ply\nformat binary_little_endian 1.0\ncomment practice survey for docs/site-team.md\n"
              f"element vertex {len(survey)}\nproperty float x\nproperty float y\nproperty float z\n"
              "property uchar red\nproperty uchar green\nproperty uchar blue\n"
              f"element face {len(triangles)}\nproperty list uchar int vertex_indices\nend_header\n")
    body = bytearray(header.encode())
    for p, c in zip(survey, colours):
        body += struct.pack("<fffBBB", *p, *c)
    for t in triangles:
        body += struct.pack("<Biii", 3, *t)
    (folder / "survey.ply").write_bytes(bytes(body))

    lines = ["name,mesh_x,mesh_y,mesh_z,latitude_deg,longitude_deg,height_m"]
    for number, ((east, north), noise) in enumerate(MARKS, 1):
        nearest = min(range(len(positions)),
                      key=lambda i: (positions[i][0] - east) ** 2 + (positions[i][1] - north) ** 2)
        mesh = survey[nearest]
        # The mesh stores floats: the surveyor reads the mark's mesh position as the file holds it.
        mesh = tuple(struct.unpack("<fff", struct.pack("<fff", *mesh)))
        enu = [SCALE * sum(r[i][k] * mesh[k] for k in range(3)) + SHIFT_ENU[i] + noise[i] for i in range(3)]
        lat, lon, h = geodetic_from_enu(enu)
        lines.append(f"mark_{number},{mesh[0]:.4f},{mesh[1]:.4f},{mesh[2]:.4f},{lat:.9f},{lon:.9f},{h:.3f}")
    (folder / "gcps.csv").write_text("\n".join(lines) + "\n")
    print(f"wrote {folder / 'survey.ply'} ({len(triangles)} triangles) and {folder / 'gcps.csv'} ({len(MARKS)} points)")


if __name__ == "__main__":
    main()
