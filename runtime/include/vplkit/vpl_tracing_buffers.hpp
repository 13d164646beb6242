#pragma once
// The runtime's side of VPL tracing (stages/vpl_tracing.hpp): a scene's emitters and reflectances
// uploaded for the tracer, the output buffers, and the blocking read of the count. The owning
// structs convert to the views the stage takes.

#include "vplkit/buffer.hpp"
#include "vplkit/stages/vpl_tracing.hpp"

#include <glm/vec3.hpp>

#include <cstdint>

namespace vplkit {
class Context;
namespace scene {
struct Scene;
}
}  // namespace vplkit

namespace vplkit {

// Everything the tracer reads about the scene besides the BVH, owned (stages/vpl_tracing.hpp's
// VplSourceSet; converts to VplSourceBuffers).
struct VplSources : stages::VplSourceSet<Buffer> {
    // Sum over emitters of the power they emit, RGB (W): point 4 pi I, spot 2 pi I x the
    // integral of the squared cone attenuation, directional E x pi r^2 of the covering disc,
    // emissive triangle pi L A (x 2 when double-sided). Range windows are not counted.
    glm::vec3 total_power{0.0f};
};

// Uploads scene.lights (validated like upload_lights: a bad light throws Error naming it), the
// emissive triangles (scene.emissive_triangles, radiance = Material::emission(), front face,
// both when the material is double-sided), the selection CDF (weight = an emitter's power summed
// over RGB) and the per-triangle diffuse reflectance (see stages/vpl_tracing.hpp; textures read
// from scene.textures and scene.images). Reads vertices, indices,
// triangle_materials, materials, emissive_triangles and lights. The BVH must be built from
// scene::triangle_positions(scene) (ids = scene triangle indices). Throws Error for a scene
// without triangles or with a material index out of range.
VplSources upload_vpl_sources(Context& context, const scene::Scene& scene);

// The VPL buffers of one tracing, owned (stages/vpl_tracing.hpp's VplTracingSet; converts to
// VplTracingBuffers): capacity = paths x max_bounces VPLs.
struct VplTracingOutput : stages::VplTracingSet<Buffer> {
    uint32_t capacity = 0;

    // Throws Error when the options are invalid or the VPL buffer would exceed the device's
    // maxStorageBufferRange.
    static VplTracingOutput create(Context& context, const stages::VplTracingOptions& options);
};

struct VplCounts {
    uint32_t vpls = 0;  // traced (at most the capacity)
    // Paths the driver ended early: lavapipe silently stops an invocation's loops after 65535
    // iterations of all of them together (bounces x BVH traversal steps); such a path's later
    // bounces are missing, so the VPL set underestimates the light. 0 on other drivers.
    uint32_t cut_short = 0;
};
// Blocking read of output.count after a run.
VplCounts download_vpl_counts(const VplTracingOutput& output);
// The number of VPLs the last run traced; throws Error when any path was cut short.
uint32_t download_vpl_count(const VplTracingOutput& output);
// The same from a VplCountBuffer that outlived its VplTracingOutput (a frame's VPLs keep it).
uint32_t checked_vpl_count(const Buffer& count, uint32_t capacity);

}  // namespace vplkit
