// The camera's pixel, sRGB-encoded RGBA in [0, 1], whatever its format (camera_interface.h): the one place that
// reads the camera, for the camera-in draw and the statistics' packing kernel alike, so they cannot disagree.
// Y'CbCr to R'G'B' by the ITU matrices (BT.601: Kr 0.299, Kb 0.114; BT.709: Kr 0.2126, Kb 0.0722), narrow range
// Y' in [16, 235] and Cb, Cr in [16, 240] (both over 255), or full range; the chroma of pixel (x, y) is the
// chroma sample (x / 2, y / 2) (nearest: 4:2:0 with midpoint siting), and R'G'B' is taken as sRGB-encoded, as
// phone cameras deliver it. Needs camera_interface.h, colour.glsl and a CameraPushConstants block `camera_push`.
// With CAMERA_SAMPLER_YCBCR (the zero-copy camera), a sampler Y'CbCr conversion does the decoding instead.
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

#ifdef CAMERA_SAMPLER_YCBCR
layout(constant_id = CAMERA_YCBCR_LINEAR_CONSTANT) const uint camera_ycbcr_linear = 0u;
layout(constant_id = CAMERA_FRAME_HEIGHT_CONSTANT) const uint camera_frame_height = 1u;

// The sampler's conversion does the matrix, the range and the chroma reconstruction and returns R'G'B'. A sampler
// with a conversion may only be read by OpImageSample* (no texelFetch), at normalised coordinates. Nearest samples
// a quarter pixel in from the top-left corner: there the luma is the pixel's and the nearest chroma sample is the
// 2 x 2 block's own under midpoint and cosited-even siting alike (at the centre, cosited-even puts odd pixels on
// the edge between two chroma samples), so it gives the host planes' rule; linear samples the centre.
vec4 cameraYcbcrPixel(ivec2 pixel) {
    const vec2 inside = camera_ycbcr_linear != 0u ? vec2(0.5) : vec2(0.25);
    const vec2 size = vec2(float(camera_push.frame_width), float(camera_frame_height));
    const vec3 rgb = textureLod(camera_plane0, (vec2(pixel) + inside) / size, 0.0).rgb;
    return vec4(clamp(rgb, 0.0, 1.0), 1.0);
}
#else
vec4 cameraYcbcrPixel(ivec2 pixel) {
    const float luma = texelFetch(camera_plane0, pixel, 0).r;
    const vec2 stored = texelFetch(camera_plane1, pixel / 2, 0).rg;
    return vec4(rgbFromYcbcr(luma, camera_chroma_swap != 0u ? stored.yx : stored.xy), 1.0);
}
#endif

// sRGB-encoded, as the statistics read the camera.
vec4 cameraSrgbPixel(ivec2 pixel) {
#ifdef CAMERA_SAMPLER_YCBCR
    return cameraYcbcrPixel(pixel);  // no texelFetch of a sampler with a conversion, not even in a dead branch
#else
    if (camera_kind == CAMERA_KIND_TWO_PLANE_YUV) return cameraYcbcrPixel(pixel);
    vec4 texel = texelFetch(camera_plane0, pixel, 0);
    if (camera_push.view_decodes_srgb != 0u) texel.rgb = srgbEncode(texel.rgb);
    return texel;
#endif
}

// Linear, as the composite's sRGB attachment takes it. An _SRGB view decodes in the sampler: no pow here, which
// on llvmpipe is most of the camera-in draw's cost.
vec4 cameraLinearPixel(ivec2 pixel) {
#ifdef CAMERA_SAMPLER_YCBCR
    const vec4 converted = cameraYcbcrPixel(pixel);
    return vec4(srgbDecode(converted.rgb), converted.a);
#else
    if (camera_kind == CAMERA_KIND_TWO_PLANE_YUV) {
        const vec4 encoded = cameraYcbcrPixel(pixel);
        return vec4(srgbDecode(encoded.rgb), encoded.a);
    }
    vec4 texel = texelFetch(camera_plane0, pixel, 0);
    if (camera_push.view_decodes_srgb == 0u) texel.rgb = srgbDecode(texel.rgb);
    return texel;
#endif
}

#endif
