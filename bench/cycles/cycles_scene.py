# The Cycles scene both Blender scripts of bench/cycles build: Cycles on the CPU with gusuku's light transport
# (Lambertian surfaces, diffuse bounces only, no denoiser, no clamping), lit by one slot's lighting as
# `gusuku-bake converge --export-lighting` writes it (the sky without its sun disc, laid out for Blender's world,
# and the sun's direction, irradiance and disc). Imported by cycles_lightmap_bake.py and cycles_view_render.py
# (run inside Blender, which puts this folder on sys.path through them). Standard library, numpy and bpy only.
import json
import math

import bpy
import mathutils
import numpy

# Debian 12's Blender 3.4 glTF importer still uses numpy.bool, which Debian 12's numpy 1.24 removed.
if not hasattr(numpy, "bool"):
    numpy.bool = bool


def start_cycles_scene(max_bounces, threads=2):
    """An empty scene rendered by Cycles on the CPU: max_bounces diffuse bounces (the site's bake.max_bounces),
    nothing glossy or transmissive, no denoiser, no sample clamping (both bias the estimate)."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.render.threads_mode = "FIXED"
    scene.render.threads = threads
    scene.cycles.max_bounces = max_bounces
    scene.cycles.diffuse_bounces = max_bounces
    scene.cycles.glossy_bounces = 0
    scene.cycles.transmission_bounces = 0
    # Passing through an alpha-masked card's hole is a transparent bounce (make_materials_lambertian): gusuku's
    # traversal skips holes at no bounce, so allow many. No other material is transparent.
    scene.cycles.transparent_max_bounces = 64
    scene.cycles.use_denoising = False
    scene.cycles.sample_clamp_direct = 0.0
    scene.cycles.sample_clamp_indirect = 0.0
    return scene


def read_sun(lighting_dir, slot):
    with open(f"{lighting_dir}/sun_{slot}.json") as stream:
        return json.load(stream)


def add_exported_lighting(scene, lighting_dir, slot, gate_direct_sun):
    """The slot's sky as the world and, for a sunny slot, a sun lamp of the tracer's direction, irradiance and
    disc. gate_direct_sun: the lamp gives nothing when sampled from the first surface a path meets (a lightmap
    texel holds E_ind, everything but the direct sun, docs/bakeset.md), and its irradiance at every later
    vertex. Returns the sun's JSON."""
    world = bpy.data.worlds.new("sky")
    scene.world = world
    world.use_nodes = True
    environment = world.node_tree.nodes.new("ShaderNodeTexEnvironment")
    environment.image = bpy.data.images.load(f"{lighting_dir}/sky_{slot}.hdr")
    # The tracer reads the texel containing a direction, unfiltered (sky_sampling.glsl skyRadiance): so does this.
    environment.interpolation = "Closest"
    world.node_tree.links.new(environment.outputs["Color"], world.node_tree.nodes["Background"].inputs["Color"])
    sun = read_sun(lighting_dir, slot)
    if not sun["present"]:
        return sun
    # E_sun per channel at normal incidence (a Cycles sun's strength is irradiance), Blender's angle is the
    # disc's diameter, shining along -direction_enu (Blender's world axes are ENU in these scenes).
    irradiance = sun["irradiance_rgb"]
    strength = max(irradiance)
    lamp_data = bpy.data.lights.new("sun", type="SUN")
    lamp_data.energy = strength
    lamp_data.color = [c / strength for c in irradiance]
    lamp_data.angle = math.radians(2.0 * sun["angular_radius_deg"])
    if gate_direct_sun:
        lamp_data.use_nodes = True
        nodes = lamp_data.node_tree.nodes
        emission = next(n for n in nodes if n.type == "EMISSION")
        light_path = nodes.new("ShaderNodeLightPath")
        after_first_bounce = nodes.new("ShaderNodeMath")
        after_first_bounce.operation = "GREATER_THAN"
        # Cycles' Light Path "Ray Depth" reads 1, not 0, when a light is sampled from the baked surface itself
        # (measured on the sample's sunny_1200: a threshold of 0.5 leaves the direct sun in, fitted scale 0.918
        # against gusuku's E_ind; 1.5 gives 3.1409, pi; no sun at all gives 3.989).
        after_first_bounce.inputs[1].default_value = 1.5
        lamp_data.node_tree.links.new(light_path.outputs["Ray Depth"], after_first_bounce.inputs[0])
        lamp_data.node_tree.links.new(after_first_bounce.outputs["Value"], emission.inputs["Strength"])
    lamp = bpy.data.objects.new("sun", lamp_data)
    lamp.rotation_mode = "QUATERNION"
    lamp.rotation_quaternion = mathutils.Vector(sun["direction_enu"]).to_track_quat("Z", "Y")
    scene.collection.objects.link(lamp)
    return sun


