// Surface attributes at a ray hit: interpolated normal, base colour (factor times texture) and emission.
// The includer #defines SHADING_TRIANGLE_BINDING, MATERIAL_BINDING and TEXTURE_BINDING first, set 0 uniform
// texel buffers: views of format VK_FORMAT_R32G32B32A32_UINT on the first two and VK_FORMAT_R32_UINT on the
// textures. Layouts match baker/include/gusuku_bake/trace_scene.h (TriangleShadingGpu, MaterialGpu), one
// 16-byte texel per vec4 member. Textures are packed RGBA8 sRGB words in one buffer because lavapipe has no
// descriptor indexing (docs/design.md 5). Why texel buffers: as for the BVH (bvh_layout.glsl), lavapipe gathers a
// texel fetch's lanes in vector code where a storage-buffer load at per-lane addresses loops over the lanes.
#ifndef GUSUKU_SCENE_SHADING_GLSL
#define GUSUKU_SCENE_SHADING_GLSL

#include "colour.glsl"

struct TriangleShadingGpu {
    vec4 normal0_u0;        // vertex 0 normal, xyz; w: vertex 0 uv0.x
    vec4 normal1_v0;        // vertex 1 normal; w: vertex 0 uv0.y
    vec4 normal2_material;  // vertex 2 normal; w: material index (float bits)
    vec4 uv0_vertex1_vertex2;
    vec4 geometric_normal;  // unit face normal of the counter-clockwise winding; w 1 on a closed part's face
};

struct MaterialGpu {
    vec4 base_color_factor;  // linear RGBA
    vec4 emission;           // linear emitted radiance, xyz; w: the alpha cutoff of a masked material (else 0)
    uvec4 texture_info;      // x: first word in the texture buffer, y: width, z: height (0: no texture),
                             // w: bit 0 double-sided
};

#ifdef TRACE_INPUTS_STORAGE_BUFFERS
// The storage-buffer variant (bvh_layout.glsl): the same words, the same bits.
layout(std430, set = 0, binding = SHADING_TRIANGLE_BINDING) readonly buffer TriangleShadingWords {
    uvec4 triangle_shading_words[];
};
layout(std430, set = 0, binding = MATERIAL_BINDING) readonly buffer MaterialWords { uvec4 material_words[]; };
layout(std430, set = 0, binding = TEXTURE_BINDING) readonly buffer TextureWords { uint texture_words[]; };
uvec4 triangleShadingWord(int index) { return triangle_shading_words[index]; }
uvec4 materialWord(int index) { return material_words[index]; }
uint textureWord(int index) { return texture_words[index]; }
#else
layout(set = 0, binding = SHADING_TRIANGLE_BINDING) uniform usamplerBuffer triangle_shading_texels;
layout(set = 0, binding = MATERIAL_BINDING) uniform usamplerBuffer material_texels;
layout(set = 0, binding = TEXTURE_BINDING) uniform usamplerBuffer texture_word_texels;
#define triangleShadingWord(index) texelFetch(triangle_shading_texels, index)
#define materialWord(index) texelFetch(material_texels, index)
#define textureWord(index) texelFetch(texture_word_texels, index).x
#endif

const uint kTriangleShadingTexels = 5u;  // vec4s in TriangleShadingGpu
const uint kMaterialTexels = 3u;         // vec4s in MaterialGpu

TriangleShadingGpu loadTriangleShading(uint triangle_index) {
    int first = int(triangle_index * kTriangleShadingTexels);
    TriangleShadingGpu shading;
    shading.normal0_u0 = uintBitsToFloat(triangleShadingWord(first));
    shading.normal1_v0 = uintBitsToFloat(triangleShadingWord(first + 1));
    shading.normal2_material = uintBitsToFloat(triangleShadingWord(first + 2));
    shading.uv0_vertex1_vertex2 = uintBitsToFloat(triangleShadingWord(first + 3));
    shading.geometric_normal = uintBitsToFloat(triangleShadingWord(first + 4));
    return shading;
}

MaterialGpu loadMaterial(uint material_index) {
    int first = int(material_index * kMaterialTexels);
    MaterialGpu material;
    material.base_color_factor = uintBitsToFloat(materialWord(first));
    material.emission = uintBitsToFloat(materialWord(first + 1));
    material.texture_info = materialWord(first + 2);
    return material;
}

vec3 fetchTexel(uvec4 info, int x, int y) {
    uint word = textureWord(int(info.x + uint(y) * info.y + uint(x)));
    vec3 encoded = vec3(float(word & 255u), float((word >> 8u) & 255u), float((word >> 16u) & 255u)) / 255.0;
    return srgbDecode(encoded);
}

