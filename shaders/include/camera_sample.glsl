// The camera's pixel, sRGB-encoded RGBA in [0, 1], whatever its format (camera_interface.h): the one place that
// reads the camera, for the camera-in draw and the statistics' packing kernel alike, so they cannot disagree.
// Y'CbCr to R'G'B' by the ITU matrices (BT.601: Kr 0.299, Kb 0.114; BT.709: Kr 0.2126, Kb 0.0722), narrow range
// Y' in [16, 235] and Cb, Cr in [16, 240] (both over 255), or full range; the chroma of pixel (x, y) is the
// chroma sample (x / 2, y / 2) (nearest: 4:2:0 with midpoint siting), and R'G'B' is taken as sRGB-encoded, as
// phone cameras deliver it. Needs camera_interface.h, colour.glsl and a CameraPushConstants block `camera_push`.
#ifndef GUSUKU_CAMERA_SAMPLE_GLSL
#define GUSUKU_CAMERA_SAMPLE_GLSL

layout(constant_id = CAMERA_KIND_CONSTANT) const uint camera_kind = CAMERA_KIND_FOUR_BYTE;
layout(constant_id = CAMERA_MATRIX_CONSTANT) const uint camera_matrix = 0u;
layout(constant_id = CAMERA_FULL_RANGE_CONSTANT) const uint camera_full_range = 0u;
layout(constant_id = CAMERA_CHROMA_SWAP_CONSTANT) const uint camera_chroma_swap = 0u;

vec3 rgbFromYcbcr(float luma, vec2 chroma) {
    float y, cb, cr;
    if (camera_full_range != 0u) {
        y = luma;
        cb = chroma.x - 128.0 / 255.0;
        cr = chroma.y - 128.0 / 255.0;
    } else {
        y = (luma * 255.0 - 16.0) / 219.0;
        cb = (chroma.x * 255.0 - 128.0) / 224.0;
        cr = (chroma.y * 255.0 - 128.0) / 224.0;
    }
    const float kr = camera_matrix == 1u ? 0.2126 : 0.299;
    const float kb = camera_matrix == 1u ? 0.0722 : 0.114;
    const float r = y + 2.0 * (1.0 - kr) * cr;
    const float b = y + 2.0 * (1.0 - kb) * cb;
    const float g = (y - kr * r - kb * b) / (1.0 - kr - kb);
    return clamp(vec3(r, g, b), 0.0, 1.0);
}

vec4 cameraYcbcrPixel(ivec2 pixel) {
    const float luma = texelFetch(camera_plane0, pixel, 0).r;
    const vec2 stored = texelFetch(camera_plane1, pixel / 2, 0).rg;
    return vec4(rgbFromYcbcr(luma, camera_chroma_swap != 0u ? stored.yx : stored.xy), 1.0);
}

// sRGB-encoded, as the statistics read the camera.
vec4 cameraSrgbPixel(ivec2 pixel) {
    if (camera_kind == CAMERA_KIND_TWO_PLANE_YUV) return cameraYcbcrPixel(pixel);
    vec4 texel = texelFetch(camera_plane0, pixel, 0);
    if (camera_push.view_decodes_srgb != 0u) texel.rgb = srgbEncode(texel.rgb);
    return texel;
}

// Linear, as the composite's sRGB attachment takes it. An _SRGB view decodes in the sampler: no pow here, which
// on llvmpipe is most of the camera-in draw's cost.
vec4 cameraLinearPixel(ivec2 pixel) {
    if (camera_kind == CAMERA_KIND_TWO_PLANE_YUV) {
        const vec4 encoded = cameraYcbcrPixel(pixel);
        return vec4(srgbDecode(encoded.rgb), encoded.a);
    }
    vec4 texel = texelFetch(camera_plane0, pixel, 0);
    if (camera_push.view_decodes_srgb == 0u) texel.rgb = srgbDecode(texel.rgb);
    return texel;
}

#endif
