#pragma once
// Direct light (direct_light.comp): emission + punctual lights with BVH shadow rays, glTF BRDF.

#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <type_traits>

namespace vplkit::stages {

// The scene's punctual lights in the shader's layout (PunctualLight, shaders/include/vplkit/lights.glsl),
// read by direct light and VPL tracing: PunctualLight[max(count, 1)] (Vulkan has no empty
// buffers: with no lights it holds one unused entry and count is 0). The runtime fills it from a
// scene's lights (vplkit/gpu_lights.hpp: upload_lights, which owns them as a LightSet<Buffer>).
template <class BufferT>
struct LightSet {
    BufferT lights;
    uint32_t count = 0;

    operator LightSet<BufferView>() const requires(!std::is_same_v<BufferT, BufferView>) { return {lights, count}; }
};
using LightBuffers = LightSet<BufferView>;

struct DirectLightParams {
    glm::vec3 camera_position{0.0f};
    glm::vec3 background{0.0f};
};

// Adds the pass "direct light": reads the BVH, the G-buffer (position, normal, geometric normal,
// albedo, emission; GENERAL layout) and the lights, writes `radiance` (RGBA32F, storage usage,
// the G-buffer's size).
void add_direct_light_pass(Device& device, StepList& passes, const GbufferViews& gbuffer, const BvhBuffers& bvh,
                           const LightBuffers& lights, const DirectLightParams& params, const ImageView& radiance);

}  // namespace vplkit::stages
