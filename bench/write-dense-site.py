#!/usr/bin/env python3
"""Writes a site whose SfM mesh is photogrammetry-sized (issue 21 item 5): a site.json like SITE_JSON whose
sfm_mesh is that site's own mesh with every triangle cut into 4^LEVELS (midpoint subdivision: each triangle into
four by its edge midpoints, LEVELS times). The sample terrace (2,950 triangles) at 3 levels is 188,800 triangles,
about a real capture's size, on exactly the same surface, so bench/tracer_speed.sh can measure the tracer's rate
on the dense site against the original in one run.

Positions, normals (renormalised) and the first texture coordinates are interpolated; the materials and images
are copied as they are. Reads only what `gusuku-bake sample` writes (one buffer, float positions, normals and
TEXCOORD_0, 32-bit indices, triangle lists); anything else is refused with one line naming the file.

Usage: write-dense-site.py SITE_JSON LEVELS OUT_DIR
  writes OUT_DIR/site.glb and OUT_DIR/site.json (the other paths made absolute). Exit status 1 on bad input, 2 on
  bad usage.
"""
import json
import math
import os
import struct
import sys

GLB_MAGIC = 0x46546C67
CHUNK_JSON = 0x4E4F534A
CHUNK_BIN = 0x004E4942


def fail(path, message):
    print(f"write-dense-site.py: {path}: {message}", file=sys.stderr)
    sys.exit(1)


def read_glb(path):
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < 20 or struct.unpack_from("<I", data, 0)[0] != GLB_MAGIC:
        fail(path, "not a binary glTF (.glb)")
    json_length, json_type = struct.unpack_from("<II", data, 12)
    if json_type != CHUNK_JSON:
        fail(path, "first chunk is not JSON")
    gltf = json.loads(data[20:20 + json_length])
    offset = 20 + json_length
    bin_length, bin_type = struct.unpack_from("<II", data, offset)
    if bin_type != CHUNK_BIN:
        fail(path, "second chunk is not BIN")
    return gltf, data[offset + 8:offset + 8 + bin_length]


def accessor_values(path, gltf, binary, index, kind, component_type):
    accessor = gltf["accessors"][index]
    if accessor["type"] != kind or accessor["componentType"] != component_type or "byteStride" in \
            gltf["bufferViews"][accessor["bufferView"]]:
        fail(path, f"/accessors/{index}: expected tightly packed {kind} of component type {component_type}")
    view = gltf["bufferViews"][accessor["bufferView"]]
    width = {"SCALAR": 1, "VEC2": 2, "VEC3": 3}[kind]
    code = "I" if component_type == 5125 else "f"
    start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    flat = struct.unpack_from(f"<{accessor['count'] * width}{code}", binary, start)
    return [flat[i:i + width] for i in range(0, len(flat), width)] if width > 1 else list(flat)


def midpoint(a, b):
    return tuple(0.5 * (x + y) for x, y in zip(a, b))


def subdivide(vertices, triangles, levels):
    """vertices: list of (position, normal, uv); triangles: index triples. Each level cuts every triangle into four
    by its edge midpoints, an edge's midpoint shared by both triangles on it (so the mesh stays watertight)."""
    for _ in range(levels):
        midpoints = {}
        result = []

        def middle(i, j):
            key = (min(i, j), max(i, j))
            if key not in midpoints:
                (pa, na, ua), (pb, nb, ub) = vertices[i], vertices[j]
                normal = midpoint(na, nb)
                length = math.sqrt(sum(c * c for c in normal)) or 1.0
                vertices.append((midpoint(pa, pb), tuple(c / length for c in normal), midpoint(ua, ub)))
                midpoints[key] = len(vertices) - 1
            return midpoints[key]

        for a, b, c in triangles:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            result += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        triangles = result
    return vertices, triangles


