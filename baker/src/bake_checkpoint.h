#pragma once
// Checkpoints of a bake's running sums, so an interrupted bake (Ctrl-C, a kill, a power cut) resumes where it
// stopped. One file per (slot, point set) under BAKESET/.checkpoint/, written atomically after each chunk of
// samples. A checkpoint is used only when its input hash and point count match the current bake: a change of
// input or settings starts that set afresh.
//
// File layout (little-endian): "GSKCKPT1", uint64 input hash, uint32 point count, uint32 samples done,
// then point count x 4 float32 sums (the tracer's vec4: irradiance sum xyz, back-face score w: 1 per first hit on
// a one-sided back, 1/9 per first hit on a double-sided face seen from behind).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

namespace gusuku::bake {

struct Checkpoint {
    uint64_t input_hash = 0;
    uint32_t samples_done = 0;
    std::vector<glm::vec4> sums;
};

/// Writes atomically (temporary file, then rename).
void writeCheckpoint(const std::string& path, const Checkpoint& checkpoint);

/// Reads a checkpoint if the file exists, is intact, and matches input_hash and point_count; otherwise
/// returns nothing (a stale or damaged checkpoint is ignored, never an error: the set is simply redone).
std::optional<Checkpoint> readMatchingCheckpoint(const std::string& path, uint64_t input_hash,
                                                 uint32_t point_count);

}  // namespace gusuku::bake
