// gusuku-view's overlay text (bench/view/view_overlay.h): the box's size, the font's scaling, upper case, the
// fallback glyph, and a font typed by hand with no two glyphs alike.

#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "view_overlay.h"

namespace {

using gusuku::view::kGlyphAdvance;
using gusuku::view::kLinePitch;
using gusuku::view::kOverlayInk;
using gusuku::view::kOverlayPadding;
using gusuku::view::kOverlayPaper;
using gusuku::view::OverlayImage;
using gusuku::view::rasteriseOverlay;

// The 5 x 7 ink pattern of a one-character overlay, as 35 '#' or '.' characters.
std::string inkPattern(char character) {
    const OverlayImage image = rasteriseOverlay({std::string(1, character)}, 1);
    std::string pattern;
    for (uint32_t y = 0; y < 7; ++y)
        for (uint32_t x = 0; x < 5; ++x) {
            const size_t at = (size_t(kOverlayPadding + y) * image.width + kOverlayPadding + x) * 4;
            pattern += image.rgba8[at] == kOverlayInk ? '#' : '.';
        }
    return pattern;
}

TEST(ViewOverlay, TheBoxFitsTheLongestLineAndEveryLineWithItsPadding) {
    const OverlayImage image = rasteriseOverlay({"sun az 245.1 el 38.2", "cloud 0.00"}, 2);
    EXPECT_EQ(image.width, (20 * kGlyphAdvance + 2 * kOverlayPadding) * 2);
    EXPECT_EQ(image.height, (2 * kLinePitch + 2 * kOverlayPadding) * 2);
    ASSERT_EQ(image.rgba8.size(), size_t(image.width) * image.height * 4);
    EXPECT_TRUE(rasteriseOverlay({}, 1).rgba8.empty());
    // Opaque, grey, and only the two levels.
    for (size_t at = 0; at < image.rgba8.size(); at += 4) {
        ASSERT_EQ(image.rgba8[at + 3], 255);
        ASSERT_TRUE(image.rgba8[at] == kOverlayInk || image.rgba8[at] == kOverlayPaper);
        ASSERT_EQ(image.rgba8[at], image.rgba8[at + 1]);
        ASSERT_EQ(image.rgba8[at], image.rgba8[at + 2]);
    }
}

TEST(ViewOverlay, ScaleTwoIsScaleOneWithEachPixelDoubled) {
    const std::vector<std::string> lines = {"proposed msaa 4 | 2026-06-21T15:00", "frame 41 ms (keys)"};
    const OverlayImage one = rasteriseOverlay(lines, 1), two = rasteriseOverlay(lines, 2);
    ASSERT_EQ(two.width, one.width * 2);
    ASSERT_EQ(two.height, one.height * 2);
    for (uint32_t y = 0; y < two.height; ++y)
        for (uint32_t x = 0; x < two.width; ++x)
            ASSERT_EQ(two.rgba8[(size_t(y) * two.width + x) * 4], one.rgba8[(size_t(y / 2) * one.width + x / 2) * 4])
                << x << "," << y;
}

TEST(ViewOverlay, LettersAreUpperCaseAndAMissingCharacterIsAQuestionMark) {
    EXPECT_EQ(inkPattern('a'), inkPattern('A'));
    EXPECT_EQ(inkPattern('z'), inkPattern('Z'));
    EXPECT_EQ(inkPattern('~'), inkPattern('?'));
    EXPECT_EQ(inkPattern(' '), std::string(35, '.'));
}

TEST(ViewOverlay, EveryCharacterTheOverlayPrintsHasAGlyphOfItsOwn) {
    // What updateTitle prints: mode and slot names, ISO 8601 times, numbers, units and punctuation.
    const std::string printed = "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789.:-+()/_%|,=";
    std::set<std::string> patterns;
    for (const char character : printed) {
        const std::string pattern = inkPattern(character);
        EXPECT_NE(pattern, inkPattern('?')) << "'" << character << "' falls back to '?'";
        EXPECT_NE(pattern, std::string(35, '.')) << "'" << character << "' draws nothing";
        patterns.insert(pattern);
    }
    EXPECT_EQ(patterns.size(), printed.size()) << "two characters share a glyph: a typing slip in the font";
    // The gap column right of a glyph stays paper: glyphs do not touch.
    const OverlayImage image = rasteriseOverlay({"MW"}, 1);
    for (uint32_t y = 0; y < 7; ++y)
        EXPECT_EQ(image.rgba8[(size_t(kOverlayPadding + y) * image.width + kOverlayPadding + 5) * 4], kOverlayPaper);
}

}  // namespace
