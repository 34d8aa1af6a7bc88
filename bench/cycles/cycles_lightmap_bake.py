# Blender (Cycles, CPU) bake of the same lightmap gusuku bakes, for the speed comparison of issues 3 and 11.
#
# Run by bench/cycles/compare_with_cycles.sh, inside Blender:
#   blender -b --factory-startup --python cycles_lightmap_bake.py -- BAKESET SITE_GLB LIGHTING_DIR SLOT REFERENCE SAMPLES...
#
# It imports the bake set's building.glb (whose TEXCOORD_1 holds gusuku's lightmap charts) and the site mesh, and
# lights them as gusuku's bake of SLOT does (LIGHTING_DIR from `gusuku-bake converge --export-lighting`): the sky
# map the tracer samples (the sun disc taken out, laid out for Blender's world) and, for a sunny slot, a sun lamp
# of the tracer's direction, irradiance and angular radius. gusuku's texels hold E_ind, everything but the direct
# sun at the texel (docs/bakeset.md), so the sun lamp's strength is gated to 0 when it is sampled
# from the baked surface itself (where a bake's Light Path ray depth reads 1, measured) and to its irradiance at every later vertex (light bounced off the
# building and the site): Cycles' DIFFUSE bake of direct + indirect light then measures E_ind / pi, as it does
# for an overcast slot with no sun at all. It bakes the building's lightmap at each sample count, timing each
# bake, with every texel taking all its samples ("fixed", as gusuku does) and, unless CYCLES_MODES says
# otherwise, with Cycles' adaptive sampling (Blender's default since 3.0). Each line gives the relative RMS
# error of luminance against Cycles' own fixed bake at REFERENCE samples, over the texels gusuku marks valid, and
# the same error with the reference's own noise taken out: the reference is the mean of two bakes of
# REFERENCE / 2 samples with different seeds, whose difference measures its noise (its mean square is 4 times
# the reference's own), and the noise of independent estimates adds in squares. Last, the agreement of that
# converged bake with gusuku's lightmap of the slot.
import math
import os
import sys
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cycles_scene  # noqa: E402  (this folder, put on the path above)

args = sys.argv[sys.argv.index("--") + 1:]
bakeset, site_glb, lighting_dir, slot = args[0], args[1], args[2], args[3]
reference_samples = int(args[4])
sample_counts = [int(a) for a in args[5:]]
modes = os.environ.get("CYCLES_MODES", "fixed,adaptive").split(",")

# Three diffuse bounces, as the sample site's bake.max_bounces; nothing else in the scene needs more.
scene = cycles_scene.start_cycles_scene(max_bounces=3)
cycles_scene.add_exported_lighting(scene, lighting_dir, slot, gate_direct_sun=True)
site_objects = set(cycles_scene.import_gltf(site_glb))
building = [o for o in cycles_scene.import_gltf(bakeset + "/building.glb") if o.type == "MESH"]

reference_image = bpy.data.images.load(f"{bakeset}/building_{slot}.exr")
resolution = reference_image.size[0]
target = bpy.data.images.new("lightmap", resolution, resolution, float_buffer=True, alpha=False)

cycles_scene.make_materials_lambertian()

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


def write_coverage_mask(path):
    """The texels the errors cover (gusuku-valid and baked by Cycles) as a binary PGM (255 = covered), row 0 at
    the top as image files and gusuku have it (Blender's pixel rows run from the bottom), so that `gusuku-bake
    converge --error-mask` measures gusuku's error over the same texels."""
    width, height = reference_image.size
    rows = [bytes(255 if valid[(height - 1 - y) * width + x] else 0 for x in range(width)) for y in range(height)]
    with open(path + ".tmp", "wb") as stream:
        stream.write(f"P5\n{width} {height}\n255\n".encode("ascii"))
        stream.write(b"".join(rows))
    os.replace(path + ".tmp", path)


def bake(samples, adaptive, seed=0):
    """One timed Cycles bake of the lightmap; returns (seconds, luminance per texel)."""
    scene.cycles.samples = samples
    scene.cycles.seed = seed
    scene.cycles.use_adaptive_sampling = adaptive
    start = time.perf_counter()
    bpy.ops.object.bake(type="DIFFUSE", pass_filter={"DIRECT", "INDIRECT"}, margin=2, use_clear=True)
    seconds = time.perf_counter() - start
    print(f"CYCLES_BAKE samples={samples} adaptive={int(adaptive)} seconds={seconds:.2f}", flush=True)
    return seconds, luminance_texels(target.pixels[:])


def timing_repeat():
    """REFERENCE 0: times the same bakes again and prints only seconds (the errors do not change between runs:
    Cycles' seed is fixed), so the comparison can interleave its timings with gusuku's."""
    for adaptive in [mode == "adaptive" for mode in modes]:
        for samples in sample_counts:
            seconds, _ = bake(samples, adaptive)
            print(f"CYCLES_TIMING mode={'adaptive' if adaptive else 'fixed'} samples={samples} seconds={seconds:.2f}",
                  flush=True)


def measured_run():
    # The reference: every texel gets all its samples (adaptive sampling would stop near its noise threshold).
    # Two halves with other seeds than the study's (0): their mean is the reference, their difference its noise.
    _, half_a = bake(reference_samples // 2, adaptive=False, seed=1)
    _, half_b = bake(reference_samples // 2, adaptive=False, seed=2)
    cycles_reference = [(a + b) / 2 for a, b in zip(half_a, half_b)]
    # Texels Cycles leaves unbaked (0 in both halves) are left out of every figure: on the shrine's many small
    # triangles Cycles bakes only 56 % of the texels gusuku traces (those whose centre a triangle covers, measured
    # on its overcast slot; gusuku traces every texel a triangle touches), and counting the rest as black would
    # compare nothing. The count is printed.
    global valid
    gusuku_valid = sum(valid)
    valid = [ok and (a > 0.0 or b > 0.0) for ok, a, b in zip(valid, half_a, half_b)]
    print(f"CYCLES_COVERAGE gusuku_valid_texels={gusuku_valid} baked_by_cycles={sum(valid)}", flush=True)
    mask_path = os.environ.get("CYCLES_COVERAGE_MASK")
    if mask_path:
        write_coverage_mask(mask_path)
    reference_rms = relative_rms(half_a, half_b) / 2
    print(f"CYCLES_REFERENCE samples={reference_samples} own_relative_rms={reference_rms:.4f}", flush=True)
    for mode in modes:
        adaptive = mode == "adaptive"
        for samples in sample_counts:
            seconds, estimate = bake(samples, adaptive)
            measured = relative_rms(estimate, cycles_reference)
            print(f"CYCLES_RESULT mode={mode} samples={samples} seconds={seconds:.2f} "
                  f"relative_rms={measured:.4f} "
                  f"relative_rms_corrected={math.sqrt(max(measured ** 2 - reference_rms ** 2, 0.0)):.4f}", flush=True)
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
