#include "fuzz_workdir.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace gusuku::fuzz {

namespace {

void writeFile(const std::string& path, const void* data, size_t size) {
    FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) throw std::runtime_error("fuzz: cannot write " + path);
    if (size > 0) std::fwrite(data, 1, size, file);
    std::fclose(file);
}

// A 2 x 2 RGBA PNG: red, green / blue, white.
const unsigned char kTexturePng[] = {
    0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A, 0x00, 0x00, 0x00, 0x0D, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
    0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x06, 0x00, 0x00, 0x00, 0x72, 0xB6, 0x0D, 0x24, 0x00, 0x00, 0x00,
    0x12, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9C, 0x63, 0xF8, 0xCF, 0xC0, 0xF0, 0x1F, 0x0C, 0x81, 0x34, 0x18, 0x00,
    0x00, 0x49, 0xC8, 0x09, 0xF7, 0xF9, 0xAB, 0xB6, 0x0D, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4E, 0x44, 0xAE,
    0x42, 0x60, 0x82};

std::string makeWorkFolder() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/gusuku_fuzz_XXXXXX";
    if (!mkdtemp(pattern.data())) throw std::runtime_error("fuzz: cannot create a work folder");
    const std::string folder = pattern;
    for (const char* name : {"building.glb", "site.glb", "sky.hdr", "sky_overcast.exr", "sky.jpg", "sky_dark.png"})
        writeFile(folder + "/" + name, "placeholder", 11);
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint16_t indices[3] = {0, 1, 2};
    unsigned char buffer[sizeof positions + sizeof indices];
    std::memcpy(buffer, positions, sizeof positions);
    std::memcpy(buffer + sizeof positions, indices, sizeof indices);
    writeFile(folder + "/buffer.bin", buffer, sizeof buffer);
    writeFile(folder + "/texture.png", kTexturePng, sizeof kTexturePng);
    return folder;
}

}  // namespace

const std::string& workFolder() {
    static const std::string folder = makeWorkFolder();
    static const bool removed_at_exit = std::atexit([] {
        std::error_code ignored;
        std::filesystem::remove_all(workFolder(), ignored);
    }) == 0;
    (void)removed_at_exit;
    return folder;
}

std::string writeInput(const std::string& name, const uint8_t* data, size_t size) {
    const std::string path = workFolder() + "/" + name;
    writeFile(path, data, size);
    return path;
}

}  // namespace gusuku::fuzz
