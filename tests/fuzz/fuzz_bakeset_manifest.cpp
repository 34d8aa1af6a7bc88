// libFuzzer target: parseBakeSetManifest on arbitrary bytes, the manifest.json every bake set reader, merge and
// gusuku-render start from. Bad input must end in gusuku::InputError; any other exception, a crash, a sanitizer
// report, a leak or a hang is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "gusuku/assets/bakeset_manifest_json.h"
#include "gusuku/formats/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        gusuku::parseBakeSetManifest("manifest.json", text);
    } catch (const gusuku::InputError&) {
    }
    return 0;
}
