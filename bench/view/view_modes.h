#pragma once
// The frames gusuku-view steps through (key M, --mode, the `mode` action): gusuku-bench's modes by their names
// (bench/bench/runtime_modes.h), so a mode seen in the window is the one the bench measures.

#include <cstddef>
#include <iterator>
#include <optional>
#include <string>

namespace gusuku::view {

/// gusuku's frame (baked light, no colour match: the camera's exposure is known), what AR apps draw today, the
/// seed paper's Reinhard match, and the two other matches.
inline constexpr const char* kViewModeNames[] = {"proposed", "direct_only", "proposed_paper_match",
                                                 "proposed_ground_match", "proposed_preserve_match"};

inline std::optional<size_t> viewModeIndex(const std::string& name) {
    for (size_t index = 0; index < std::size(kViewModeNames); ++index)
        if (name == kViewModeNames[index]) return index;
    return std::nullopt;
}

}  // namespace gusuku::view
