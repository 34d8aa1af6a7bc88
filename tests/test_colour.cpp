// The colour module (gusuku/maths/colour.h) against independent answers: the sRGB standard's own numbers, the Lab
// definition's closed forms, published Lab values of the sRGB primaries, the 34 CIEDE2000 pairs published by
// Sharma, Wu and Dalal (2005) with their dE00, and docs/design.md 4's pinned transfer example. Then its GLSL twin
// (shaders/include/colour.glsl, run by shaders/tests/colour_probe.comp on the device) against the C++ for a
// 17^3 grid of linear colours plus HDR values.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <gtest/gtest.h>

#include "colour_probe_comp_spv.h"
#include "gpu_test_support.h"
#include "gusuku/maths/colour.h"
#include "gusuku/gpu/gpu_compute.h"

namespace gusuku {
namespace {

using glm::dvec3;
using glm::vec3;

void expectNear(const dvec3& actual, const dvec3& expected, double tolerance, const char* what) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(actual[c], expected[c], tolerance) << what << ", channel " << c;
}

// ---- sRGB curve and luminance ------------------------------------------------------------------------------

TEST(ColourSrgb, MatchesTheStandardsNumbers) {
    // IEC 61966-2-1: the two segments meet at linear 0.0031308 / encoded 0.04045; 0.5 <-> 0.735357 and
    // 0.5 encoded <-> 0.214041 follow from the formulas (independently evaluated to 6 digits).
    EXPECT_NEAR(srgbEncode(0.5), 0.735357, 1e-6);
    EXPECT_NEAR(srgbDecode(0.5), 0.214041, 1e-6);
    EXPECT_NEAR(srgbEncode(0.0031308), 0.04045, 1e-7);
    EXPECT_NEAR(srgbDecode(0.04045), 0.0031308, 1e-8);
    EXPECT_EQ(srgbEncode(0.0), 0.0);
    EXPECT_NEAR(srgbEncode(1.0), 1.0, 1e-15);
    EXPECT_NEAR(srgbDecode(1.0), 1.0, 1e-15);
    EXPECT_NEAR(srgbEncode(0.001), 0.01292, 1e-12);  // linear segment
    // HDR follows the power segment: 1.055 * 4^(1/2.4) - 0.055.
    EXPECT_NEAR(srgbEncode(4.0), 1.055 * std::pow(4.0, 1.0 / 2.4) - 0.055, 1e-12);
    // Float and double overloads and the per-channel form agree.
    EXPECT_NEAR(srgbEncode(0.5f), 0.735357f, 1e-6f);
    const vec3 encoded = srgbEncode(vec3(0.5f, 0.001f, 4.0f));
    EXPECT_EQ(encoded.x, srgbEncode(0.5f));
    EXPECT_EQ(encoded.y, srgbEncode(0.001f));
    EXPECT_EQ(encoded.z, srgbEncode(4.0f));
}

TEST(ColourSrgb, RoundTripsOverTheRangeAndBeyond) {
    for (int i = 0; i <= 2000; ++i) {
        const double linear = 8.0 * i / 2000.0;  // 0 .. 8, HDR included
        EXPECT_NEAR(srgbDecode(srgbEncode(linear)), linear, 1e-12 * std::max(1.0, linear)) << linear;
        const float linear_f = float(linear);
        EXPECT_NEAR(srgbDecode(srgbEncode(linear_f)), linear_f, 4e-7f * std::max(1.0f, linear_f)) << linear;
    }
    const vec3 rgb(0.0f, 0.2f, 1.0f);
    const vec3 back = srgbDecode(srgbEncode(rgb));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], rgb[c], 2e-7f);
}

TEST(ColourLuminance, HasTheRec709Weights) {
    EXPECT_EQ(luminanceRec709(vec3(1, 0, 0)), 0.2126f);
    EXPECT_EQ(luminanceRec709(vec3(0, 1, 0)), 0.7152f);
    EXPECT_EQ(luminanceRec709(vec3(0, 0, 1)), 0.0722f);
    EXPECT_NEAR(luminanceRec709(dvec3(1.0)), 1.0, 1e-15);
    EXPECT_NEAR(luminanceRec709(dvec3(2.0, 3.0, 4.0)), 0.4252 + 2.1456 + 0.2888, 1e-14);
    // The XYZ matrix's Y row, derived from the primaries, rounds to the same weights.
    for (const dvec3 primary : {dvec3(1, 0, 0), dvec3(0, 1, 0), dvec3(0, 0, 1)})
        EXPECT_NEAR(xyzFromLinearRec709(primary).y, luminanceRec709(primary), 1e-4);
}

