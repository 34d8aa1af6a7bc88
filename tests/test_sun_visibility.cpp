// The sun's state kept apart from the sky's (issue 41 item 3; gusuku/maths/sun_visibility.h): the regime a report
// gives, the frame's evidence deciding the instant, hysteresis against flicker, a ramp as quick as a cloud's edge,
// and the frame's light taking the sky's state and the sun's scale separately (gusuku/maths/frame_lighting.h).

#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/maths/frame_lighting.h"
#include "gusuku/maths/sun_visibility.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace gusuku {
namespace {

constexpr double kFrameSeconds = 1.0 / 30.0;

// A small deterministic generator (xorshift32), so the noisy sequences are the same on every machine.
class NoiseSource {
public:
    float uniform() {  // [0, 1)
        state_ ^= state_ << 13;
        state_ ^= state_ >> 17;
        state_ ^= state_ << 5;
        return float(state_ >> 8) / float(1u << 24);
    }

private:
    uint32_t state_ = 2463534242u;
};

TEST(SkyRegime, MetarClassesAndTheHighVeil) {
    // METAR's amounts as the weather reader gives them (oktas / 8), and a cloud base in feet.
    EXPECT_EQ(skyRegimeFromCover(0.0f, -1.0f), SkyRegime::kClear);          // SKC, CAVOK
    EXPECT_EQ(skyRegimeFromCover(1.5f / 8.0f, 2500.0f), SkyRegime::kClear);  // FEW025
    EXPECT_EQ(skyRegimeFromCover(3.5f / 8.0f, 2500.0f), SkyRegime::kBroken); // SCT025
    EXPECT_EQ(skyRegimeFromCover(6.0f / 8.0f, 3500.0f), SkyRegime::kBroken); // BKN035
    EXPECT_EQ(skyRegimeFromCover(1.0f, 1200.0f), SkyRegime::kOvercast);      // OVC012
    EXPECT_EQ(skyRegimeFromCover(1.0f, std::nanf("")), SkyRegime::kOvercast);  // base not known: taken as low
    EXPECT_EQ(skyRegimeFromCover(1.0f, 20000.0f), SkyRegime::kHighThinOvercast);  // OVC200: cirrostratus
    EXPECT_EQ(skyRegimeFromCover(std::nanf(""), 0.0f), SkyRegime::kUnknown);
}

TEST(SunVisibility, AHighVeilKeepsASofterSunAndAnOvercastReportHidesIt) {
    SunVisibilityFilter veil;
    const SunVisibilityState& under_veil = veil.update(0.0, SkyRegime::kHighThinOvercast, nullptr);
    EXPECT_TRUE(under_veil.sun_out);
    EXPECT_FLOAT_EQ(under_veil.sun_visibility, 1.0f);
    EXPECT_FLOAT_EQ(under_veil.sun_strength, kHighThinOvercastSunStrength);
    EXPECT_EQ(under_veil.cue, SunStateCue::kRegimePrior);

    SunVisibilityFilter overcast;
    const SunVisibilityState& grey = overcast.update(0.0, SkyRegime::kOvercast, nullptr);
    EXPECT_FALSE(grey.sun_out);
    EXPECT_FLOAT_EQ(grey.sun_visibility, 0.0f);
}

TEST(SunVisibility, AConfidentFrameOverrulesTheReport) {
    // The report says overcast (an airport 30 km away, half an hour old); the frame shows hard shadows.
    SunVisibilityFilter filter;
    const SunEvidence shadows{0.95f, 1.0f, -1.0f};
    filter.update(0.0, SkyRegime::kOvercast, &shadows);
    EXPECT_TRUE(filter.state().sun_out);
    EXPECT_EQ(filter.state().cue, SunStateCue::kFrame);
    // And the other way: a clear report, but no shadow where the site must cast one.
    SunVisibilityFilter clear;
    const SunEvidence no_shadow{0.05f, 1.0f, -1.0f};
    clear.update(0.0, SkyRegime::kClear, &no_shadow);
    EXPECT_FALSE(clear.state().sun_out);
    EXPECT_EQ(clear.state().cue, SunStateCue::kFrame);
    // With no confidence the frame says nothing, however it leans.
    SunVisibilityFilter unsure;
    const SunEvidence unsure_evidence{0.05f, 0.0f, -1.0f};
    unsure.update(0.0, SkyRegime::kClear, &unsure_evidence);
    EXPECT_TRUE(unsure.state().sun_out);
    EXPECT_EQ(unsure.state().cue, SunStateCue::kRegimePrior);
}

// A cloud passes over the sun for ten seconds under broken cloud, at 30 frames a second. The evidence is noisy
// throughout, and for a second around each cloud edge it is no better than a coin (the penumbra of a cloud's edge,
// a half-lit frame): one change when the cloud comes, one when it goes, and the ramps last transition_seconds.
TEST(SunVisibility, ACloudPassingForTenSecondsGivesTwoChanges) {
    const double cloud_arrives = 20.0, cloud_leaves = 30.0, end = 50.0;
    SunVisibilityFilter filter;
    NoiseSource noise;
    double hidden_at = -1.0, out_again_at = -1.0, dark_at = -1.0, bright_again_at = -1.0;
    for (double time = 0.0; time < end; time += kFrameSeconds) {
        const bool behind_cloud = time >= cloud_arrives && time < cloud_leaves;
        const bool near_edge = std::fabs(time - cloud_arrives) < 0.5 || std::fabs(time - cloud_leaves) < 0.5;
        SunEvidence evidence;
        evidence.confidence = 0.5f + 0.5f * noise.uniform();
        evidence.sun_out_probability = near_edge ? noise.uniform()
                                       : behind_cloud ? 0.3f * noise.uniform()
                                                      : 0.7f + 0.3f * noise.uniform();
        const SunVisibilityState& state = filter.update(time, SkyRegime::kBroken, &evidence);
        if (!state.sun_out && hidden_at < 0.0) hidden_at = time;
        if (hidden_at >= 0.0 && state.sun_out && out_again_at < 0.0) out_again_at = time;
        if (state.sun_visibility == 0.0f && dark_at < 0.0) dark_at = time;
        if (out_again_at >= 0.0 && state.sun_visibility == 1.0f && bright_again_at < 0.0) bright_again_at = time;
    }
    EXPECT_EQ(filter.state().changes, 2u);
    // Each change within a second and a half of the cloud's edge (the coin-flip second around it, then the hold).
    EXPECT_GT(hidden_at, cloud_arrives - 0.5);
    EXPECT_LT(hidden_at, cloud_arrives + 1.5);
    EXPECT_GT(out_again_at, cloud_leaves - 0.5);
    EXPECT_LT(out_again_at, cloud_leaves + 1.5);
    // The ramp: 1.5 s from full sun to none, and back, within a frame.
    const SunVisibilityOptions defaults;
    EXPECT_NEAR(dark_at - hidden_at, defaults.transition_seconds, 1.5 * kFrameSeconds);
    EXPECT_NEAR(bright_again_at - out_again_at, defaults.transition_seconds, 1.5 * kFrameSeconds);
}

TEST(SunVisibility, EvidenceThatFlickersEveryFrameChangesNothing) {
    SunVisibilityFilter filter;
    for (int frame = 0; frame < 300; ++frame) {
        const SunEvidence evidence{frame % 2 == 0 ? 0.95f : 0.05f, 1.0f, -1.0f};
        filter.update(frame * kFrameSeconds, SkyRegime::kBroken, &evidence);
    }
    EXPECT_EQ(filter.state().changes, 0u);
    EXPECT_FLOAT_EQ(filter.state().sun_visibility, 1.0f);
}

TEST(SunVisibility, TheMeasuredStrengthIsFollowedAndBadNumbersAreNone) {
    // Thin cloud: the sun dimmed to a third, measured every frame.
    SunVisibilityFilter filter;
    const SunEvidence dimmed{0.9f, 1.0f, 1.0f / 3.0f};
    for (int frame = 0; frame < 300; ++frame) filter.update(frame * kFrameSeconds, SkyRegime::kClear, &dimmed);
    EXPECT_NEAR(filter.state().sun_strength, 1.0f / 3.0f, 0.02f / 3.0f);  // ten time constants: within 2 %
    // NaN and out-of-range evidence counts as none: the prior holds, nothing becomes NaN.
    SunVisibilityFilter robust;
    const SunEvidence nonsense{std::nanf(""), 7.0f, std::nanf("")};
    for (int frame = 0; frame < 30; ++frame) robust.update(frame * kFrameSeconds, SkyRegime::kClear, &nonsense);
    EXPECT_TRUE(robust.state().sun_out);
    EXPECT_FLOAT_EQ(robust.state().sun_strength, 1.0f);
    EXPECT_FALSE(std::isnan(robust.state().posterior));
    // A clock that goes back is no time passing: no ramp step, no change.
    robust.update(-100.0, SkyRegime::kOvercast, nullptr);
    EXPECT_FLOAT_EQ(robust.state().sun_visibility, 1.0f);
}

TEST(FrameLighting, BrokenCloudWithTheSunOutBlendsTheSkyButKeepsTheWholeSun) {
    const BakeSetManifest manifest = testing::makeSyntheticBakeSet().manifest;
    SunObserver observer;
    observer.latitude_deg = manifest.site.latitude_deg;
    observer.longitude_deg = manifest.site.longitude_deg;
    observer.height_m = manifest.site.height_m;
    const double noon = testing::syntheticLocalTime(12, 0);
    const FrameLighting clear = computeFrameLighting(manifest, observer, noon, 0.0f, true);
    // BKN (6 oktas): the sky three quarters towards the overcast slot, the sun out at full strength.
    const FrameLighting broken_sun_out = computeFrameLighting(manifest, observer, noon, SkyAndSun{0.75f, 1.0f}, true);
    EXPECT_FLOAT_EQ(broken_sun_out.sunny_weight, 0.25f);
    EXPECT_FLOAT_EQ(broken_sun_out.overcast_weight, 0.75f);
    EXPECT_EQ(broken_sun_out.sun_irradiance_rgb, clear.sun_irradiance_rgb);
    // The same sky with the sun behind a cloud: no sun at all, not a quarter of one.
    const FrameLighting broken_sun_hidden =
        computeFrameLighting(manifest, observer, noon, SkyAndSun{0.75f, 0.0f}, true);
    EXPECT_EQ(broken_sun_hidden.sun_irradiance_rgb, glm::dvec3(0.0));
    EXPECT_FLOAT_EQ(broken_sun_hidden.overcast_weight, 0.75f);
    // The cover overload is {c, 1 - c}, bit for bit.
    const FrameLighting by_cover = computeFrameLighting(manifest, observer, noon, 0.75f, true);
    const FrameLighting by_parts = computeFrameLighting(manifest, observer, noon, SkyAndSun{0.75f, 0.25f}, true);
    EXPECT_EQ(by_cover.sun_irradiance_rgb, by_parts.sun_irradiance_rgb);
    EXPECT_EQ(by_cover.sunny_weight, by_parts.sunny_weight);
    // A NaN scale is no sun, never a NaN.
    const FrameLighting nan_scale =
        computeFrameLighting(manifest, observer, noon, SkyAndSun{0.0f, std::nanf("")}, true);
    EXPECT_EQ(nan_scale.sun_irradiance_rgb, glm::dvec3(0.0));
}

}  // namespace
}  // namespace gusuku
