# Blender (Cycles, CPU) bake of the same lightmap gusuku bakes, for the speed comparison of issue 3.
#
# Run by bench/cycles/compare_with_cycles.sh, inside Blender:
#   blender -b --factory-startup --python cycles_lightmap_bake.py -- BAKESET SITE_GLB SKY_HDR REFERENCE SAMPLES...
#
# It imports the bake set's building.glb (whose TEXCOORD_1 holds gusuku's lightmap charts) and the site mesh,
# lights them with the overcast sky only (an overcast slot has no sun, so gusuku's E_ind is the whole
# irradiance and Cycles' DIFFUSE bake of direct + indirect light measures the same quantity, times 1/pi), and
# bakes the building's lightmap at each sample count, timing each bake, twice: with every texel taking all its
# samples ("fixed", as gusuku does) and with Cycles' adaptive sampling (Blender's default since 3.0: texels stop
# once their noise estimate is under a threshold, so the error stalls near it). It prints one line per bake
# with the relative RMS error of luminance against Cycles' own fixed bake at REFERENCE samples, over the texels
# gusuku marks valid, and the agreement of that converged bake with gusuku's overcast lightmap.
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
reference_samples = int(args[3])
sample_counts = [int(a) for a in args[4:]]

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

# gusuku's surfaces are Lambertian. Blender's glTF importer gives every material a Principled BSDF, whose
# diffuse lobe is not Lambertian (retro-reflection at roughness > 0) and whose specular layer takes energy
# through a Fresnel term. Replace each with a Diffuse BSDF (roughness 0: Lambert) fed the same base colour, so
# both tools bake the same light transport.
for material in bpy.data.materials:
    if material.node_tree is None:
        continue
    tree = material.node_tree
    for principled in [n for n in tree.nodes if n.type == "BSDF_PRINCIPLED"]:
        diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Roughness"].default_value = 0.0
        base_colour = principled.inputs["Base Color"]
        if base_colour.is_linked:
            tree.links.new(base_colour.links[0].from_socket, diffuse.inputs["Color"])
        else:
            diffuse.inputs["Color"].default_value = base_colour.default_value
        for link in list(principled.outputs["BSDF"].links):
            tree.links.new(diffuse.outputs["BSDF"], link.to_socket)
        tree.nodes.remove(principled)

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


def bake(samples, adaptive):
    """One timed Cycles bake of the lightmap; returns (seconds, luminance per texel)."""
    scene.cycles.samples = samples
    scene.cycles.use_adaptive_sampling = adaptive
    start = time.perf_counter()
    bpy.ops.object.bake(type="DIFFUSE", pass_filter={"DIRECT", "INDIRECT"}, margin=2, use_clear=True)
    seconds = time.perf_counter() - start
    print(f"CYCLES_BAKE samples={samples} adaptive={int(adaptive)} seconds={seconds:.2f}", flush=True)
    return seconds, luminance_texels(target.pixels[:])


def timing_repeat():
    """REFERENCE 0: times the same bakes again and prints only seconds (the errors do not change between runs:
    Cycles' seed is fixed), so the comparison can interleave its timings with gusuku's."""
    for adaptive in (False, True):
        for samples in sample_counts:
            seconds, _ = bake(samples, adaptive)
            print(f"CYCLES_TIMING mode={'adaptive' if adaptive else 'fixed'} samples={samples} seconds={seconds:.2f}",
                  flush=True)


def measured_run():
    # The reference: every texel gets all its samples (adaptive sampling would stop near its noise threshold).
    _, cycles_reference = bake(reference_samples, adaptive=False)
    for adaptive in (False, True):
        mode = "adaptive" if adaptive else "fixed"
        for samples in sample_counts:
            seconds, estimate = bake(samples, adaptive)
            print(f"CYCLES_RESULT mode={mode} samples={samples} seconds={seconds:.2f} "
                  f"relative_rms={relative_rms(estimate, cycles_reference):.4f}", flush=True)
    # Cycles' diffuse light pass is irradiance / pi; the fitted scale should come out near pi.
    fit = (sum(g for g, ok in zip(gusuku_luminance, valid) if ok) /
           sum(c for c, ok in zip(cycles_reference, valid) if ok))
    print(f"CYCLES_AGREEMENT reference_samples={reference_samples} fitted_scale={fit:.4f} (pi = {math.pi:.4f}) "
          f"relative_rms_vs_gusuku_at_pi={relative_rms(cycles_reference, gusuku_luminance, math.pi):.4f}",
          flush=True)


if reference_samples == 0:
    timing_repeat()
else:
    measured_run()
