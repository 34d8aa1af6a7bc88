# Blender (Cycles, CPU) camera renders of gusuku-bench's visitor poses: an independent truth for the bench's
# camera tracer (issue 20 item 6). Run by compare_views_with_cycles.sh, inside Blender:
#   blender -b --factory-startup --python cycles_view_render.py -- SITE_JSON LIGHTING_DIR SLOT OUT_DIR WIDTH HEIGHT SAMPLES VIEWS
#
# The scene is built from the site file itself, not from the bake set: the building's own glTF (site.json
# /building: enu_offset_m, heading_deg, scale) and the site mesh (/sfm_mesh: scale, rotation_wxyz,
# translation_enu_m) imported by Blender's glTF importer and placed by the transforms written out below, so no
# gusuku code stands between the model files and Cycles. It is lit by LIGHTING_DIR (`gusuku-bake converge --slot
# SLOT --export-lighting`): the sky without its sun disc and a sun lamp of the tracer's direction, irradiance and
# disc, here ungated (a camera sees direct sunlight). Surfaces are Lambertian (cycles_scene.py), bounces as the
# site's bake.max_bounces.
#
# VIEWS is gusuku-bench's --views (NAME:E,N,U:E,N,U[:HFOV], ';'-separated; default field of view 60 degrees,
# horizontal): the camera is the bench's pinhole (CameraIntrinsics::fromFieldOfView: square pixels, principal
# point at the centre) looking from the first point at the second, world up +U, each pixel the box average of
# its rays (the tracer jitters its rays uniformly in the pixel). Per view it writes, in OUT_DIR, each radiance
# frame twice, SAMPLES a pixel with two seeds (NAME_building.exr and NAME_building_b.exr, ...): their mean is the
# estimate and their difference its noise, which gusuku-bench --cycles-truth takes out of the comparison:
#   NAME_building.exr  linear Rec.709 radiance (RGBA float), the site with the building
#   NAME_site.exr      the same without the building (the camera frame)
#   NAME_materials.exr the building material at each pixel's centre: R = index + 1 in materials.json's list
#                      (0: no building material), one sample, no filter
# and materials.json: the building's material names in index order.
import json
import math
import os
import sys

import bpy
import mathutils

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cycles_scene  # noqa: E402  (this folder, put on the path above)


def fail(message):
    print(f"cycles_view_render: {message}", file=sys.stderr, flush=True)
    sys.exit(1)


def parse_views(text):
    """gusuku-bench's --views (bench/bench/bench_views.h): [(name, position, look_at, horizontal_fov_deg)]."""
    views = []
    for number, pose in enumerate(p for p in text.split(";") if p.strip()):
        fields = pose.strip().split(":")
        try:
            position = [float(v) for v in fields[1].split(",")]
            look_at = [float(v) for v in fields[2].split(",")]
            fov = float(fields[3]) if len(fields) > 3 else 60.0
        except (IndexError, ValueError):
            fail(f"VIEWS pose {number + 1} '{pose}': expected NAME:E,N,U:E,N,U[:FOV]")
        if len(position) != 3 or len(look_at) != 3:
            fail(f"VIEWS pose {number + 1} '{fields[0]}': a point needs three coordinates")
        views.append((fields[0], mathutils.Vector(position), mathutils.Vector(look_at), fov))
    if not views:
        fail("VIEWS: no pose")
    return views


# Blender's importer maps glTF (x, y, z) to (x, -z, y); gusuku's site transforms start from the model's own
# axes, so the importer's change is undone first.
GLTF_FROM_BLENDER = mathutils.Matrix(((1, 0, 0, 0), (0, 0, 1, 0), (0, -1, 0, 0), (0, 0, 0, 1)))
ENU_FROM_GLTF = GLTF_FROM_BLENDER.inverted()


def place(objects, enu_from_model):
    """Parents the imported roots to an empty whose matrix takes Blender's import frame to site ENU."""
    holder = bpy.data.objects.new("placement", None)
    bpy.context.scene.collection.objects.link(holder)
    holder.matrix_world = enu_from_model @ GLTF_FROM_BLENDER
    for obj in objects:
        if obj.parent is None:
            obj.parent = holder


def building_transform(building):
    """site.cpp BuildingConfig::enuFromModel: translate(origin) x turn about up by -heading x scale x ENU<-glTF."""
    if "enu_offset_m" not in building:
        fail("site.json /building: only enu_offset_m placement is supported here (not a geodetic position)")
    turn = mathutils.Matrix.Rotation(-math.radians(building.get("heading_deg", 0.0)), 4, "Z")
    scale = mathutils.Matrix.Scale(building.get("scale", 1.0), 4)
    return mathutils.Matrix.Translation(building["enu_offset_m"]) @ turn @ scale @ ENU_FROM_GLTF


def site_mesh_transform(sfm):
    """site.cpp SfmMeshConfig::enuFromModel: translate x rotate (quaternion w, x, y, z) x scale."""
    rotation = mathutils.Quaternion(sfm.get("rotation_wxyz", [1, 0, 0, 0])).to_matrix().to_4x4()
    return (mathutils.Matrix.Translation(sfm.get("translation_enu_m", [0, 0, 0])) @ rotation @
            mathutils.Matrix.Scale(sfm.get("scale", 1.0), 4))


