// ISO 8601 parsing/formatting and Julian days, checked against values worked out by hand from the calendar
// (and the Unix epoch's definition), never against the code's own output.
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "gusuku/maths/time_utc.h"

namespace {

using gusuku::formatIso8601;
using gusuku::julianDayFromUtcSeconds;
using gusuku::parseDateAtOffset;
using gusuku::parseIso8601Utc;

// 2000-01-01T00:00:00Z is 10957 days after the epoch (30 years, 7 of them leap: 72..96).
constexpr double kY2kSeconds = 946684800.0;

TEST(Iso8601, ParsesTheEpochAndY2k) {
    EXPECT_DOUBLE_EQ(parseIso8601Utc("1970-01-01T00:00:00Z"), 0.0);
    EXPECT_DOUBLE_EQ(parseIso8601Utc("2000-01-01T00:00:00Z"), kY2kSeconds);
    EXPECT_DOUBLE_EQ(parseIso8601Utc("1969-12-31T23:59:59Z"), -1.0);
}

TEST(Iso8601, AppliesOffsetsInTheRightDirection) {
    // 09:00 at +09:00 (Okinawa) is midnight UTC; 17:00 at -07:00 is midnight UTC the next day.
    EXPECT_DOUBLE_EQ(parseIso8601Utc("2000-01-01T09:00:00+09:00"), kY2kSeconds);
    EXPECT_DOUBLE_EQ(parseIso8601Utc("1999-12-31T17:00:00-07:00"), kY2kSeconds);
    EXPECT_DOUBLE_EQ(parseIso8601Utc("2000-01-01T05:30:00+05:30"), kY2kSeconds);
    // Seconds are optional.
    EXPECT_DOUBLE_EQ(parseIso8601Utc("2000-01-01T00:01Z"), kY2kSeconds + 60.0);
}

TEST(Iso8601, ParsesFractionalSeconds) {
    EXPECT_DOUBLE_EQ(parseIso8601Utc("2000-01-01T00:00:00.5Z"), kY2kSeconds + 0.5);
    EXPECT_NEAR(parseIso8601Utc("2000-01-01T00:00:01.250+00:00"), kY2kSeconds + 1.25, 1e-6);
}

TEST(Iso8601, HandlesLeapYears) {
    // 2024 is a leap year: 29 Feb exists and 1 Mar is two days after 28 Feb.
    const double feb28 = parseIso8601Utc("2024-02-28T00:00:00Z");
    EXPECT_DOUBLE_EQ(parseIso8601Utc("2024-02-29T00:00:00Z") - feb28, 86400.0);
    EXPECT_DOUBLE_EQ(parseIso8601Utc("2024-03-01T00:00:00Z") - feb28, 2.0 * 86400.0);
    // 2000 is a leap year (divisible by 400); 1900 and 2100 are not.
    EXPECT_NO_THROW(parseIso8601Utc("2000-02-29T12:00:00Z"));
    EXPECT_THROW(parseIso8601Utc("1900-02-29T12:00:00Z"), std::invalid_argument);
    EXPECT_THROW(parseIso8601Utc("2100-02-29T12:00:00Z"), std::invalid_argument);
    // 2024-12-31 is day 366 of 2024: 2025-01-01 is 366 days after 2024-01-01.
    EXPECT_DOUBLE_EQ(parseIso8601Utc("2025-01-01T00:00:00Z") - parseIso8601Utc("2024-01-01T00:00:00Z"),
                     366.0 * 86400.0);
}

TEST(Iso8601, RejectsBadText) {
    for (const char* text : {"2026-06-21T09:00:00",        // no offset: ambiguous
                             "2026-13-01T00:00:00Z",       // month 13
                             "2026-02-30T00:00:00Z",       // 30 February
                             "2026-04-31T00:00:00Z",       // 31 April
                             "2026-06-21 09:00:00Z",       // space instead of T
                             "2026-06-21T24:00:00Z",       // hour 24
                             "2026-06-21T09:60:00Z",       // minute 60
                             "2026-06-21T09:00:00+0900",   // offset without colon
                             "2026-06-21T09:00:00+09:00x", // trailing text
                             "2026-06-21T09:00:00.Z",      // '.' without digits
                             "26-06-21T09:00:00Z", ""}) {
        EXPECT_THROW(parseIso8601Utc(text), std::invalid_argument) << "'" << text << "'";
    }
}

TEST(Iso8601, AHugeTextIsCutInTheMessage) {
    const std::string huge = "2026-06-21T" + std::string(100000, '9');
    try {
        parseIso8601Utc(huge);
        ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& error) {
        const std::string message = error.what();
        EXPECT_LT(message.size(), 200u) << message.substr(0, 300);
        EXPECT_EQ(message.rfind("'" + huge.substr(0, 60) + "...' (100011 characters) is not an ISO 8601 time: ", 0),
                  0u)
            << message;
    }
}

TEST(Iso8601, MissingOffsetMessageSaysWhatIsWrong) {
    try {
        parseIso8601Utc("2026-06-21T09:00:00");
        FAIL() << "a time without an offset was accepted";
    } catch (const std::invalid_argument& error) {
        EXPECT_NE(std::string(error.what()).find("offset"), std::string::npos) << error.what();
    }
    try {
        parseIso8601Utc("2026-13-01T00:00:00Z");
        FAIL() << "month 13 was accepted";
    } catch (const std::invalid_argument& error) {
        EXPECT_NE(std::string(error.what()).find("month"), std::string::npos) << error.what();
    }
}

TEST(Iso8601, FormatsInTheRequestedZone) {
    EXPECT_EQ(formatIso8601(0.0, 0), "1970-01-01T00:00:00Z");
    EXPECT_EQ(formatIso8601(kY2kSeconds, 9 * 60), "2000-01-01T09:00:00+09:00");
    EXPECT_EQ(formatIso8601(kY2kSeconds, -7 * 60), "1999-12-31T17:00:00-07:00");
    EXPECT_EQ(formatIso8601(kY2kSeconds, -(3 * 60 + 30)), "1999-12-31T20:30:00-03:30");
    EXPECT_EQ(formatIso8601(kY2kSeconds + 0.25, 0), "2000-01-01T00:00:00.250Z");
    EXPECT_EQ(formatIso8601(-1.0, 0), "1969-12-31T23:59:59Z");
}

TEST(Iso8601, RoundTripsThroughFormatAndParse) {
    for (const char* text : {"2026-06-21T09:00:00+09:00", "2003-10-17T12:30:30-07:00", "2024-02-29T23:59:59Z",
                             "1910-03-15T00:30:00Z", "2210-12-15T21:30:00+05:45", "2026-06-21T09:00:00.125+09:00"}) {
        const std::string original = text;
        const double utc_seconds = parseIso8601Utc(original);
        int offset_minutes = 0;
        if (original.back() != 'Z') {
            const std::string suffix = original.substr(original.size() - 6);
            offset_minutes = (std::stoi(suffix.substr(1, 2)) * 60 + std::stoi(suffix.substr(4, 2))) *
                             (suffix[0] == '-' ? -1 : 1);
        }
        EXPECT_EQ(formatIso8601(utc_seconds, offset_minutes), original);
        EXPECT_DOUBLE_EQ(parseIso8601Utc(formatIso8601(utc_seconds, 0)), utc_seconds) << original;
    }
}

TEST(Iso8601, ParsesDatesAtAnOffset) {
    EXPECT_DOUBLE_EQ(parseDateAtOffset("2000-01-01", 0), kY2kSeconds);
    // Midnight at +09:00 is 15:00 UTC the day before.
    EXPECT_DOUBLE_EQ(parseDateAtOffset("2000-01-01", 9 * 60), kY2kSeconds - 9 * 3600.0);
    EXPECT_THROW(parseDateAtOffset("2026-02-30", 0), std::invalid_argument);
    EXPECT_THROW(parseDateAtOffset("2026-02-03T00:00Z", 0), std::invalid_argument);
}

TEST(JulianDay, MatchesTheAstronomicalEpochs) {
    // J2000.0 is JD 2451545.0 by definition; the Unix epoch is JD 2440587.5.
    EXPECT_DOUBLE_EQ(julianDayFromUtcSeconds(parseIso8601Utc("2000-01-01T12:00:00Z")), 2451545.0);
    EXPECT_DOUBLE_EQ(julianDayFromUtcSeconds(0.0), 2440587.5);
    // Reda and Andreas (2004), Table A4.1: 1987-01-27T00:00:00 UT is JD 2446822.5; 1988-06-19T12:00 UT 2447332.0.
    EXPECT_DOUBLE_EQ(julianDayFromUtcSeconds(parseIso8601Utc("1987-01-27T00:00:00Z")), 2446822.5);
    EXPECT_DOUBLE_EQ(julianDayFromUtcSeconds(parseIso8601Utc("1988-06-19T12:00:00Z")), 2447332.0);
}

}  // namespace
