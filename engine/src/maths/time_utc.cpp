// ISO 8601 instants with explicit offsets, and Julian days. All calendar arithmetic is done here with the
// proleptic Gregorian days-from-civil formula, so nothing depends on the machine's zone (no mktime, no timegm,
// no TZ).
#include "gusuku/maths/time_utc.h"

#include "gusuku/formats/input_error.h"  // quotedForMessage

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace gusuku {

namespace {

constexpr double kSecondsPerDay = 86400.0;
constexpr double kJulianDayOfUnixEpoch = 2440587.5;  // 1970-01-01T00:00:00Z

struct CivilDate {
    int64_t year;
    int month;  // 1..12
    int day;    // 1..31
};

bool isLeapYear(int64_t year) { return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0; }

int daysInMonth(int64_t year, int month) {
    static constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return month == 2 && isLeapYear(year) ? 29 : kDays[month - 1];
}

// Days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant's days_from_civil): eras of 400 years
// repeat exactly, and starting the year in March puts the leap day last.
int64_t daysFromCivil(int64_t year, int month, int day) {
    year -= month <= 2 ? 1 : 0;
    const int64_t era = (year >= 0 ? year : year - 399) / 400;
    const int64_t year_of_era = year - era * 400;
    const int64_t day_of_year = (153 * (month > 2 ? month - 3 : month + 9) + 2) / 5 + day - 1;
    const int64_t day_of_era = year_of_era * 365 + year_of_era / 4 - year_of_era / 100 + day_of_year;
    return era * 146097 + day_of_era - 719468;
}

// The inverse of daysFromCivil.
CivilDate civilFromDays(int64_t days) {
    days += 719468;
    const int64_t era = (days >= 0 ? days : days - 146096) / 146097;
    const int64_t day_of_era = days - era * 146097;
    const int64_t year_of_era = (day_of_era - day_of_era / 1460 + day_of_era / 36524 - day_of_era / 146096) / 365;
    const int64_t day_of_year = day_of_era - (365 * year_of_era + year_of_era / 4 - year_of_era / 100);
    const int64_t month_index = (5 * day_of_year + 2) / 153;  // 0 = March
    const int day = int(day_of_year - (153 * month_index + 2) / 5 + 1);
    const int month = int(month_index < 10 ? month_index + 3 : month_index - 9);
    return {year_of_era + era * 400 + (month <= 2 ? 1 : 0), month, day};
}

// A cursor over the text being parsed; every failure names the part that is wrong and quotes the text.
class IsoReader {
public:
    explicit IsoReader(const std::string& text) : text_(text) {}

    [[noreturn]] void fail(const std::string& problem) const {
        // A long text is cut in the message (a 100 KB argument is a mistake, not a time to echo back).
        throw std::invalid_argument(quotedForMessage(text_) + " is not an ISO 8601 time: " + problem);
    }

    bool atEnd() const { return position_ >= text_.size(); }
    char peek() const { return atEnd() ? '\0' : text_[position_]; }

    int readDigits(int count, const char* part) {
        int value = 0;
        for (int i = 0; i < count; ++i) {
            const char c = peek();
            if (c < '0' || c > '9')
                fail(std::string(part) + " needs " + std::to_string(count) + " digits");
            value = value * 10 + (c - '0');
            ++position_;
        }
        return value;
    }

    void expect(char wanted, const char* what) {
        if (peek() != wanted) fail(std::string("expected ") + what);
        ++position_;
    }

    // Digits after a decimal point, as a fraction of one.
    double readFraction() {
        double fraction = 0.0;
        double scale = 0.1;
        int digit_count = 0;
        while (peek() >= '0' && peek() <= '9') {
            fraction += scale * (peek() - '0');
            scale *= 0.1;
            ++position_;
            ++digit_count;
        }
        if (digit_count == 0) fail("the fractional seconds after '.' have no digits");
        return fraction;
    }

private:
    const std::string& text_;
    size_t position_ = 0;
};

CivilDate readDate(IsoReader& reader) {
    CivilDate date;
    date.year = reader.readDigits(4, "the year");
    reader.expect('-', "'-' after the year");
    date.month = reader.readDigits(2, "the month");
    reader.expect('-', "'-' after the month");
    date.day = reader.readDigits(2, "the day");
    if (date.month < 1 || date.month > 12) reader.fail("month " + std::to_string(date.month) + " is not 1..12");
    const int last_day = daysInMonth(date.year, date.month);
    if (date.day < 1 || date.day > last_day)
        reader.fail("day " + std::to_string(date.day) + " does not exist in " + std::to_string(date.year) + "-" +
                    (date.month < 10 ? "0" : "") + std::to_string(date.month) + " (1.." +
                    std::to_string(last_day) + ")");
    return date;
}

void checkFinite(double utc_seconds, const char* function) {
    if (!std::isfinite(utc_seconds))
        throw std::invalid_argument(std::string(function) + ": the UTC time is not a finite number");
}

}  // namespace

double parseIso8601Utc(const std::string& text) {
    IsoReader reader(text);
    const CivilDate date = readDate(reader);
    reader.expect('T', "'T' between the date and the time of day");
    const int hour = reader.readDigits(2, "the hour");
    reader.expect(':', "':' after the hour");
    const int minute = reader.readDigits(2, "the minute");
    int second = 0;
    double fraction = 0.0;
    if (reader.peek() == ':') {
        reader.expect(':', "':'");
        second = reader.readDigits(2, "the seconds");
        if (reader.peek() == '.') {
            reader.expect('.', "'.'");
            fraction = reader.readFraction();
        }
    }
    if (hour > 23) reader.fail("hour " + std::to_string(hour) + " is not 0..23");
    if (minute > 59) reader.fail("minute " + std::to_string(minute) + " is not 0..59");
    // A leap second (:60) cannot be represented by seconds since the epoch without a leap table; reject it.
    if (second > 59) reader.fail("second " + std::to_string(second) + " is not 0..59");

    int offset_minutes = 0;
    if (reader.atEnd())
        reader.fail("it has no UTC offset; add 'Z' or '+hh:mm'/'-hh:mm' (a clock time without a zone is "
                    "ambiguous)");
    if (reader.peek() == 'Z') {
        reader.expect('Z', "'Z'");
    } else if (reader.peek() == '+' || reader.peek() == '-') {
        const int sign = reader.peek() == '-' ? -1 : 1;
        reader.expect(reader.peek(), "a sign");
        const int offset_hours = reader.readDigits(2, "the offset hours");
        reader.expect(':', "':' in the offset (+hh:mm)");
        const int offset_rest = reader.readDigits(2, "the offset minutes");
        if (offset_hours > 23 || offset_rest > 59) reader.fail("the offset is not a valid +hh:mm");
        offset_minutes = sign * (offset_hours * 60 + offset_rest);
    } else {
        reader.fail("expected 'Z', '+hh:mm' or '-hh:mm' after the time of day");
    }
    if (!reader.atEnd()) reader.fail("unexpected text after the UTC offset");

    const double local_seconds = double(daysFromCivil(date.year, date.month, date.day)) * kSecondsPerDay +
                                 hour * 3600.0 + minute * 60.0 + second + fraction;
    return local_seconds - offset_minutes * 60.0;
}

double parseDateAtOffset(const std::string& date_text, int utc_offset_minutes) {
    IsoReader reader(date_text);
    const CivilDate date = readDate(reader);
    if (!reader.atEnd()) reader.fail("expected only a date YYYY-MM-DD");
    return double(daysFromCivil(date.year, date.month, date.day)) * kSecondsPerDay - utc_offset_minutes * 60.0;
}

std::string formatIso8601(double utc_seconds, int utc_offset_minutes) {
    checkFinite(utc_seconds, "formatIso8601");
    // Whole milliseconds, rounded once, so 59.9996 s carries into the next minute instead of printing "60".
    const double local_ms_real = std::round((utc_seconds + utc_offset_minutes * 60.0) * 1000.0);
    if (std::fabs(local_ms_real) > 9.0e15) throw std::invalid_argument("formatIso8601: the UTC time is out of range");
    const int64_t local_ms = int64_t(local_ms_real);
    const int64_t ms_per_day = 86400000;
    int64_t days = local_ms / ms_per_day;
    int64_t ms_of_day = local_ms % ms_per_day;
    if (ms_of_day < 0) {
        ms_of_day += ms_per_day;
        days -= 1;
    }
    const CivilDate date = civilFromDays(days);
    const int hour = int(ms_of_day / 3600000);
    const int minute = int(ms_of_day / 60000 % 60);
    const int second = int(ms_of_day / 1000 % 60);
    const int millisecond = int(ms_of_day % 1000);

    char text[64];
    int length = std::snprintf(text, sizeof text, "%04lld-%02d-%02dT%02d:%02d:%02d", (long long)date.year,
                               date.month, date.day, hour, minute, second);
    if (millisecond != 0) length += std::snprintf(text + length, sizeof text - length, ".%03d", millisecond);
    std::string result(text, size_t(length));
    if (utc_offset_minutes == 0) return result + "Z";
    const int magnitude = utc_offset_minutes < 0 ? -utc_offset_minutes : utc_offset_minutes;
    std::snprintf(text, sizeof text, "%c%02d:%02d", utc_offset_minutes < 0 ? '-' : '+', magnitude / 60,
                  magnitude % 60);
    return result + text;
}

double julianDayFromUtcSeconds(double utc_seconds) {
    checkFinite(utc_seconds, "julianDayFromUtcSeconds");
    return utc_seconds / kSecondsPerDay + kJulianDayOfUnixEpoch;
}

}  // namespace gusuku
