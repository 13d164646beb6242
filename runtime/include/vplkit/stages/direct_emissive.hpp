#pragma once
// Direct light from emissive triangles (direct_emissive.comp): area-light sampling with BVH shadow
// rays, added to the radiance image the direct-light pass wrote.

#include "vplkit/buffer.hpp"
#include "vplkit/scene.hpp"

#include <glm/vec3.hpp>

#include <cstdint>

namespace vplkit {
class Context;
class Image;
class PassList;
struct GpuBvh;
}  // namespace vplkit

namespace vplkit::stages {

struct GbufferImages;

// The scene's emissive triangles (EmissiveTriangle, shaders/include/vplkit/emitters.glsl), each
// with the probability of being sampled, proportional to its power (luminance of the emitted
// radiance x area). Never empty: with no emitter it holds one unused entry and count 0.
struct GpuEmitters {
    Buffer triangles;
    uint32_t count = 0;
    double total_power = 0.0;  // sum of luminance(radiance) x area x pi, watts in luminance
};
GpuEmitters upload_emitters(Context& context, const scene::Scene& scene);

struct DirectEmissiveParams {
    glm::vec3 camera_position{0.0f};
    uint32_t samples = 16;  // per pixel
    uint32_t seed = 0;      // the same seed gives the same image
};

// Adds the pass "direct emissive": adds the emitters' direct light to `radiance` (RGBA32F,
// storage, the G-buffer's size). With no emitter the pass still records and adds nothing (the
// planner leaves it out of such frames).
void add_direct_emissive_pass(Context& context, PassList& passes, GbufferImages& gbuffer, const GpuBvh& bvh,
                              const GpuEmitters& emitters, const DirectEmissiveParams& params, Image& radiance);

}  // namespace vplkit::stages