// ---- XYZ and Lab ------------------------------------------------------------------------------------------

TEST(ColourLab, WhiteGreysAndBlackFollowTheDefinition) {
    // Linear white -> the D65 white point -> L 100, a = b = 0 (to the 7 digits of the matrix: 2e-7 in XYZ,
    // 1.7e-5 in Lab).
    expectNear(xyzFromLinearRec709(dvec3(1.0)), kD65WhiteXyz, 2e-7, "white XYZ");
    expectNear(labFromLinearRec709(dvec3(1.0)), dvec3(100, 0, 0), 3e-5, "white Lab (double)");
    expectNear(dvec3(labFromLinearRec709(vec3(1.0f))), dvec3(100, 0, 0), 1e-3, "white Lab (float)");
    expectNear(labFromLinearRec709(dvec3(0.0)), dvec3(0.0), 1e-12, "black Lab");
    // Greys: L = 116 Y^(1/3) - 16 above epsilon, kappa Y below; a = b = 0.
    for (const double y : {0.18, 0.5, 0.01, 2.0}) {
        const double expected_l = 116.0 * std::cbrt(y) - 16.0;
        expectNear(labFromLinearRec709(dvec3(y)), dvec3(expected_l, 0, 0), 3e-5 * std::cbrt(y), "grey");
    }
    expectNear(labFromLinearRec709(dvec3(0.001)), dvec3(24389.0 / 27.0 * 0.001, 0, 0), 1e-6, "dark grey");
    // The two segments meet at Y = epsilon: L = kappa epsilon = 8 either way.
    const double eps = 216.0 / 24389.0;
    EXPECT_NEAR(labFromXyz(kD65WhiteXyz * (eps * (1 + 1e-12))).x, 8.0, 1e-9);
    EXPECT_NEAR(labFromXyz(kD65WhiteXyz * (eps * (1 - 1e-12))).x, 8.0, 1e-9);
}

TEST(ColourLab, PrimariesHaveTheirPublishedLabValues) {
    // sRGB primaries in CIELAB (D65), as commonly tabulated to 2 decimals (e.g. Lindbloom's calculator).
    struct Pinned {
        dvec3 rgb, lab;
    };
    const Pinned pinned[] = {{{1, 0, 0}, {53.24, 80.09, 67.20}},
                             {{0, 1, 0}, {87.73, -86.18, 83.18}},
                             {{0, 0, 1}, {32.30, 79.19, -107.86}},
                             {{1, 1, 0}, {97.14, -21.55, 94.48}}};
    for (const Pinned& p : pinned) {
        expectNear(labFromLinearRec709(p.rgb), p.lab, 0.006, "primary (double)");
        expectNear(dvec3(labFromLinearRec709(vec3(p.rgb))), p.lab, 0.006, "primary (float)");
    }
}

TEST(ColourLab, RoundTripsIncludingHdrAndOutOfGamut) {
    std::mt19937 rng(2005);
    std::uniform_real_distribution<double> channel(-0.2, 8.0);
    for (int i = 0; i < 2000; ++i) {
        const dvec3 rgb(channel(rng), channel(rng), channel(rng));
        const dvec3 back = linearRec709FromLab(labFromLinearRec709(rgb));
        expectNear(back, rgb, 1e-11, "double RGB -> Lab -> RGB");
        const vec3 rgb_f(rgb);
        const vec3 back_f = linearRec709FromLab(labFromLinearRec709(rgb_f));
        expectNear(dvec3(back_f), dvec3(rgb_f), 4e-6 * std::max({1.0, rgb.x, rgb.y, rgb.z}), "float round trip");
        const dvec3 lab = labFromLinearRec709(rgb);
        expectNear(labFromXyz(xyzFromLab(lab)), lab, 1e-9, "double Lab -> XYZ -> Lab");
    }
}

// ---- CIEDE2000 --------------------------------------------------------------------------------------------

struct Ciede2000Pair {
    dvec3 lab1, lab2;
    double delta_e;
};

