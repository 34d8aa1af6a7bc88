#pragma once
// Writes a bake set's files (layout in docs/bakeset.md): building.glb with its lightmap UVs, ground_geometry.exr,
// occluder.glb (the SfM mesh simplified, when site.json has one), per slot building_<slot>.exr, ground_<slot>_with.exr and ground_<slot>_without.exr, and manifest.json last,
// so a bake set with a manifest is always complete. Every file is written atomically.

#include <optional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>
#include "bake_geometry.h"
#include "gusuku/formats/bakeset_manifest.h"
#include "gusuku_bake/bake_job.h"
#include "gusuku_bake/slot_lighting.h"

namespace gusuku::bake {

/// A texel is invalid (inside geometry, seen from behind a wall) when more than this share of its first rays
/// hit back faces; invalid texels are filled by dilation from their valid neighbours.
inline constexpr float kMaxBackfaceFraction = 0.1f;

/// Averages, validity, denoise and dilation of the building lightmap. Returns resolution^2 RGBA texels (alpha 1
/// where traced and valid, 0 elsewhere; RGB filled by dilation in invalid texels and the padding around charts),
/// and per texel of geometry.texels the irradiance with alpha 1/0 for validity (for statistics).
struct ProcessedLightmap {
    std::vector<glm::vec4> image;
    std::vector<glm::vec4> per_texel;
    size_t invalid_texels = 0;
};
/// texel_luminance_variance: per texel of geometry.texels, the variance of its mean luminance (the filter's
/// measure of noise, lightmap_denoise.h); empty: the filter's stop without measured variance.
ProcessedLightmap processBuildingLightmap(const BakeGeometry& geometry, const std::vector<glm::vec4>& sums,
                                          uint32_t samples, bool denoise,
                                          const std::vector<float>& texel_luminance_variance = {});

class BakeOutputWriter {
public:
    BakeOutputWriter(std::string output_dir, const BakeGeometry& geometry, uint32_t samples, bool denoise);

    void writeGeometry();
    /// building_luminance_variance: per texel, as processBuildingLightmap's.
    void writeSlot(const SlotLighting& lighting, const std::vector<glm::vec4>& building_sums,
                   const std::vector<float>& building_luminance_variance,
                   const std::vector<glm::vec4>& ground_with_sums, const std::vector<glm::vec4>& ground_without_sums);
    /// Input paths are written relative to the output folder (gusuku/assets/bakeset_loader.h's
    /// bakeSetRelativeInputPath), so the set moves with its inputs. `partial`: this is one slot's partial set.
    void writeManifest(const SiteConfig& site, uint64_t input_hash, const BakeReport& report,
                       const std::optional<BakeSetPartial>& partial = std::nullopt);
    /// After writeGeometry: the hash of the files every slot shares (bake_merge.h's slotIndependentFilesHash).
    uint64_t slotIndependentHash() const;

private:
    void writeGroundImage(const std::string& file, const std::vector<glm::vec4>& sums);
    void writeOccluder();

    std::string output_dir_;
    const BakeGeometry& geometry_;
    uint32_t samples_;
    bool denoise_;
    std::vector<BakeSetSlot> slots_;  ///< manifest entries of the slots written so far
    std::optional<BakeSetOccluderInfo> occluder_;  ///< the manifest's entry once occluder.glb is written
};

}  // namespace gusuku::bake
