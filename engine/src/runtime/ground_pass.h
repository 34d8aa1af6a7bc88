#pragma once
// The ground ratio in the main pass (docs/design.md 8): the ground quads the building can change (its shadow,
// its baked light; ground_quads.h chooses them) multiply the camera by the ratio of the ground's light with the
// building to its light without. The quads are chosen again only when what chooses them changes (the rounded
// sun, the mode, whether the sun shines, the slots in use, or a sun weaker than the choice assumed: the cells the
// frame's light leaves at a ratio of exactly 1 are not drawn, ground_sunlit.h); each frame slot copies the newest
// choice into its own host-visible buffers when it next renders, so no write lands under a frame still in flight.
// A FramePass (frame_pass.h).
// Private to gusuku_runtime.

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "device_object.h"
#include "frame_pass.h"
#include "frame_preparation.h"
#include "ground_quads.h"
#include "gusuku/gpu/gpu_compute.h"

namespace gusuku::runtime_detail {

class FrameSet;

/// What chooses the ground quads.
struct GroundRequest {
    bool wanted = false;                 ///< groundQuadsWanted
    bool include_baked_changes = false;  ///< not direct-only: the quads only the baked light changes too
    bool sun_shines = false;
    glm::dvec3 shadow_sun{0.0};          ///< the shadow maps' rounded sun
    std::array<int, 3> slots_in_use{-1, -1, -1};  ///< the blend's slots of non-zero weight (prepare fills it)
    bool operator==(const GroundRequest&) const = default;
};

/// The fraction of the frame's E_sun a choice assumes while it holds: chosen again once the sun falls below it
/// (a setting sun, weather's sun_scale), so a frame's sun is never weaker than the one its quads were chosen for.
constexpr double kGroundSunFloorFraction = 0.97;

class GroundPass final : public FramePass {
public:
    GroundPass(const PassContext& context, const GroundGrid& grid, const FrameSet& frame_set, uint32_t slot_count,
               VkRenderPass main_pass, VkSampleCountFlagBits samples);

    /// Host side, in `slot` (whose previous frame has completed): the quads chosen for `request`, copied into
    /// the slot's buffers when they hold an older choice. blend and sun_irradiance_rgb are the frame's (the
    /// marked cells its light leaves at a ratio of exactly 1 are not drawn: ground_sunlit.h).
    void prepare(uint32_t slot, GroundRequest request, const SlotBlend& blend, const glm::dvec3& sun_irradiance_rgb);
    void recordInMainPass(PassRecording& recording) override;

    uint32_t quadsDrawn() const { return quads_drawn_; }  ///< with at least one triangle drawn
    uint64_t memoryBytes() const;

private:
    struct SlotBuffers {
        GpuBuffer indices;         // host-visible: the quads chosen, 6 indices each
        GpuBuffer candidates;      // host-visible vertex stream: per cell, the building's shadow may fall here
        uint64_t generation = 0;   // which choice the two hold
    };
    void choose(const GroundRequest& request, const SlotBlend& blend, const glm::dvec3& sun_irradiance_rgb);

    const PassContext context_;
    const GroundGrid grid_;
    const FrameSet& frame_set_;
    std::vector<SlotBuffers> slots_;
    Pipeline shadow_pipeline_;   // quads the building's shadow may reach
    Pipeline baked_pipeline_;    // quads only its baked light changes: no building shadow
    Pipeline sunless_pipeline_;  // the same with no sun at all: no shadow-map reads
    std::optional<GroundRequest> chosen_for_;  // what the quads were last chosen for
    uint32_t index_count_ = 0;                 // all triangles drawn, times 3
    uint32_t shadow_index_count_ = 0;          // the first of them, the quads the building's shadow may reach
    uint32_t quads_drawn_ = 0;                 // quads with at least one triangle drawn
    uint64_t generation_ = 0;                  // counts the choices; each slot uploads the newest
    // The reused host arrays that choose them (no allocation per frame).
    std::vector<uint8_t> cell_marked_;
    std::vector<float> shadow_candidate_;      // per cell: 1 where the building's shadow may fall
    std::vector<uint32_t> quad_indices_;
    std::vector<uint8_t> pass_through_;        // per cell: the baked change leaves the ratio at 1 (ground_sunlit.h)
    glm::dvec3 sun_floor_{0.0};                // the E_sun the choice assumed
};

}  // namespace gusuku::runtime_detail