// The four texels and the weights of a bilinear lookup with repeat wrapping (glTF's default sampler), shared by
// the colour and the alpha lookups so that an alpha-masked texel's hole lines up with its colour.
struct BilinearTaps {
    int x0, y0, x1, y1;
    vec2 weight;
};

BilinearTaps bilinearRepeatTaps(uvec4 info, vec2 uv) {
    vec2 texel_coordinate = uv * vec2(info.yz) - 0.5;
    vec2 base = floor(texel_coordinate);
    int w = int(info.y), h = int(info.z);
    BilinearTaps taps;
    taps.weight = texel_coordinate - base;
    taps.x0 = int(mod(base.x, float(w)));
    taps.y0 = int(mod(base.y, float(h)));
    taps.x1 = (taps.x0 + 1) % w;
    taps.y1 = (taps.y0 + 1) % h;
    return taps;
}

vec3 sampleBaseColorTexture(uvec4 info, vec2 uv) {
    BilinearTaps t = bilinearRepeatTaps(info, uv);
    vec3 top = mix(fetchTexel(info, t.x0, t.y0), fetchTexel(info, t.x1, t.y0), t.weight.x);
    vec3 bottom = mix(fetchTexel(info, t.x0, t.y1), fetchTexel(info, t.x1, t.y1), t.weight.x);
    return mix(top, bottom, t.weight.y);
}

// The texture's alpha (stored linear in the word's top byte), bilinear with repeat wrapping as the colour.
float fetchTexelAlpha(uvec4 info, int x, int y) {
    return float(textureWord(int(info.x + uint(y) * info.y + uint(x))) >> 24u) / 255.0;
}

float sampleBaseColorAlpha(uvec4 info, vec2 uv) {
    BilinearTaps t = bilinearRepeatTaps(info, uv);
    float top = mix(fetchTexelAlpha(info, t.x0, t.y0), fetchTexelAlpha(info, t.x1, t.y0), t.weight.x);
    float bottom = mix(fetchTexelAlpha(info, t.x0, t.y1), fetchTexelAlpha(info, t.x1, t.y1), t.weight.x);
    return mix(top, bottom, t.weight.y);
}

// Below this base-colour alpha a masked material is a hole (bvh_alpha_mask.glsl).
float materialAlphaCutoff(MaterialGpu material) { return material.emission.w; }

struct SurfacePoint {
    vec3 shading_normal;    // interpolated, flipped to the side the ray came from
    vec3 geometric_normal;  // flipped to the side the ray came from
    vec3 albedo;            // diffuse reflectance, linear, clamped below 1 so no bounce gains energy
    vec3 emission;
    bool front_face;        // the ray hit the counter-clockwise side
    bool double_sided;
    bool closed_part;       // a face of a closed, outward-wound part (baker/include/gusuku_bake/closed_parts.h)
};

SurfacePoint evaluateSurface(uint triangle_index, float barycentric_u, float barycentric_v, vec3 ray_direction) {
    TriangleShadingGpu shading = loadTriangleShading(triangle_index);
    float w0 = 1.0 - barycentric_u - barycentric_v;
    SurfacePoint surface;
    vec3 geometric = shading.geometric_normal.xyz;
    surface.front_face = dot(geometric, ray_direction) < 0.0;
    surface.closed_part = shading.geometric_normal.w > 0.5;
    float side = surface.front_face ? 1.0 : -1.0;
    surface.geometric_normal = geometric * side;
    vec3 interpolated = w0 * shading.normal0_u0.xyz + barycentric_u * shading.normal1_v0.xyz +
                        barycentric_v * shading.normal2_material.xyz;
    float interpolated_length = length(interpolated);
    surface.shading_normal = interpolated_length > 1e-6 ? interpolated * (side / interpolated_length)
                                                        : surface.geometric_normal;
    // A shading normal bent below the surface would send light through it: fall back to the face normal.
    if (dot(surface.shading_normal, surface.geometric_normal) <= 0.0) surface.shading_normal = surface.geometric_normal;

    MaterialGpu material = loadMaterial(floatBitsToUint(shading.normal2_material.w));
    vec3 albedo = material.base_color_factor.rgb;
    if (material.texture_info.z > 0u) {
        vec2 uv0 = vec2(shading.normal0_u0.w, shading.normal1_v0.w);
        vec2 uv = w0 * uv0 + barycentric_u * shading.uv0_vertex1_vertex2.xy +
                  barycentric_v * shading.uv0_vertex1_vertex2.zw;
        albedo *= sampleBaseColorTexture(material.texture_info, uv);
    }
    surface.albedo = clamp(albedo, vec3(0.0), vec3(0.98));
    surface.emission = material.emission.xyz;
    surface.double_sided = (material.texture_info.w & 1u) != 0u;
    return surface;
}

#endif