// Sharma, Wu and Dalal (2005), Table 1: all 34 pairs and their published dE00 (4 decimals).
constexpr std::array<Ciede2000Pair, 34> kSharmaPairs = {{
    {{50.0000, 2.6772, -79.7751}, {50.0000, 0.0000, -82.7485}, 2.0425},
    {{50.0000, 3.1571, -77.2803}, {50.0000, 0.0000, -82.7485}, 2.8615},
    {{50.0000, 2.8361, -74.0200}, {50.0000, 0.0000, -82.7485}, 3.4412},
    {{50.0000, -1.3802, -84.2814}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, -1.1848, -84.8006}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, -0.9009, -85.5211}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, 0.0000, 0.0000}, {50.0000, -1.0000, 2.0000}, 2.3669},
    {{50.0000, -1.0000, 2.0000}, {50.0000, 0.0000, 0.0000}, 2.3669},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0009}, 7.1792},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0010}, 7.1792},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0011}, 7.2195},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0012}, 7.2195},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0009, -2.4900}, 4.8045},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0010, -2.4900}, 4.8045},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0011, -2.4900}, 4.7461},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 0.0000, -2.5000}, 4.3065},
    {{50.0000, 2.5000, 0.0000}, {73.0000, 25.0000, -18.0000}, 27.1492},
    {{50.0000, 2.5000, 0.0000}, {61.0000, -5.0000, 29.0000}, 22.8977},
    {{50.0000, 2.5000, 0.0000}, {56.0000, -27.0000, -3.0000}, 31.9030},
    {{50.0000, 2.5000, 0.0000}, {58.0000, 24.0000, 15.0000}, 19.4535},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.1736, 0.5854}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.2972, 0.0000}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 1.8634, 0.5757}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.2592, 0.3350}, 1.0000},
    {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644},
    {{63.0109, -31.0961, -5.8663}, {62.8187, -29.7946, -4.0864}, 1.2630},
    {{61.2901, 3.7196, -5.3901}, {61.4292, 2.2480, -4.9620}, 1.8731},
    {{35.0831, -44.1164, 3.7933}, {35.0232, -40.0716, 1.5901}, 1.8645},
    {{22.7233, 20.0904, -46.6940}, {23.0331, 14.9730, -42.5619}, 2.0373},
    {{36.4612, 47.8580, 18.3852}, {36.2715, 50.5065, 21.2231}, 1.4146},
    {{90.8027, -2.0831, 1.4410}, {91.1528, -1.6435, 0.0447}, 1.4441},
    {{90.9257, -0.5406, -0.9208}, {88.6381, -0.8985, -0.7239}, 1.5381},
    {{6.7747, -0.2908, -2.4247}, {5.8714, -0.0985, -2.2286}, 0.6377},
    {{2.0776, 0.0795, -1.1350}, {0.9033, -0.0636, -0.5514}, 0.9082},
}};

TEST(ColourCiede2000, MatchesTheThirtyFourPublishedPairs) {
    for (size_t i = 0; i < kSharmaPairs.size(); ++i) {
        const Ciede2000Pair& pair = kSharmaPairs[i];
        // Published to 4 decimals: within half a unit of the last place, plus the double's rounding.
        EXPECT_NEAR(ciede2000(pair.lab1, pair.lab2), pair.delta_e, 0.5e-4 + 1e-9) << "pair " << i + 1;
    }
}

TEST(ColourCiede2000, IsZeroForEqualColoursAndSymmetricOffTheHueBoundary) {
    for (size_t i = 0; i < kSharmaPairs.size(); ++i) {
        const Ciede2000Pair& pair = kSharmaPairs[i];
        EXPECT_EQ(ciede2000(pair.lab1, pair.lab1), 0.0);
        // Pairs 9-16 sit on purpose within 0.02 degrees of |h'1 - h'2| = 180 degrees, where the formula's
        // mean hue jumps; swapping the colours may flip the side there, so symmetry is checked elsewhere.
        if (i >= 8 && i < 16) continue;
        EXPECT_NEAR(ciede2000(pair.lab2, pair.lab1), pair.delta_e, 0.5e-4 + 1e-9) << "swapped pair " << i + 1;
    }
}

TEST(ColourCiede2000, FloatVersionAgreesOffTheHueBoundary) {
    for (size_t i = 0; i < kSharmaPairs.size(); ++i) {
        if (i >= 8 && i < 16) continue;  // see above: float rounding may pick the other side of the jump
        const Ciede2000Pair& pair = kSharmaPairs[i];
        EXPECT_NEAR(ciede2000(vec3(pair.lab1), vec3(pair.lab2)), pair.delta_e, 1e-4 + 5e-5) << "pair " << i + 1;
    }
}