def dense_glb(path, levels):
    gltf, binary = read_glb(path)
    chunks = bytearray()
    views, accessors = [], []

    def add_view(payload, target=None):
        while len(chunks) % 4:
            chunks.append(0)
        view = {"buffer": 0, "byteOffset": len(chunks), "byteLength": len(payload)}
        if target:
            view["target"] = target
        chunks.extend(payload)
        views.append(view)
        return len(views) - 1

    for image in gltf.get("images", []):
        view = gltf["bufferViews"][image["bufferView"]]
        start = view.get("byteOffset", 0)
        image["bufferView"] = add_view(binary[start:start + view["byteLength"]])
    triangle_count = 0
    for mesh in gltf["meshes"]:
        for primitive in mesh["primitives"]:
            attributes = primitive["attributes"]
            if primitive.get("mode", 4) != 4 or set(attributes) != {"POSITION", "NORMAL", "TEXCOORD_0"}:
                fail(path, "a primitive that is not a triangle list of POSITION, NORMAL and TEXCOORD_0")
            positions = accessor_values(path, gltf, binary, attributes["POSITION"], "VEC3", 5126)
            normals = accessor_values(path, gltf, binary, attributes["NORMAL"], "VEC3", 5126)
            uvs = accessor_values(path, gltf, binary, attributes["TEXCOORD_0"], "VEC2", 5126)
            indices = accessor_values(path, gltf, binary, primitive["indices"], "SCALAR", 5125)
            vertices = list(zip(positions, normals, uvs))
            triangles = [tuple(indices[i:i + 3]) for i in range(0, len(indices), 3)]
            vertices, triangles = subdivide(vertices, triangles, levels)
            triangle_count += len(triangles)
            flat_positions = [c for v in vertices for c in v[0]]
            new_attributes = {}
            for name, component, kind in (("POSITION", 0, "VEC3"), ("NORMAL", 1, "VEC3"), ("TEXCOORD_0", 2, "VEC2")):
                values = [c for v in vertices for c in v[component]]
                accessor = {"bufferView": add_view(struct.pack(f"<{len(values)}f", *values), 34962),
                            "componentType": 5126, "count": len(vertices), "type": kind}
                if name == "POSITION":
                    accessor["min"] = [min(flat_positions[a::3]) for a in range(3)]
                    accessor["max"] = [max(flat_positions[a::3]) for a in range(3)]
                accessors.append(accessor)
                new_attributes[name] = len(accessors) - 1
            flat_indices = [i for t in triangles for i in t]
            accessors.append({"bufferView": add_view(struct.pack(f"<{len(flat_indices)}I", *flat_indices), 34963),
                              "componentType": 5125, "count": len(flat_indices), "type": "SCALAR"})
            primitive["attributes"] = new_attributes
            primitive["indices"] = len(accessors) - 1
    while len(chunks) % 4:
        chunks.append(0)
    gltf["accessors"], gltf["bufferViews"] = accessors, views
    gltf["buffers"] = [{"byteLength": len(chunks)}]
    text = json.dumps(gltf, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    total = 12 + 8 + len(text) + 8 + len(chunks)
    return (struct.pack("<III", GLB_MAGIC, 2, total) + struct.pack("<II", len(text), CHUNK_JSON) + text +
            struct.pack("<II", len(chunks), CHUNK_BIN) + bytes(chunks)), triangle_count


def absolute(path, folder):
    return path if os.path.isabs(path) else os.path.normpath(os.path.join(folder, path))


def main():
    if len(sys.argv) != 4 or not sys.argv[2].isdigit() or not 0 <= int(sys.argv[2]) <= 5:
        print(__doc__.split("Usage: ")[1], file=sys.stderr, end="")
        sys.exit(2)
    site_path, levels, out_dir = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    try:
        with open(site_path) as f:
            site = json.load(f)
    except (OSError, ValueError) as error:
        fail(site_path, f"not readable as JSON ({error})")
    if "sfm_mesh" not in site or "path" not in site["sfm_mesh"]:
        fail(site_path, "/sfm_mesh/path: missing (the site has no SfM mesh to make dense)")
    folder = os.path.dirname(os.path.abspath(site_path))
    mesh_path = absolute(site["sfm_mesh"]["path"], folder)
    try:
        glb, triangle_count = dense_glb(mesh_path, levels)
    except (OSError, ValueError, KeyError, IndexError, struct.error) as error:
        fail(mesh_path, f"not read ({error})")
    site["sfm_mesh"]["path"] = os.path.abspath(os.path.join(out_dir, "site.glb"))
    site["building"]["path"] = absolute(site["building"]["path"], folder)
    for sky in site.get("skies", {}).values():
        sky["path"] = absolute(sky["path"], folder)
    site["site"]["name"] = site["site"]["name"] + f", SfM mesh subdivided to {triangle_count} triangles"
    os.makedirs(out_dir, exist_ok=True)
    # Written to temporary names first, so a failure leaves no half-written pair.
    for name, payload in (("site.glb", glb), ("site.json", (json.dumps(site, indent=2) + "\n").encode())):
        with open(os.path.join(out_dir, name + ".tmp"), "wb") as f:
            f.write(payload)
    for name in ("site.glb", "site.json"):
        os.replace(os.path.join(out_dir, name + ".tmp"), os.path.join(out_dir, name))
    print(f"wrote {out_dir}/site.glb ({triangle_count} triangles) and {out_dir}/site.json")


if __name__ == "__main__":
    main()
