# The terms of one building material's colour in the runtime's composite (issue 20 item 9), each read from the
# files themselves, no gusuku code in between. Run inside Blender:
#   blender -b --factory-startup --python material_colour_terms.py -- SITE_JSON BAKESET LIGHTING_DIR SLOT MATERIAL
#
# The runtime shades a building pixel as albedo x (V E_sun cos + E_ind) / pi x exposure (docs/design.md 3), so
# its colour is the product of three colours: the base colour (texture x factor, sampled at a mip level: the mip
# chain is a box filter in linear light, which keeps the mean, so the mean at every level is printed), the baked
# E_ind (the slot's lightmap, read at the material's faces' TEXCOORD_1) and the sun's irradiance. Each line gives
# a term's mean linear RGB and its G/R and B/R, the saturation the finding is about:
#   texture_source  the site's own glTF texture (decoded by Blender), mean over every texel, per mip level
#   texture_bakeset the texture as the bake set's building.glb holds it (what the runtime uploads)
#   lightmap        mean E_ind over the lightmap texels the material's face corners and centres land on
#   sun             the slot's sun irradiance (LIGHTING_DIR/sun_SLOT.json)
import json
import os
import sys

import bpy
import numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cycles_scene  # noqa: E402  (this folder, put on the path above)


def srgb_decode(encoded):
    return numpy.where(encoded <= 0.04045, encoded / 12.92, ((encoded + 0.055) / 1.055) ** 2.4)


def pixels_of(image, raw):
    """RGBA float array, rows from the bottom (Blender's order). raw: the stored values (no colour transform)."""
    if raw:
        image.colorspace_settings.name = "Non-Color"
    width, height = image.size
    return numpy.array(image.pixels[:], dtype=numpy.float64).reshape(height, width, 4)


def colour_line(label, rgb):
    r, g, b = rgb[:3]
    print(f"TERM {label}: linear ({r:.4f}, {g:.4f}, {b:.4f}) G/R {g / r:.3f} B/R {b / r:.3f}", flush=True)


def base_colour_image(material):
    """The image feeding the material's base colour (the glTF importer's Image Texture node), or None."""
    for node in material.node_tree.nodes:
        if node.type == "TEX_IMAGE" and node.image is not None:
            return node.image
    return None


def mip_means(linear_rgb):
    """Mean RGB of each mip level, box-filtered 2 x 2 in linear light as the runtime's chain (odd sides cropped)."""
    level, means = linear_rgb, []
    while True:
        means.append(level.reshape(-1, 3).mean(axis=0))
        height, width = level.shape[0] // 2, level.shape[1] // 2
        if height == 0 or width == 0:
            return means
        level = level[:2 * height, :2 * width].reshape(height, 2, width, 2, 3).mean(axis=(1, 3))


def texture_terms(label, material):
    image = base_colour_image(material)
    if image is None:
        print(f"TERM {label}: no base colour texture", flush=True)
        return
    linear = srgb_decode(pixels_of(image, raw=True)[..., :3])
    means = mip_means(linear)
    for level in (0, 1, 2, 3, 4, len(means) - 1):
        colour_line(f"{label} {image.size[0]}x{image.size[1]} mip {level}", means[level])


def lightmap_term(obj_list, material_name, lightmap):
    height, width = lightmap.shape[:2]
    samples = []
    for obj in obj_list:
        mesh = obj.data
        if len(mesh.uv_layers) < 2:
            continue
        uv = mesh.uv_layers[1].data
        for polygon in mesh.polygons:
            slot_material = obj.material_slots[polygon.material_index].material
            if slot_material is None or slot_material.name != material_name:
                continue
            corners = [uv[loop].uv for loop in polygon.loop_indices]
            centre = sum((c for c in corners[1:]), corners[0].copy()) / len(corners)
            for point in corners + [centre]:
                x = min(max(int(point.x * width), 0), width - 1)
                y = min(max(int(point.y * height), 0), height - 1)  # Blender's rows run from the bottom, as UV v
                texel = lightmap[y, x]
                if texel[3] >= 0.999:
                    samples.append(texel[:3])
    if not samples:
        print(f"TERM lightmap: no valid texel under {material_name}", flush=True)
        return
    colour_line(f"lightmap E_ind ({len(samples)} texel reads)", numpy.mean(samples, axis=0))


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    if len(args) != 5:
        print("material_colour_terms: usage: -- SITE_JSON BAKESET LIGHTING_DIR SLOT MATERIAL", file=sys.stderr)
        sys.exit(1)
    site_json, bakeset, lighting_dir, slot, material_name = args
    with open(site_json) as stream:
        site = json.load(stream)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    source = os.path.join(os.path.dirname(os.path.abspath(site_json)), site["building"]["path"])
    cycles_scene.import_gltf(source)
    if material_name not in bpy.data.materials:
        print(f"material_colour_terms: {source}: no material named '{material_name}'", file=sys.stderr)
        sys.exit(1)
    texture_terms("texture_source", bpy.data.materials[material_name])
    baked_objects = [o for o in cycles_scene.import_gltf(f"{bakeset}/building.glb") if o.type == "MESH"]
    baked_materials = {s.material.name for o in baked_objects for s in o.material_slots if s.material}
    baked_name = next((n for n in sorted(baked_materials) if n.startswith(material_name) and n != material_name),
                      material_name)
    texture_terms("texture_bakeset", bpy.data.materials[baked_name])
    lightmap = pixels_of(bpy.data.images.load(f"{bakeset}/building_{slot}.exr"), raw=False)
    lightmap_term(baked_objects, baked_name, lightmap)
    sun = cycles_scene.read_sun(lighting_dir, slot)
    if sun["present"]:
        colour_line("sun E_sun at normal incidence", sun["irradiance_rgb"])


main()