// ---- Reinhard transfer ------------------------------------------------------------------------------------

TEST(ColourTransfer, SigmaRatioRunsTargetOverSource) {
    // docs/design.md 4's pinned direction: src mu (50,0,0) sigma (10,5,5), tgt mu (60,5,-5) sigma (20,5,5);
    // the src pixel (60,5,-5) is one source sigma above in L (-> 60 + 1 * 20 = 80) and one below/above in a, b.
    const LabStatistics source{vec3(50, 0, 0), vec3(10, 5, 5)};
    const LabStatistics target{vec3(60, 5, -5), vec3(20, 5, 5)};
    const LabTransfer transfer = makeLabTransfer(source, target);
    const vec3 mapped = applyLabTransfer(transfer, vec3(60, 5, -5));
    EXPECT_NEAR(mapped.x, 80.0f, 1e-5f);
    EXPECT_NEAR(mapped.y, 10.0f, 1e-5f);
    EXPECT_NEAR(mapped.z, -10.0f, 1e-5f);
}

TEST(ColourTransfer, MeasuresPopulationStatisticsSkippingNonFinitePixels) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<vec3> pixels = {vec3(50, 0, 10), vec3(60, 10, -10), vec3(nan, 0, 0),
                                      vec3(0, std::numeric_limits<float>::infinity(), 0)};
    const LabStatistics statistics = measureLabStatistics(pixels);
    expectNear(dvec3(statistics.mean), dvec3(55, 5, 0), 1e-6, "mean");
    expectNear(dvec3(statistics.standard_deviation), dvec3(5, 5, 10), 1e-6, "sigma (divided by N)");
    const LabStatistics empty = measureLabStatistics({});
    expectNear(dvec3(empty.mean), dvec3(0.0), 0.0, "empty mean");
    expectNear(dvec3(empty.standard_deviation), dvec3(0.0), 0.0, "empty sigma");
}

TEST(ColourTransfer, TransferredPixelsTakeTheTargetStatistics) {
    // Reinhard's property: within the gain clamp, the transferred set has exactly the target's mu and sigma.
    std::mt19937 rng(30);
    std::normal_distribution<float> l(45.0f, 8.0f), a(3.0f, 4.0f), b(-6.0f, 5.0f);
    std::vector<vec3> source_pixels(5000);
    for (vec3& p : source_pixels) p = vec3(l(rng), a(rng), b(rng));
    const LabStatistics source = measureLabStatistics(source_pixels);
    const LabStatistics target{vec3(62, -2, 9), vec3(15, 6, 3)};
    const LabTransfer transfer = makeLabTransfer(source, target);
    std::vector<vec3> mapped;
    for (const vec3& p : source_pixels) mapped.push_back(applyLabTransfer(transfer, p));
    const LabStatistics result = measureLabStatistics(mapped);
    expectNear(dvec3(result.mean), dvec3(target.mean), 1e-3, "mean after transfer");
    expectNear(dvec3(result.standard_deviation), dvec3(target.standard_deviation), 1e-3, "sigma after transfer");
}

TEST(ColourTransfer, FlatSourceStaysFiniteAndTheGainIsClamped) {
    const LabStatistics flat_source{vec3(50, 0, 0), vec3(0.0f)};
    const LabStatistics target{vec3(60, 5, -5), vec3(20, 5, 0)};
    // sigma_src = 0: the floor makes the ratio finite, the clamp bounds it to max_gain.
    const LabTransfer clamped = makeLabTransfer(flat_source, target, 4.0f);
    EXPECT_EQ(clamped.gain, vec3(4.0f, 4.0f, 0.25f));  // b: target flat too, gain clamped from 0 up to 1/4
    const vec3 mapped = applyLabTransfer(clamped, vec3(50.5f, -1.0f, 2.0f));
    expectNear(dvec3(mapped), dvec3(62, 1, -4.5), 1e-5, "flat source, clamped gain");
    // Without the clamp only the floor acts: gain = sigma_tgt / 0.01.
    const LabTransfer unclamped =
        makeLabTransfer(flat_source, target, std::numeric_limits<float>::infinity());
    EXPECT_NEAR(unclamped.gain.x, 20.0f / kLabTransferMinSourceSigma, 1e-2f);
    EXPECT_EQ(unclamped.gain.z, 0.0f);
    for (const vec3& pixel : {vec3(50, 0, 0), vec3(50.001f, 1e-4f, -1e-4f), vec3(100, 100, -100)}) {
        const vec3 out = applyLabTransfer(unclamped, pixel);
        for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(out[c])) << "channel " << c;
    }
    // A flat pixel of a flat source lands on the target mean, whatever the gain.
    expectNear(dvec3(applyLabTransfer(unclamped, vec3(50, 0, 0))), dvec3(target.mean), 1e-6, "flat pixel");
    // max_gain below 1 (or NaN) means gain 1: a pure shift of means.
    EXPECT_EQ(makeLabTransfer(flat_source, target, 0.5f).gain, vec3(1.0f));
    EXPECT_EQ(makeLabTransfer(flat_source, target, std::numeric_limits<float>::quiet_NaN()).gain, vec3(1.0f));
}

