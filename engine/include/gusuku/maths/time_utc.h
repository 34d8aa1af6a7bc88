#pragma once
// UTC time. Internally gusuku holds instants as UTC seconds since the Unix epoch (double); files carry
// ISO 8601 with an explicit offset. The machine's local zone is never consulted.

#include <string>

namespace gusuku {

/// Parses "YYYY-MM-DDThh:mm[:ss[.fff]](Z|+hh:mm|-hh:mm)" into UTC seconds since 1970-01-01T00:00:00Z.
/// A missing offset is an error (a clock time without a zone is ambiguous). Throws std::invalid_argument
/// with a message saying which part is wrong.
double parseIso8601Utc(const std::string& text);

/// Parses a date "YYYY-MM-DD"; returns UTC seconds of its 00:00 at the given offset (minutes east of UTC).
double parseDateAtOffset(const std::string& date, int utc_offset_minutes);

/// Formats UTC seconds as ISO 8601 in the zone utc_offset_minutes east of UTC, e.g. "2026-06-21T09:00:00+09:00".
std::string formatIso8601(double utc_seconds, int utc_offset_minutes);

/// Julian day (UT) of UTC seconds since the Unix epoch: JD = unix / 86400 + 2440587.5.
double julianDayFromUtcSeconds(double utc_seconds);

}  // namespace gusuku
