#pragma once
// What the VPL tracer (vpl_tracing.hpp) reads about a scene, from a renderer's own data: its
// punctual lights (renderer_lights.hpp), its emissive triangles if any, and its triangles with
// a diffuse albedo per triangle or one for all. The result is host data in one block: copy it
// into one storage buffer and take the views.
//
//   const std::vector<glm::vec3> triangles = ...;   // 3 vertices per triangle: build_bvh's input
//   auto sources = vplkit::stages::vpl_sources_from_renderer(lights, {}, {triangles, {}, glm::vec3(0.6f)});
//   // a buffer of sources.bytes() with storage usage, then:
//   sources.write(mapped);                          // or a staging copy of the same bytes
//   vplkit::stages::add_trace_vpls_passes(kit, steps, bvh, sources.views(my_buffer_view), options, out);
//
// A kind that is absent (no punctual light, no emissive triangle, no emitter at all) has no
// record and no view; the tracer traces no path when nothing emits.

#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/renderer_lights.hpp"
#include "vplkit/stages/vpl_tracing.hpp"
#include "vplkit/views.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace vplkit::stages {

// An emissive triangle: Lambertian, `radiance` (W / (m^2 sr), linear RGB, >= 0) leaving its
// front face (counter-clockwise (v0, v1, v2) seen from the front), both faces when double_sided.
struct RendererEmitter {
    uint32_t triangle = 0;  // index into RendererSurfaces::triangles (vertices 3t .. 3t + 2)
    glm::vec3 radiance{0.0f};
    bool double_sided = false;
};

struct RendererSurfaces {
    // World-space vertices, 3 per triangle: the same list (and order) the BVH was built from,
    // so triangle t here is the BVH's id t.
    std::span<const glm::vec3> triangles;
    // Diffuse reflectance (linear RGB in [0, 1]; albedo / pi is the BRDF) per triangle, or empty:
    // every triangle reflects `albedo`. A glTF material's is base colour x (1 - metallic).
    std::span<const glm::vec3> triangle_albedo;
    glm::vec3 albedo{0.5f};
};

// A texture's mean colour, linear RGB: what a surface textured with it reflects on average, the
// per-triangle albedo the tracer takes (it has no UVs at a hit; the kit's own loader does the
// same). `rgba`: width x height texels, 8 bits a channel, RGBA order; `srgb`: the texels are
// sRGB-encoded colour (a base colour texture), else linear. Multiply by the material's factor
// (and by 1 - metallic). Throws vplkit::Error when rgba holds fewer than width x height texels
// or the image is empty.
glm::vec3 mean_texture_albedo(std::span<const uint8_t> rgba, uint32_t width, uint32_t height, bool srgb);

// The tracer's sources as host data, each array at an offset of its own in one block.
struct VplSourceData {
    std::vector<shaders::PunctualLight> lights;      // empty: no punctual light
    std::vector<shaders::EmitterTriangle> emissive;  // empty: no emissive triangle
    std::vector<float> emitter_cdf;                  // selection_cdf of the powers; empty: nothing emits
    std::vector<shaders::vec4> triangle_albedo;      // rgb per triangle
    uint32_t emitter_count = 0;                      // lights + emissive, 0 when nothing emits
    glm::vec3 scene_center{0.0f};                    // the triangles' bounding sphere
    float scene_radius = 0.0f;
    glm::dvec3 total_power{0.0};  // W, RGB: what all emitters emit (punctual_light_power's rules)

    // Bytes of the block: each array at a multiple of 256 bytes (every device's storage-buffer
    // offset alignment is at most that).
    uint64_t bytes() const;
    // Writes the block to `destination` (bytes() of them).
    void write(void* destination) const;
    // The views add_trace_vpls_passes takes, into `block`: a buffer holding write()'s bytes at
    // block.offset (which must be a multiple of the device's minStorageBufferOffsetAlignment).
    // An empty array gets an empty view. Throws Error when `block` is smaller than bytes().
    VplSourceBuffers views(const BufferView& block) const;
};

// Throws vplkit::Error naming the problem: no triangle, a vertex count not a multiple of 3, a
// non-finite vertex, triangle_albedo neither empty nor one per triangle, an albedo outside
// [0, 1] or not finite, a bad light (to_punctual_light), an emitter's triangle out of range or
// radiance negative or not finite. Emitters of zero area or radiance are left out.
VplSourceData vpl_sources_from_renderer(std::span<const RendererLight> lights,
                                        std::span<const RendererEmitter> emitters, const RendererSurfaces& surfaces);

}  // namespace vplkit::stages