def load_site(site_json):
    with open(site_json) as stream:
        site = json.load(stream)
    base = os.path.dirname(os.path.abspath(site_json))
    site_objects = cycles_scene.import_gltf(os.path.join(base, site["sfm_mesh"]["path"]))
    place(site_objects, site_mesh_transform(site["sfm_mesh"]))
    building_objects = cycles_scene.import_gltf(os.path.join(base, site["building"]["path"]))
    place(building_objects, building_transform(site["building"]))
    return site, [o for o in building_objects if o.type == "MESH"]


def add_camera(scene, position, look_at, fov_deg, width, height):
    data = bpy.data.cameras.new("bench")
    data.sensor_fit = "HORIZONTAL"
    data.angle = math.radians(fov_deg)
    data.clip_start, data.clip_end = 0.01, 10000.0
    camera = bpy.data.objects.new("bench", data)
    camera.rotation_mode = "QUATERNION"
    camera.rotation_quaternion = (look_at - position).to_track_quat("-Z", "Y")
    camera.location = position
    scene.collection.objects.link(camera)
    scene.camera = camera
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0


def render_to(scene, path):
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)


def render_two_seeds(scene, stem):
    """STEM.exr with seed 1 and STEM_b.exr with seed 2."""
    for seed, suffix in ((1, ""), (2, "_b")):
        scene.cycles.seed = seed
        render_to(scene, f"{stem}{suffix}.exr")


def material_id_pass(scene, building_objects, path):
    """Swaps every building material for an emission of (index + 1, 0, 0), hides the rest, renders one
    unfiltered sample (each pixel its centre), then restores the materials."""
    names = sorted({s.material.name for o in building_objects for s in o.material_slots if s.material})
    saved = {o.name: [s.material for s in o.material_slots] for o in building_objects}
    emissions = {}
    for index, name in enumerate(names):
        material = bpy.data.materials.new(f"id_{index}")
        material.use_nodes = True
        tree = material.node_tree
        tree.nodes.clear()
        emission = tree.nodes.new("ShaderNodeEmission")
        emission.inputs["Color"].default_value = (index + 1.0, 0.0, 0.0, 1.0)
        output = tree.nodes.new("ShaderNodeOutputMaterial")
        tree.links.new(emission.outputs["Emission"], output.inputs["Surface"])
        emissions[name] = material
    for obj in building_objects:
        for slot in obj.material_slots:
            if slot.material:
                slot.material = emissions[slot.material.name]
    others = [o for o in scene.objects if o.type in {"MESH", "LIGHT"} and o not in building_objects]
    for obj in others:
        obj.hide_render = True
    world_strength = scene.world.node_tree.nodes["Background"].inputs["Strength"]
    world_strength.default_value = 0.0
    samples, filter_width = scene.cycles.samples, scene.cycles.filter_width
    scene.cycles.samples, scene.cycles.filter_width = 1, 0.01
    render_to(scene, path)
    scene.cycles.samples, scene.cycles.filter_width = samples, filter_width
    world_strength.default_value = 1.0
    for obj in others:
        obj.hide_render = False
    for obj in building_objects:
        for slot, material in zip(obj.material_slots, saved[obj.name]):
            slot.material = material
    return names


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    if len(args) != 8:
        fail("usage: -- SITE_JSON LIGHTING_DIR SLOT OUT_DIR WIDTH HEIGHT SAMPLES VIEWS")
    site_json, lighting_dir, slot, out_dir = args[:4]
    width, height, samples = int(args[4]), int(args[5]), int(args[6])
    views = parse_views(args[7])
    with open(site_json) as stream:
        max_bounces = int(json.load(stream)["bake"].get("max_bounces", 3))
    scene = cycles_scene.start_cycles_scene(max_bounces=max_bounces)
    cycles_scene.add_exported_lighting(scene, lighting_dir, slot, gate_direct_sun=False)
    _, building_objects = load_site(site_json)
    cycles_scene.make_materials_lambertian(textures_in_linear_light=True)
    scene.cycles.samples = samples
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 1.0
    scene.view_settings.view_transform = "Standard"  # EXR is written scene-linear whatever the view; set anyway
    settings = scene.render.image_settings
    settings.file_format, settings.color_mode, settings.color_depth, settings.exr_codec = "OPEN_EXR", "RGBA", "32", "ZIP"
    os.makedirs(out_dir, exist_ok=True)
    names = []
    for name, position, look_at, fov in views:
        add_camera(scene, position, look_at, fov, width, height)
        render_two_seeds(scene, f"{out_dir}/{name}_building")
        names = material_id_pass(scene, building_objects, f"{out_dir}/{name}_materials.exr")
        for obj in building_objects:
            obj.hide_render = True
        render_two_seeds(scene, f"{out_dir}/{name}_site")
        for obj in building_objects:
            obj.hide_render = False
        print(f"CYCLES_VIEW {name} {width}x{height} samples={samples}", flush=True)
    with open(f"{out_dir}/materials.json", "w") as stream:
        json.dump(names, stream)


main()
