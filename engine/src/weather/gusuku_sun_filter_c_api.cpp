// gusuku_weather.h's sun filter: SunVisibilityFilter (gusuku/maths/sun_visibility.h) behind the C API's conventions.
#include <cstdio>
#include <new>

#include "gusuku/maths/sun_visibility.h"
#include "gusuku/weather/gusuku_weather.h"
#include "gusuku_c_errors.h"

struct gusuku_sun_filter {
    gusuku::SunVisibilityFilter filter;
};

namespace {

using gusuku::c_api_detail::fail;

static_assert(int(gusuku::SkyRegime::kUnknown) == GUSUKU_SKY_REGIME_UNKNOWN &&
              int(gusuku::SkyRegime::kClear) == GUSUKU_SKY_REGIME_CLEAR &&
              int(gusuku::SkyRegime::kBroken) == GUSUKU_SKY_REGIME_BROKEN &&
              int(gusuku::SkyRegime::kOvercast) == GUSUKU_SKY_REGIME_OVERCAST &&
              int(gusuku::SkyRegime::kHighThinOvercast) == GUSUKU_SKY_REGIME_HIGH_THIN_OVERCAST,
              "gusuku_sky_regime mirrors SkyRegime value for value");

gusuku_result failArgument(const char* function, const char* problem) {
    char message[GUSUKU_MESSAGE_CAPACITY];
    std::snprintf(message, sizeof message, "%s: %s", function, problem);
    return fail(GUSUKU_ERROR_INVALID_ARGUMENT, message);
}

}  // namespace

extern "C" gusuku_result gusuku_sun_filter_create(gusuku_sun_filter** out_filter) {
    if (out_filter == nullptr) return failArgument("gusuku_sun_filter_create", "out_filter: is NULL");
    *out_filter = new (std::nothrow) gusuku_sun_filter{};
    if (*out_filter == nullptr) return fail(GUSUKU_ERROR_OUT_OF_MEMORY, "gusuku_sun_filter_create: out of memory");
    return GUSUKU_OK;
}

extern "C" gusuku_result gusuku_sun_filter_update(gusuku_sun_filter* filter, double time_seconds,
                                                  gusuku_sky_regime regime, const gusuku_sun_evidence* evidence,
                                                  gusuku_sun_state* out_state) {
    const char* const function = "gusuku_sun_filter_update";
    if (filter == nullptr) return failArgument(function, "filter: is NULL");
    if (out_state == nullptr) return failArgument(function, "out_state: is NULL");
    if (int(regime) < GUSUKU_SKY_REGIME_UNKNOWN || int(regime) > GUSUKU_SKY_REGIME_HIGH_THIN_OVERCAST)
        return failArgument(function, "regime: not a gusuku_sky_regime");
    gusuku::SunEvidence converted;
    if (evidence != nullptr)
        converted = {evidence->sun_out_probability, evidence->confidence, evidence->sun_strength};
    const gusuku::SunVisibilityState& state =
        filter->filter.update(time_seconds, gusuku::SkyRegime(regime), evidence != nullptr ? &converted : nullptr);
    out_state->sun_out = state.sun_out ? 1 : 0;
    out_state->sun_visibility = state.sun_visibility;
    out_state->sun_strength = state.sun_strength;
    out_state->posterior = state.posterior;
    out_state->decided_by_frame = state.cue == gusuku::SunStateCue::kFrame ? 1 : 0;
    out_state->changes = state.changes;
    return GUSUKU_OK;
}

extern "C" void gusuku_sun_filter_free(gusuku_sun_filter* filter) { delete filter; }