def import_gltf(path):
    """Imports a glTF or glb; returns the objects it made (Blender's importer turns glTF's +Y up into +Z up:
    glTF (x, y, z) -> (x, -z, y), the axis change gusuku's loader makes into ENU)."""
    bpy.ops.object.select_all(action="DESELECT")
    bpy.ops.import_scene.gltf(filepath=path)
    return list(bpy.context.selected_objects)


def linear_light_copy(image):
    """A float copy of an 8-bit sRGB texture, decoded to linear light (the sRGB curve, as gusuku's tracer
    decodes), so that Cycles' bilinear lookup mixes linear values as the tracer's does."""
    image.colorspace_settings.name = "Non-Color"  # read the stored bytes, untransformed
    width, height = image.size
    texels = numpy.empty(width * height * 4, dtype=numpy.float32)
    image.pixels.foreach_get(texels)
    rgba = texels.reshape(-1, 4)
    encoded = rgba[:, :3]
    rgba[:, :3] = numpy.where(encoded <= 0.04045, encoded / 12.92, ((encoded + 0.055) / 1.055) ** 2.4)
    copy = bpy.data.images.new(image.name + " linear", width, height, alpha=True, float_buffer=True)
    copy.colorspace_settings.name = "Linear"
    copy.pixels.foreach_set(texels)
    return copy


def make_materials_lambertian(textures_in_linear_light=False):
    """gusuku's surfaces are Lambertian. Blender's glTF importer gives every material a Principled BSDF, whose
    diffuse lobe is not Lambertian (retro-reflection at roughness > 0) and whose specular layer takes energy
    through a Fresnel term. Each becomes a Diffuse BSDF (roughness 0: Lambert) fed the same base colour.
    textures_in_linear_light: Cycles keeps an 8-bit sRGB texture as bytes and decodes after its bilinear lookup,
    mixing neighbouring texels in sRGB rather than linear light, which darkens a grainy texture's mean: on the
    shrine the building read 1.02 % (front pose) and 0.32 % (corner) darker than the bench's camera tracer
    over the bench's mask (bench/cycles/README.md). With it, every 8-bit sRGB texture is replaced by a float
    copy decoded to linear light, so Cycles' lookup is the tracer's: decode, then interpolate."""
    copies = {}
    for material in bpy.data.materials:
        if material.node_tree is None:
            continue
        tree = material.node_tree
        for node in tree.nodes:
            if not (textures_in_linear_light and node.type == "TEX_IMAGE" and node.image is not None):
                continue
            # An image two materials share is copied once (its colour space is Non-Color after the first).
            if node.image.name not in copies and not node.image.is_float and \
                    node.image.colorspace_settings.name == "sRGB":
                copies[node.image.name] = linear_light_copy(node.image)
            if node.image.name in copies:
                node.image = copies[node.image.name]
        for principled in [n for n in tree.nodes if n.type == "BSDF_PRINCIPLED"]:
            diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
            diffuse.inputs["Roughness"].default_value = 0.0
            base_colour = principled.inputs["Base Color"]
            if base_colour.is_linked:
                tree.links.new(base_colour.links[0].from_socket, diffuse.inputs["Color"])
            else:
                diffuse.inputs["Color"].default_value = base_colour.default_value
            surface = diffuse.outputs["BSDF"]
            cutout = alpha_cutout_socket(material, principled)
            if cutout is not None:
                surface = cut_out(tree, diffuse, cutout, material.alpha_threshold)
            for link in list(principled.outputs["BSDF"].links):
                tree.links.new(surface, link.to_socket)
            tree.nodes.remove(principled)


def alpha_cutout_socket(material, principled):
    """The socket holding an alpha-masked (glTF alphaMode MASK) material's alpha, or None. Blender's glTF
    importer feeds it to the Principled BSDF's Alpha and marks the material blend_method CLIP with the cutoff as
    alpha_threshold; Cycles ignores both and reads Alpha as partial transparency, and replacing the Principled
    node dropped it: the house's cut-out vine and tree cards were opaque quads in Cycles where gusuku's tracer
    lets rays through their holes (bvh_alpha_mask.glsl)."""
    if material.blend_method != "CLIP":
        return None
    alpha = principled.inputs["Alpha"]
    return alpha.links[0].from_socket if alpha.is_linked else None


def cut_out(tree, diffuse, alpha_socket, cutoff):
    """Diffuse where alpha >= cutoff, a hole (Transparent BSDF) elsewhere, as gusuku's alpha test decides."""
    below = tree.nodes.new("ShaderNodeMath")
    below.operation = "LESS_THAN"
    tree.links.new(alpha_socket, below.inputs[0])
    below.inputs[1].default_value = cutoff
    hole = tree.nodes.new("ShaderNodeBsdfTransparent")
    mix = tree.nodes.new("ShaderNodeMixShader")
    tree.links.new(below.outputs["Value"], mix.inputs["Fac"])
    tree.links.new(diffuse.outputs["BSDF"], mix.inputs[1])
    tree.links.new(hole.outputs["BSDF"], mix.inputs[2])
    return mix.outputs["Shader"]
