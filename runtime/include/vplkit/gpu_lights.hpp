#pragma once
// A scene's lights uploaded for the direct-light stages (stages/direct_light.hpp,
// stages/direct_emissive.hpp): the owning buffers, which convert to the views the stages take.

#include "vplkit/buffer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_lights.hpp"
#include "vplkit/stages/direct_emissive.hpp"
#include "vplkit/stages/direct_light.hpp"
#include "vplkit/shaders/types.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace vplkit {
class Context;
}

namespace vplkit {

// The scene's punctual lights in the shader's layout (PunctualLight, shaders/include/vplkit/lights.glsl).
// Never empty (Vulkan has no empty buffers): with no lights it holds one unused entry and count 0.
using GpuLights = stages::LightSet<Buffer>;
// Throws vplkit::Error naming the light for a non-finite or negative value.
GpuLights upload_lights(Context& context, std::span<const scene::Light> lights);

// The scene's emissive triangles (EmissiveTriangle, shaders/include/vplkit/emitters.glsl), each
// with the probability of being sampled, proportional to its power (luminance of the emitted
// radiance x area). Never empty: with no emitter it holds one unused entry and count 0.
struct GpuEmitters : stages::EmitterSet<Buffer> {
    double total_power = 0.0;  // sum of luminance(radiance) x area x pi, watts in luminance
};
GpuEmitters upload_emitters(Context& context, const scene::Scene& scene);

// The radiance emissive triangle t emits, constant over the triangle: the material's emissive
// factor x strength, times the emissive texture's mean over the triangle where it has one (64
// nearest-texel reads at the centroids of an 8 x 8 subdivision in UV space, sRGB decoded). The
// G-buffer shows the texture itself; light leaving the triangle (direct light, the light tree's
// power, light paths) uses this mean: its power is exact to the quadrature, its light's spatial
// variation within one triangle is not kept.
glm::vec3 triangle_emission(const scene::Scene& scene, uint32_t t);

// One emissive triangle as upload_emitters uploads it (cdf unset), with its power.
struct EmitterTriangle {
    shaders::EmissiveTriangle triangle{};
    glm::dvec3 power{0.0};         // RGB watts: radiance x area x pi x (2 when double-sided)
    double luminance_power = 0.0;  // Rec. 709 luminance of `power`: the flat sampler's weight
    uint32_t scene_triangle = 0;   // its index among the scene's triangles
};
// The scene's emissive triangles that emit (luminance power > 0 and finite), in
// scene.emissive_triangles order: the entries of upload_emitters' buffer, one for one.
std::vector<EmitterTriangle> emitter_triangles(const scene::Scene& scene);

}  // namespace vplkit
