#pragma once
// Checkpoints of a bake's running sums, so an interrupted bake (Ctrl-C, a kill, a power cut) resumes where it
// stopped. One file per (slot, point set) under BAKESET/.checkpoint/, written atomically at a dispatch boundary
// (every 2 s, at a stop, at the set's end), which may fall inside a sample pass cut into point ranges: the file
// then says which points hold the pass's sample, and the resumed bake traces the rest. A checkpoint is used only when its input hash and point count match the current bake: a change of
// input or settings starts that set afresh.
//
// File layout (little-endian): "GSKCKPT3", uint64 input hash, uint32 point count, uint32 samples done,
// uint32 points with the next sample (points [0, this) hold samples_done + 1 samples), then point count x 4
// float32 sums (the tracer's vec4: irradiance sum xyz, back-face score w: 1 per first hit on a one-sided back, 1/9
// per first hit on a closed part's double-sided face seen from behind), then point count x float32 sums
// of squared luminance (the lightmap filter's measure of each texel's noise). "GSKCKPT1" (before the squares)
// and "GSKCKPT2" (before part-done passes) are recognised and not resumed: their tracer code differs, so that
// set is traced afresh.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

namespace gusuku::bake {

struct Checkpoint {
    uint64_t input_hash = 0;
    uint32_t samples_done = 0;
    uint32_t points_with_next_sample = 0;  ///< PointAccumulator's: below the point count
    std::vector<glm::vec4> sums;
    std::vector<float> luminance_square_sums;  ///< as many as sums
};

/// Writes atomically (temporary file, then rename).
void writeCheckpoint(const std::string& path, const Checkpoint& checkpoint);

/// Reads a checkpoint if the file exists, is intact, and matches input_hash and point_count; otherwise
/// returns nothing (a stale or damaged checkpoint is ignored, never an error: the set is simply redone).
/// When a file exists but is not used because an older gusuku-bake wrote it, `ignored_reason` (if given) gets
/// one line saying so, for the bake to print.
std::optional<Checkpoint> readMatchingCheckpoint(const std::string& path, uint64_t input_hash,
                                                 uint32_t point_count, std::string* ignored_reason = nullptr);

}  // namespace gusuku::bake
