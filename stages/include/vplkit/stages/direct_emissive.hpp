#pragma once
// Direct light from emissive triangles (direct_emissive.comp): area-light sampling with BVH shadow
// rays, added to the radiance image the direct-light pass wrote.

#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <type_traits>

namespace vplkit::stages {

// The scene's emissive triangles (EmissiveTriangle[max(count, 1)], shaders/include/vplkit/emitters.glsl),
// each with its entry of the selection CDF (selection_cdf.hpp; weights proportional to power).
// Never empty: with no emitter it holds one unused entry and count is 0. The runtime fills it
// from a scene (vplkit/gpu_lights.hpp: upload_emitters, which owns them as GpuEmitters).
template <class BufferT>
struct EmitterSet {
    BufferT triangles;
    uint32_t count = 0;

    operator EmitterSet<BufferView>() const requires(!std::is_same_v<BufferT, BufferView>) {
        return {triangles, count};
    }
};
using EmitterBuffers = EmitterSet<BufferView>;

struct DirectEmissiveParams {
    glm::vec3 camera_position{0.0f};
    uint32_t samples = 16;  // per pixel
    uint32_t seed = 0;      // the same seed gives the same image
};

// Adds the pass "direct emissive": reads the BVH, the G-buffer (position, normal, geometric
// normal, albedo; GENERAL layout) and the emitters, adds their direct light to `radiance`
// (read and written; RGBA32F, storage, the G-buffer's size). With no emitter the pass still
// records and adds nothing (the planner leaves it out of such frames).
void add_direct_emissive_pass(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                              const EmitterBuffers& emitters, const DirectEmissiveParams& params,
                              const ImageView& radiance);

}  // namespace vplkit::stages
