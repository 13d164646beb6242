#pragma once
// Direct light (direct_light.comp): emission + punctual lights with BVH shadow rays, glTF BRDF.

#include "vplkit/buffer.hpp"
#include "vplkit/scene_lights.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>

namespace vplkit {
class Context;
class Image;
class PassList;
struct GpuBvh;
}  // namespace vplkit

namespace vplkit::stages {

struct GbufferImages;

// The scene's punctual lights in the shader's layout (PunctualLight, shaders/include/vplkit/lights.glsl).
// Never empty (Vulkan has no empty buffers): with no lights it holds one unused entry and count 0.
struct GpuLights {
    Buffer buffer;
    uint32_t count = 0;
};
// Throws vplkit::Error naming the light for a non-finite or negative value.
GpuLights upload_lights(Context& context, std::span<const scene::Light> lights);

struct DirectLightParams {
    glm::vec3 camera_position{0.0f};
    glm::vec3 background{0.0f};
};

// Adds the pass "direct light", writing `radiance` (RGBA32F, storage usage, the G-buffer's size).
void add_direct_light_pass(Context& context, PassList& passes, GbufferImages& gbuffer, const GpuBvh& bvh,
                           const GpuLights& lights, const DirectLightParams& params, Image& radiance);

}  // namespace vplkit::stages
