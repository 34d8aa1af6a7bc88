#pragma once
// Periodic-term tables of NREL's Solar Position Algorithm (Reda and Andreas 2004, NREL/TP-560-34302,
// Tables A4.2 and A4.3, with NREL's 2006 corrections). Internal to sun_spa.cpp; not a public header.

#include <cstddef>

namespace gusuku::spa_terms {

/// One term A * cos(B + C * JME) of an Earth heliocentric series (A in 1e-8 rad or AU, B in rad, C in rad per
/// Julian ephemeris millennium).
struct EarthTerm {
    double amplitude;
    double phase_rad;
    double frequency_rad_per_millennium;
};

/// One series (L0, L1, ... ) as a pointer and a count, so the series of a quantity can differ in length.
struct EarthSeries {
    const EarthTerm* terms;
    std::size_t count;
};

/// Heliocentric longitude L0..L5, latitude B0..B1 and radius vector R0..R4.
extern const EarthSeries kLongitudeSeries[6];
extern const EarthSeries kLatitudeSeries[2];
extern const EarthSeries kRadiusSeries[5];

/// One nutation term: the multipliers of the five fundamental arguments X0..X4 (Y in the paper) and the
/// coefficients of longitude (a + b*JCE) * sin(arg) and obliquity (c + d*JCE) * cos(arg), in 0.0001 arcsec.
struct NutationTerm {
    int argument_multipliers[5];
    double longitude_a, longitude_b;
    double obliquity_c, obliquity_d;
};

inline constexpr std::size_t kNutationTermCount = 63;
extern const NutationTerm kNutationTerms[kNutationTermCount];

}  // namespace gusuku::spa_terms
