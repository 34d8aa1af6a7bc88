# Blender (Cycles, CPU) bake of the same lightmap gusuku bakes, for the speed comparison of issue 3.
#
# Run by bench/cycles/compare_with_cycles.sh, inside Blender:
#   blender -b --factory-startup --python cycles_lightmap_bake.py -- BAKESET SITE_GLB SKY_HDR SAMPLES... 
#
# It imports the bake set's building.glb (whose TEXCOORD_1 holds gusuku's lightmap charts) and the site mesh,
# lights them with the overcast sky only (an overcast slot has no sun, so gusuku's E_ind is the whole
# irradiance and Cycles' DIFFUSE bake of direct + indirect light measures the same quantity, times 1/pi), and
# bakes the building's lightmap at each sample count, timing each bake. It prints one line per bake with the
# relative RMS error of luminance against Cycles' own highest-sample bake (the last count given) over the texels
# gusuku marks valid, and the agreement of Cycles' converged bake with gusuku's overcast lightmap.
import math
import sys
import time

import bpy
import numpy

# Debian 12's Blender 3.4 glTF importer still uses numpy.bool, which Debian 12's numpy 1.24 removed.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

args = sys.argv[sys.argv.index("--") + 1:]
bakeset, site_glb, sky_hdr = args[0], args[1], args[2]
sample_counts = [int(a) for a in args[3:]]

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.render.threads_mode = "FIXED"
scene.render.threads = 2
# Three diffuse bounces, as the sample site's bake.max_bounces; nothing else in the scene needs more.
scene.cycles.max_bounces = 3
scene.cycles.diffuse_bounces = 3
scene.cycles.glossy_bounces = 0
scene.cycles.transmission_bounces = 0
scene.cycles.transparent_max_bounces = 0
scene.cycles.use_denoising = False
scene.cycles.sample_clamp_direct = 0.0
scene.cycles.sample_clamp_indirect = 0.0

world = bpy.data.worlds.new("sky")
scene.world = world
world.use_nodes = True
environment = world.node_tree.nodes.new("ShaderNodeTexEnvironment")
environment.image = bpy.data.images.load(sky_hdr)
world.node_tree.links.new(environment.outputs["Color"], world.node_tree.nodes["Background"].inputs["Color"])

bpy.ops.import_scene.gltf(filepath=site_glb)
site_objects = set(bpy.context.selected_objects)
bpy.ops.import_scene.gltf(filepath=bakeset + "/building.glb")
building = [o for o in bpy.context.selected_objects if o.type == "MESH"]

reference_image = bpy.data.images.load(bakeset + "/building_overcast.exr")
resolution = reference_image.size[0]
target = bpy.data.images.new("lightmap", resolution, resolution, float_buffer=True, alpha=False)

# gusuku's surfaces are purely diffuse: turn off the Principled BSDF's specular layer everywhere, so Cycles'
# diffuse light is not reduced by a Fresnel term gusuku does not model.
for material in bpy.data.materials:
    if material.node_tree is None:
        continue
    for node in material.node_tree.nodes:
        if node.type == "BSDF_PRINCIPLED":
            node.inputs["Specular"].default_value = 0.0

for obj in building:
    uv_layers = obj.data.uv_layers
    uv_layers.active_index = 1  # TEXCOORD_1: the lightmap charts
    for slot in obj.material_slots:
        nodes = slot.material.node_tree.nodes
        node = nodes.new("ShaderNodeTexImage")
        node.image = target
        nodes.active = node

bpy.ops.object.select_all(action="DESELECT")
for obj in building:
    obj.select_set(True)
bpy.context.view_layer.objects.active = building[0]


def luminance_texels(pixels, alpha_mask=None):
    values = []
    for i in range(0, len(pixels), 4):
        values.append(0.2126 * pixels[i] + 0.7152 * pixels[i + 1] + 0.0722 * pixels[i + 2])
    return values


gusuku_pixels = reference_image.pixels[:]
valid = [gusuku_pixels[i + 3] >= 0.999 for i in range(0, len(gusuku_pixels), 4)]
gusuku_luminance = luminance_texels(gusuku_pixels)


def relative_rms(estimate, reference, scale=1.0):
    squared, total, count = 0.0, 0.0, 0
    for e, r, ok in zip(estimate, reference, valid):
        if not ok:
            continue
        squared += (e * scale - r) ** 2
        total += r
        count += 1
    return math.sqrt(squared / count) / (total / count)


results = []
for samples in sample_counts:
    scene.cycles.samples = samples
    start = time.perf_counter()
    bpy.ops.object.bake(type="DIFFUSE", pass_filter={"DIRECT", "INDIRECT"}, margin=2, use_clear=True)
    seconds = time.perf_counter() - start
    results.append((samples, seconds, luminance_texels(target.pixels[:])))
    print(f"CYCLES_BAKE samples={samples} seconds={seconds:.2f}", flush=True)

reference_samples, _, cycles_reference = results[-1]
for samples, seconds, estimate in results[:-1]:
    print(f"CYCLES_RESULT samples={samples} seconds={seconds:.2f} "
          f"relative_rms={relative_rms(estimate, cycles_reference):.4f}", flush=True)
# Cycles' diffuse light pass is irradiance / pi; the fitted scale should come out near pi.
fit = sum(g for g, ok in zip(gusuku_luminance, valid) if ok) / sum(c for c, ok in zip(cycles_reference, valid) if ok)
print(f"CYCLES_AGREEMENT reference_samples={reference_samples} fitted_scale={fit:.4f} (pi = {math.pi:.4f}) "
      f"relative_rms_vs_gusuku_at_pi={relative_rms(cycles_reference, gusuku_luminance, math.pi):.4f}", flush=True)
