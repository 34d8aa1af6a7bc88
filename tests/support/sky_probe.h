#pragma once
// GPU probe of shaders/include/sky_sampling.glsl (shaders/tests/sky_probe.comp), for tests: the GLSL sky lookup
// and sampling evaluated on the device, so tests can hold it to the CPU twins in gusuku_bake/sky_light.h.

#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "gusuku/gpu/vulkan_context.h"
#include "gusuku_bake/sky_light.h"

namespace gusuku::bake {

// ------------------------------------------------------------------------------------------------------------
// GPU probe of sky_sampling.glsl (sky_probe.cpp, shaders/tests/sky_probe.comp)
// ------------------------------------------------------------------------------------------------------------

/// One probe's results, all computed by the GLSL include on the device.
struct SkyProbeResult {
    glm::vec3 sampled_direction_enu{0.0f};  ///< sampleSkyDirection(xi)
    float sampled_pdf = 0.0f;               ///< its pdf_solid_angle out-parameter
    glm::vec3 radiance_at_direction{0.0f};  ///< skyRadiance(direction)
    float pdf_at_direction = 0.0f;          ///< skyPdf(direction)
    glm::vec3 radiance_at_sample{0.0f};     ///< skyRadiance(sampled direction)
    float pdf_at_sample = 0.0f;             ///< skyPdf(sampled direction)
    glm::vec3 combined_radiance{0.0f};      ///< skyRadianceAndPdf(direction): its radiance
    float combined_pdf = 0.0f;              ///< and its pdf out-parameter
    SkyRows rows;                           ///< skyRowsFacing(direction), the direction taken as a normal
    float rows_probability = 0.0f;          ///< skyRowsProbability(rows)
    glm::vec3 rows_sampled_direction_enu{0.0f};  ///< sampleSkyDirectionInRows(xi, rows)
    float rows_sampled_pdf = 0.0f;               ///< its pdf_solid_angle out-parameter
};

/// Runs shaders/tests/sky_probe.comp for xi[i] and directions[i] (equal sizes, else std::invalid_argument).
/// One synchronous dispatch; throws std::runtime_error on Vulkan failure.
std::vector<SkyProbeResult> runSkyProbeGpu(VulkanContext& context, const SkySamplingTables& tables,
                                           const std::vector<glm::vec2>& xi,
                                           const std::vector<glm::vec3>& directions_enu);

}  // namespace gusuku::bake
