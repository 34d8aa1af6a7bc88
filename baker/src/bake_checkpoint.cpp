#include "bake_checkpoint.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "gusuku/assets/atomic_file.h"

namespace gusuku::bake {

namespace {
constexpr char kMagic[8] = {'G', 'S', 'K', 'C', 'K', 'P', 'T', '3'};
constexpr char kMagicWithoutSquares[8] = {'G', 'S', 'K', 'C', 'K', 'P', 'T', '1'};
constexpr char kMagicWithoutPartPasses[8] = {'G', 'S', 'K', 'C', 'K', 'P', 'T', '2'};
}  // namespace

void writeCheckpoint(const std::string& path, const Checkpoint& checkpoint) {
    if (checkpoint.luminance_square_sums.size() != checkpoint.sums.size())
        throw std::invalid_argument("writeCheckpoint: as many luminance square sums as sums needed");
    if (checkpoint.points_with_next_sample >= std::max<size_t>(checkpoint.sums.size(), 1))
        throw std::invalid_argument("writeCheckpoint: points_with_next_sample must be below the point count");
    std::string bytes(kMagic, sizeof kMagic);
    const uint32_t point_count = uint32_t(checkpoint.sums.size());
    bytes.append(reinterpret_cast<const char*>(&checkpoint.input_hash), sizeof checkpoint.input_hash);
    bytes.append(reinterpret_cast<const char*>(&point_count), sizeof point_count);
    bytes.append(reinterpret_cast<const char*>(&checkpoint.samples_done), sizeof checkpoint.samples_done);
    bytes.append(reinterpret_cast<const char*>(&checkpoint.points_with_next_sample),
                 sizeof checkpoint.points_with_next_sample);
    bytes.append(reinterpret_cast<const char*>(checkpoint.sums.data()),
                 checkpoint.sums.size() * sizeof(glm::vec4));
    bytes.append(reinterpret_cast<const char*>(checkpoint.luminance_square_sums.data()),
                 checkpoint.luminance_square_sums.size() * sizeof(float));
    writeBytesAtomically(path, bytes.data(), bytes.size());
}

std::optional<Checkpoint> readMatchingCheckpoint(const std::string& path, uint64_t input_hash,
                                                 uint32_t point_count, std::string* ignored_reason) {
    std::ifstream file(path, std::ios::binary);
    if (!file) return std::nullopt;
    char magic[8];
    Checkpoint checkpoint;
    uint32_t stored_point_count = 0;
    file.read(magic, sizeof magic);
    const bool without_squares = std::memcmp(magic, kMagicWithoutSquares, sizeof magic) == 0;
    if (file && (without_squares || std::memcmp(magic, kMagicWithoutPartPasses, sizeof magic) == 0)) {
        if (ignored_reason)
            *ignored_reason = path + ": checkpoint written by an older gusuku-bake (" +
                              (without_squares ? "GSKCKPT1, no per-texel variance" : "GSKCKPT2, older tracer") +
                              "); this set is traced afresh";
        return std::nullopt;
    }
    file.read(reinterpret_cast<char*>(&checkpoint.input_hash), sizeof checkpoint.input_hash);
    file.read(reinterpret_cast<char*>(&stored_point_count), sizeof stored_point_count);
    file.read(reinterpret_cast<char*>(&checkpoint.samples_done), sizeof checkpoint.samples_done);
    file.read(reinterpret_cast<char*>(&checkpoint.points_with_next_sample), sizeof checkpoint.points_with_next_sample);
    if (!file || std::memcmp(magic, kMagic, sizeof magic) != 0 || checkpoint.input_hash != input_hash ||
        stored_point_count != point_count || checkpoint.points_with_next_sample >= std::max(point_count, 1u))
        return std::nullopt;
    checkpoint.sums.resize(point_count);
    checkpoint.luminance_square_sums.resize(point_count);
    file.read(reinterpret_cast<char*>(checkpoint.sums.data()), std::streamsize(point_count * sizeof(glm::vec4)));
    file.read(reinterpret_cast<char*>(checkpoint.luminance_square_sums.data()),
              std::streamsize(point_count * sizeof(float)));
    if (!file) return std::nullopt;
    return checkpoint;
}

}  // namespace gusuku::bake
