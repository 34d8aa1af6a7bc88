// libFuzzer target: loadPlyMesh on arbitrary bytes as a .ply survey mesh (gusuku/assets/survey_mesh.h).
// Bad input must end in gusuku::InputError; any other exception, a crash, a sanitizer report, a leak or a hang is
// a finding. The transform is a site's typical similarity (scale, a turn, an offset) so finishSurveyMesh runs too.
#include <cstddef>
#include <cstdint>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "fuzz_workdir.h"
#include "gusuku/assets/survey_mesh.h"
#include "gusuku/formats/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = gusuku::fuzz::writeInput("input.ply", data, size);
    const glm::dmat4 enu_from_model = glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, -2.0, 1.0)) *
                                      glm::rotate(glm::dmat4(1.0), 1.0, glm::dvec3(1.0, 0.0, 0.0)) *
                                      glm::scale(glm::dmat4(1.0), glm::dvec3(0.5));
    try {
        gusuku::loadPlyMesh(path, enu_from_model);
    } catch (const gusuku::InputError&) {
    }
    return 0;
}
