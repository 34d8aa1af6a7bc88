// What the runtime weighs in device memory (Runtime::deviceMemoryBytes): the bake set as uploaded and each
// pass's own images and buffers.

#include "runtime_impl.h"

namespace gusuku::runtime_detail {

uint64_t RuntimeImpl::deviceMemoryBytes() const {
    uint64_t bytes = camera_->memoryBytes() + targets_->memoryBytes() + shadows_->memoryBytes() +
                     frame_set_->memoryBytes() + colour_->stateBuffer().size() + ground_->memoryBytes() +
                     submission_->memoryBytes() + (sun_evidence_ ? sun_evidence_->memoryBytes() : 0);
    for (const GpuImage* image : {&scene_.lightmaps, &scene_.ground_irradiance, &scene_.ground_geometry,
                                  &scene_.white_texture})
        bytes += image->memoryBytes();
    for (const GpuImage& texture : scene_.textures) bytes += texture.memoryBytes();
    for (const GpuBuffer* buffer : {&scene_.building_vertices, &scene_.building_indices, &scene_.occluder_vertices,
                                    &scene_.occluder_indices})
        bytes += buffer->size();
    return bytes;
}

}  // namespace gusuku::runtime_detail
