#pragma once
// Why the bake marked a building texel invalid. The tracer marks a texel whose first rays mostly see back faces
// (irradiance_paths.glsl's back-face score against kMaxBackfaceFraction), summing one score for every kind of back
// face; this re-traces a fixed fan of first rays from each invalid texel's centre on the CPU (the bake's BVH) and
// names the kind of back face that weighs most in that score: a one-sided face of the building, the site's ground
// seen from below, or a closed double-sided part seen from inside. A texel is invalid when most of its footprint is
// (lightmap_uv.h's keptFootprintSlots), so a texel whose centre lies in the open but most of whose footprint's
// sub-points lie inside a part or under the ground is named from those sub-points' rays (the shrine's "unexplained"
// texels were these). Reasons depend on geometry only, so they are traced once per texel and reused by every slot.

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "bake_geometry.h"
#include "gusuku_bake/bake_job.h"
#include "gusuku_bake/lightmap_uv.h"

namespace gusuku::bake {

/// First rays re-traced per invalid texel (a stratified cosine fan): enough to name the main reason.
inline constexpr int kInvalidReasonRaysPerSide = 8;  // 8 x 8 = 64 rays

enum class InvalidTexelReason : uint8_t { OneSidedBack, UnderGround, ClosedDoubleSided, Unexplained };

class InvalidTexelAccounting {
public:
    /// footprint: the texels' footprints as traced (nullptr: centres only).
    explicit InvalidTexelAccounting(const BakeGeometry& geometry, const LightmapFootprint* footprint = nullptr);

    /// The slot's invalid texels by reason. texel_sums: per texel of geometry.texels, the folded sums
    /// (texelSumsFromFootprint) of `samples` samples; invalid where w / samples > kMaxBackfaceFraction, the test
    /// processBuildingLightmap applies.
    InvalidTexelCounts count(const std::string& slot, const std::vector<glm::vec4>& texel_sums, uint32_t samples);

    /// The main reason for texel i of geometry.texels (traced once, then remembered).
    InvalidTexelReason reason(size_t texel);

private:
    /// Adds the back-face scores of the ray fan from one surface point (by InvalidTexelReason).
    void scorePoint(const glm::vec3& position, const glm::vec3& shading_normal, const glm::vec3& geometric_normal,
                    double score[3]);

    const BakeGeometry& geometry_;
    const LightmapFootprint* footprint_;
    std::vector<bool> closed_;         ///< per triangle of the trace scene (closedOutwardTriangles)
    std::vector<int8_t> reason_of_;    ///< per texel: -1 not traced yet, else an InvalidTexelReason
};

}  // namespace gusuku::bake