// ---- GLSL twin on the device ------------------------------------------------------------------------------

constexpr int kProbeOutputs = 7;  // kColourProbeOutputs in colour_probe.comp

struct ProbeInput {
    vec3 rgb, lab1, lab2;
};

// 17^3 linear colours over [0, 1] (0 and 1 included), then HDR ones up to 16. lab1 is the colour's own Lab
// (C++, float); lab2 alternates between a near neighbour (dE ~ 1) and a far colour of the grid.
std::vector<ProbeInput> probeInputs() {
    std::vector<vec3> colours;
    for (int r = 0; r <= 16; ++r)
        for (int g = 0; g <= 16; ++g)
            for (int b = 0; b <= 16; ++b) colours.emplace_back(r / 16.0f, g / 16.0f, b / 16.0f);
    for (float r : {0.5f, 2.0f, 16.0f})
        for (float g : {0.0f, 1.5f, 4.0f})
            for (float b : {0.25f, 3.0f, 16.0f}) colours.emplace_back(r, g, b);
    std::vector<ProbeInput> inputs;
    for (size_t i = 0; i < colours.size(); ++i) {
        ProbeInput input;
        input.rgb = colours[i];
        input.lab1 = labFromLinearRec709(colours[i]);
        const vec3 partner = i % 2 == 0 ? colours[(i * 7919 + 13) % colours.size()]
                                        : colours[i] * vec3(0.97f, 1.02f, 0.99f) + vec3(0.004f, 0.0f, 0.006f);
        input.lab2 = labFromLinearRec709(partner);
        inputs.push_back(input);
    }
    return inputs;
}

struct MaxError {
    double value = 0.0;
    size_t probe = 0;
    void add(double error, size_t i) {
        if (error > value) value = error, probe = i;
    }
};

class ColourGlslTest : public testing::GpuTest {};

