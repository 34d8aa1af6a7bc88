// Colour maths for shaders: the GLSL twin of engine/include/gusuku/maths/colour.h (float only), with the same
// function names, constants and formulas; read the contracts there. tests/test_colour.cpp holds every function
// here to its C++ twin through shaders/tests/colour_probe.comp. Change both files together.
//
// Linear Rec.709 RGB (sRGB primaries, D65) <-> CIE XYZ (Y = relative luminance) <-> CIE L*a*b* with white
// (0.95047, 1, 1.08883), epsilon 216/24389, kappa 24389/27 (docs/design.md 2); the sRGB curve of IEC 61966-2-1;
// CIEDE2000 (Sharma, Wu and Dalal 2005); Reinhard's transfer of Lab statistics (docs/design.md 4).
// No bindings, no extensions; includes only constants.glsl.
#ifndef GUSUKU_COLOUR_GLSL
#define GUSUKU_COLOUR_GLSL

#include "constants.glsl"

const vec3 kD65WhiteXyz = vec3(0.95047, 1.0, 1.08883);
const float kLabEpsilon = 216.0 / 24389.0;
const float kLabKappa = 24389.0 / 27.0;

// ---- sRGB transfer curve, per channel (no clamping) ----

float srgbEncode(float linear) {
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
}

// The expression the baker's texture fetch has always used (scene_shading.glsl): keep it, bakes depend on it.
float srgbDecode(float encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : pow((encoded + 0.055) / 1.055, 2.4);
}

vec3 srgbEncode(vec3 linear_rgb) {
    return vec3(srgbEncode(linear_rgb.r), srgbEncode(linear_rgb.g), srgbEncode(linear_rgb.b));
}

vec3 srgbDecode(vec3 encoded_rgb) {
    return vec3(srgbDecode(encoded_rgb.r), srgbDecode(encoded_rgb.g), srgbDecode(encoded_rgb.b));
}

// ---- Luminance: Y = 0.2126 R + 0.7152 G + 0.0722 B, left to right as in colour.h ----

float luminanceRec709(vec3 rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; }

// ---- Linear Rec.709 <-> XYZ <-> Lab ----

// colour.cpp says where the digits come from (7-digit forward matrix, its exact inverse).
vec3 xyzFromLinearRec709(vec3 rgb) {
    return vec3(0.4124564 * rgb.r + 0.3575761 * rgb.g + 0.1804375 * rgb.b,
                0.2126729 * rgb.r + 0.7151522 * rgb.g + 0.0721750 * rgb.b,
                0.0193339 * rgb.r + 0.1191920 * rgb.g + 0.9503041 * rgb.b);
}

vec3 linearRec709FromXyz(vec3 xyz) {
    return vec3(3.2404548360214085 * xyz.x - 1.5371388501025751 * xyz.y - 0.4985315468684809 * xyz.z,
                -0.9692663898756538 * xyz.x + 1.8760109288424912 * xyz.y + 0.0415560823466735 * xyz.z,
                0.0556434196042137 * xyz.x - 0.2040258542676981 * xyz.y + 1.0572251624579288 * xyz.z);
}

// GLSL has no cbrt; pow is defined here because relative > epsilon > 0.
float labForward(float relative) {
    return relative > kLabEpsilon ? pow(relative, 1.0 / 3.0) : (kLabKappa * relative + 16.0) / 116.0;
}

float labInverse(float f) {
    float cube = f * f * f;
    return cube > kLabEpsilon ? cube : (116.0 * f - 16.0) / kLabKappa;
}

vec3 labFromXyz(vec3 xyz) {
    float fx = labForward(xyz.x / kD65WhiteXyz.x);
    float fy = labForward(xyz.y / kD65WhiteXyz.y);
    float fz = labForward(xyz.z / kD65WhiteXyz.z);
    return vec3(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz));
}

vec3 xyzFromLab(vec3 lab) {
    float fy = (lab.x + 16.0) / 116.0;
    float fx = fy + lab.y / 500.0;
    float fz = fy - lab.z / 200.0;
    float yr = lab.x > 8.0 ? fy * fy * fy : lab.x / kLabKappa;  // kappa * epsilon = 8
    return vec3(labInverse(fx) * kD65WhiteXyz.x, yr * kD65WhiteXyz.y, labInverse(fz) * kD65WhiteXyz.z);
}

vec3 labFromLinearRec709(vec3 rgb) { return labFromXyz(xyzFromLinearRec709(rgb)); }
vec3 linearRec709FromLab(vec3 lab) { return linearRec709FromXyz(xyzFromLab(lab)); }

// ---- CIEDE2000, kL = kC = kH = 1; radians; the steps of colour_difference.cpp ----

