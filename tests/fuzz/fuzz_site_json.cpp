// libFuzzer target: loadSiteConfig on arbitrary bytes. Bad input must end in gusuku::InputError; any other
// exception, a crash, a sanitizer report, a leak or a hang is a finding.
#include <cstddef>
#include <cstdint>

#include "fuzz_workdir.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/assets/site.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = gusuku::fuzz::writeInput("site.json", data, size);
    try {
        gusuku::loadSiteConfig(path);
    } catch (const gusuku::InputError&) {
    }
    return 0;
}
