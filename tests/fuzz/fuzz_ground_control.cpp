// libFuzzer target: `gusuku-bake georef`'s input, a ground control point CSV (gusuku_bake/ground_control.h), read
// and, when it holds 3 or more points, fitted (gusuku_bake/similarity_fit.h). Each input must be refused with an
// InputError (a bad line) or DegeneratePoints, or give a fit whose scale, rotation, translation and residuals are
// finite; anything else (another exception, a NaN, a sanitizer report) is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "gusuku/formats/input_error.h"
#include "gusuku_bake/ground_control.h"
#include "gusuku_bake/similarity_fit.h"

namespace {

void requireFinite(double value, const char* what) {
    if (std::isfinite(value)) return;
    std::fprintf(stderr, "fuzz_ground_control: %s is %g\n", what, value);
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const gusuku::GeodeticPoint origin{26.2856, 127.8008, 160.0};
    std::vector<gusuku::bake::GroundControlPoint> points;
    try {
        // Zone 52N serves the grid form; the latitude/longitude form ignores it.
        points = gusuku::bake::readGroundControlPoints("gcps.csv", text, origin, gusuku::UtmZone{52, true});
    } catch (const gusuku::InputError&) {
        return 0;
    }
    std::vector<glm::dvec3> mesh, enu;
    for (const gusuku::bake::GroundControlPoint& point : points) {
        mesh.push_back(point.mesh);
        enu.push_back(point.enu_m);
    }
    try {
        const gusuku::bake::SimilarityFit fit = gusuku::bake::fitSimilarity(mesh, enu);
        requireFinite(fit.transform.scale, "scale");
        for (const double component : fit.transform.rotation_wxyz) requireFinite(component, "a rotation component");
        for (int axis = 0; axis < 3; ++axis) requireFinite(fit.transform.translation[axis], "a translation component");
        for (const double residual : fit.residuals_m) requireFinite(residual, "a residual");
    } catch (const gusuku::bake::DegeneratePoints&) {
    }
    return 0;
}