float colourSeventhPower(float x) {
    float x2 = x * x;
    return x2 * x2 * x2 * x;
}

float colourHueAngle(float b, float a_prime) {
    if (b == 0.0 && a_prime == 0.0) return 0.0;  // GLSL's atan(0, 0) is undefined; the formula says 0
    float h = atan(b, a_prime);
    return h < 0.0 ? h + 2.0 * kPi : h;
}

float ciede2000(vec3 lab1, vec3 lab2) {
    const float two_pi = 2.0 * kPi;
    const float pow25_7 = 6103515625.0;
    float c1 = sqrt(lab1.y * lab1.y + lab1.z * lab1.z);
    float c2 = sqrt(lab2.y * lab2.y + lab2.z * lab2.z);
    float c_mean7 = colourSeventhPower((c1 + c2) / 2.0);
    float g = 0.5 * (1.0 - sqrt(c_mean7 / (c_mean7 + pow25_7)));
    float a1p = (1.0 + g) * lab1.y;
    float a2p = (1.0 + g) * lab2.y;
    float c1p = sqrt(a1p * a1p + lab1.z * lab1.z);
    float c2p = sqrt(a2p * a2p + lab2.z * lab2.z);
    float h1p = colourHueAngle(lab1.z, a1p);
    float h2p = colourHueAngle(lab2.z, a2p);

    float delta_lp = lab2.x - lab1.x;
    float delta_cp = c2p - c1p;
    float chroma_product = c1p * c2p;
    float delta_hp = 0.0;
    if (chroma_product != 0.0) {
        delta_hp = h2p - h1p;
        if (delta_hp > kPi) delta_hp -= two_pi;
        else if (delta_hp < -kPi) delta_hp += two_pi;
    }
    float delta_big_hp = 2.0 * sqrt(chroma_product) * sin(delta_hp / 2.0);

    float l_mean = (lab1.x + lab2.x) / 2.0;
    float cp_mean = (c1p + c2p) / 2.0;
    float hp_mean = h1p + h2p;
    if (chroma_product != 0.0) {
        if (abs(h1p - h2p) <= kPi) hp_mean /= 2.0;
        else if (hp_mean < two_pi) hp_mean = (hp_mean + two_pi) / 2.0;
        else hp_mean = (hp_mean - two_pi) / 2.0;
    }
    float t = 1.0 - 0.17 * cos(hp_mean - radians(30.0)) + 0.24 * cos(2.0 * hp_mean) +
              0.32 * cos(3.0 * hp_mean + radians(6.0)) - 0.20 * cos(4.0 * hp_mean - radians(63.0));
    float hue_from_275 = (hp_mean - radians(275.0)) / radians(25.0);
    float delta_theta = radians(30.0) * exp(-hue_from_275 * hue_from_275);
    float cp_mean7 = colourSeventhPower(cp_mean);
    float r_c = 2.0 * sqrt(cp_mean7 / (cp_mean7 + pow25_7));
    float l_from_50_sq = (l_mean - 50.0) * (l_mean - 50.0);
    float s_l = 1.0 + 0.015 * l_from_50_sq / sqrt(20.0 + l_from_50_sq);
    float s_c = 1.0 + 0.045 * cp_mean;
    float s_h = 1.0 + 0.015 * cp_mean * t;
    float r_t = -sin(2.0 * delta_theta) * r_c;

    float lightness = delta_lp / s_l;
    float chroma = delta_cp / s_c;
    float hue = delta_big_hp / s_h;
    return sqrt(lightness * lightness + chroma * chroma + hue * hue + r_t * chroma * hue);
}

// ---- Reinhard transfer of Lab statistics (docs/design.md 4) ----
// gain = clamp(sigma_tgt / max(sigma_src, kLabTransferMinSourceSigma), 1 / max_gain, max_gain), max_gain below
// 1 taken as 1; then y = (x - mu_src) * gain + mu_tgt. colour.h documents why the floor and the clamp.

const float kLabTransferMinSourceSigma = 0.01;
const float kLabTransferDefaultMaxGain = 4.0;

vec3 labTransferGain(vec3 source_sigma, vec3 target_sigma, float max_gain) {
    float upper = max_gain >= 1.0 ? max_gain : 1.0;
    float lower = 1.0 / upper;
    return clamp(target_sigma / max(source_sigma, vec3(kLabTransferMinSourceSigma)), vec3(lower), vec3(upper));
}

vec3 applyLabTransfer(vec3 lab, vec3 source_mean, vec3 gain, vec3 target_mean) {
    return (lab - source_mean) * gain + target_mean;
}

#endif  // GUSUKU_COLOUR_GLSL