TEST_F(ColourGlslTest, EveryFunctionMatchesItsCppTwin) {
    const std::vector<ProbeInput> inputs = probeInputs();
    std::vector<glm::vec4> packed;
    for (const ProbeInput& p : inputs)
        packed.insert(packed.end(), {glm::vec4(p.rgb, 0), glm::vec4(p.lab1, 0), glm::vec4(p.lab2, 0)});
    const LabStatistics source{vec3(50, 2, -3), vec3(10, 0.001f, 6)};  // a: flat source, floor and clamp act
    const LabStatistics target{vec3(60, 5, -5), vec3(20, 5, 3)};
    const float max_gain = 4.0f;
    const std::array<glm::vec4, 4> statistics = {glm::vec4(source.mean, max_gain),
                                                 glm::vec4(source.standard_deviation, 0),
                                                 glm::vec4(target.mean, 0), glm::vec4(target.standard_deviation, 0)};

    GpuBuffer input_buffer(context(), packed.size() * sizeof(glm::vec4));
    GpuBuffer statistics_buffer(context(), sizeof statistics);
    GpuBuffer output_buffer(context(), inputs.size() * kProbeOutputs * sizeof(glm::vec4));
    input_buffer.uploadVector(packed);
    statistics_buffer.upload(statistics.data(), sizeof statistics);
    ComputePipeline pipeline(context(), kColourProbeCompSpirv, sizeof kColourProbeCompSpirv, 3, sizeof(uint32_t));
    pipeline.bindBuffers({&input_buffer, &statistics_buffer, &output_buffer});
    const uint32_t probe_count = uint32_t(inputs.size());
    pipeline.dispatchAndWait(&probe_count, (probe_count + 63) / 64);
    const std::vector<glm::vec4> out = output_buffer.downloadVector<glm::vec4>(inputs.size() * kProbeOutputs);

    const LabTransfer transfer = makeLabTransfer(source, target, max_gain);
    // Tolerances: float rounding only, relative to the size of the quantity (the device's pow, atan, cos and
    // sqrt are within a few ulp of the C library's; the chains below multiply that by at most ~10).
    auto relative = [](double a, double b, double scale) { return std::fabs(a - b) / std::max(1.0, scale); };
    MaxError srgb_encode, srgb_decode, luminance, xyz, lab, rgb_from_lab, delta_e, transferred, gain;
    for (size_t i = 0; i < inputs.size(); ++i) {
        const ProbeInput& p = inputs[i];
        const glm::vec4* o = out.data() + i * kProbeOutputs;
        const vec3 encoded = srgbEncode(p.rgb), decoded = srgbDecode(p.rgb), xyz_cpu = xyzFromLinearRec709(p.rgb);
        const vec3 lab_cpu = labFromLinearRec709(p.rgb), rgb_cpu = linearRec709FromLab(p.lab1);
        const vec3 transferred_cpu = applyLabTransfer(transfer, p.lab1);
        for (int c = 0; c < 3; ++c) {
            srgb_encode.add(relative(o[0][c], encoded[c], encoded[c]), i);
            srgb_decode.add(relative(o[1][c], decoded[c], decoded[c]), i);
            xyz.add(relative(o[2][c], xyz_cpu[c], std::fabs(xyz_cpu[c])), i);
            // a = 500 (fx - fy): one float ulp of a cube root f is 500 * 1.2e-7 f = 6e-5 f in a; f grows as
            // L / 116, so the error is scaled by L / 100 (HDR colours reach L ~ 270).
            lab.add(std::fabs(o[3][c] - lab_cpu[c]) / std::max(1.0f, lab_cpu.x / 100.0f), i);
            rgb_from_lab.add(relative(o[4][c], rgb_cpu[c], std::fabs(rgb_cpu[c])), i);
            transferred.add(relative(o[5][c], transferred_cpu[c], std::fabs(transferred_cpu[c])), i);
            gain.add(relative(o[6][c], transfer.gain[c], transfer.gain[c]), i);
        }
        const float y = luminanceRec709(p.rgb);
        luminance.add(relative(o[0].w, y, y), i);
        const double delta_e_cpu = ciede2000(dvec3(p.lab1), dvec3(p.lab2));
        delta_e.add(std::fabs(o[1].w - delta_e_cpu), i);
    }
    std::printf("colour.glsl vs colour.h over %zu colours, largest differences:\n"
                "  srgbEncode %.2e, srgbDecode %.2e (relative), luminance %.2e, XYZ %.2e (relative)\n"
                "  Lab %.2e (absolute, per 100 of L), RGB from Lab %.2e (relative),\n"
                "  CIEDE2000 %.2e (absolute, against the double version)\n"
                "  transfer %.2e, gain %.2e (relative)\n",
                inputs.size(), srgb_encode.value, srgb_decode.value, luminance.value, xyz.value, lab.value,
                rgb_from_lab.value, delta_e.value, transferred.value, gain.value);
    // Each bound is 3-5 times what lavapipe measures (in the printout above), so that a device whose pow or
    // atan is a few ulp off the C library's still passes, while a wrong constant or formula (errors of 1e-3 and
    // up) fails. Luminance, XYZ, the gain and the transfer allow 2-4 ulp for a device that fuses a multiply-add.
    EXPECT_LT(srgb_encode.value, 1e-6) << "probe " << srgb_encode.probe;
    EXPECT_LT(srgb_decode.value, 1e-6) << "probe " << srgb_decode.probe;
    EXPECT_LT(luminance.value, 3e-7) << "probe " << luminance.probe;
    EXPECT_LT(xyz.value, 5e-7) << "probe " << xyz.probe;
    EXPECT_LT(lab.value, 5e-4) << "probe " << lab.probe;
    EXPECT_LT(rgb_from_lab.value, 5e-6) << "probe " << rgb_from_lab.probe;
    EXPECT_LT(delta_e.value, 1e-3) << "probe " << delta_e.probe;
    EXPECT_LT(transferred.value, 5e-7) << "probe " << transferred.probe;
    EXPECT_LT(gain.value, 3e-7) << "probe " << gain.probe;
}

}  // namespace
}  // namespace gusuku
