#include "bake_checkpoint.h"

#include <cstring>
#include <fstream>

#include "gusuku/atomic_file.h"

namespace gusuku::bake {

namespace {
constexpr char kMagic[8] = {'G', 'S', 'K', 'C', 'K', 'P', 'T', '1'};
}

void writeCheckpoint(const std::string& path, const Checkpoint& checkpoint) {
    std::string bytes(kMagic, sizeof kMagic);
    const uint32_t point_count = uint32_t(checkpoint.sums.size());
    bytes.append(reinterpret_cast<const char*>(&checkpoint.input_hash), sizeof checkpoint.input_hash);
    bytes.append(reinterpret_cast<const char*>(&point_count), sizeof point_count);
    bytes.append(reinterpret_cast<const char*>(&checkpoint.samples_done), sizeof checkpoint.samples_done);
    bytes.append(reinterpret_cast<const char*>(checkpoint.sums.data()),
                 checkpoint.sums.size() * sizeof(glm::vec4));
    writeBytesAtomically(path, bytes.data(), bytes.size());
}

std::optional<Checkpoint> readMatchingCheckpoint(const std::string& path, uint64_t input_hash,
                                                 uint32_t point_count) {
    std::ifstream file(path, std::ios::binary);
    if (!file) return std::nullopt;
    char magic[8];
    Checkpoint checkpoint;
    uint32_t stored_point_count = 0;
    file.read(magic, sizeof magic);
    file.read(reinterpret_cast<char*>(&checkpoint.input_hash), sizeof checkpoint.input_hash);
    file.read(reinterpret_cast<char*>(&stored_point_count), sizeof stored_point_count);
    file.read(reinterpret_cast<char*>(&checkpoint.samples_done), sizeof checkpoint.samples_done);
    if (!file || std::memcmp(magic, kMagic, sizeof magic) != 0 || checkpoint.input_hash != input_hash ||
        stored_point_count != point_count)
        return std::nullopt;
    checkpoint.sums.resize(point_count);
    file.read(reinterpret_cast<char*>(checkpoint.sums.data()), std::streamsize(point_count * sizeof(glm::vec4)));
    if (!file) return std::nullopt;
    return checkpoint;
}

}  // namespace gusuku::bake
