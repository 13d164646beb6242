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

namespace vplkit::stages {

// Everything the tracer reads about the scene besides the BVH.
struct VplSources {
    Buffer lights;           // PunctualLight[max(punctual_count, 1)] (lights.glsl)
    Buffer emissive;         // EmitterTriangle[max(emissive_count, 1)] (trace_vpls.comp)
    Buffer emitter_cdf;      // float[max(emitter_count, 1)]
    Buffer triangle_albedo;  // vec4[triangle_count]: diffuse reflectance per scene triangle (rgb)
    uint32_t punctual_count = 0;
    uint32_t emissive_count = 0;
    // punctual_count + emissive_count, or 0 when no emitter has any power (then no path is traced).
    uint32_t emitter_count = 0;
    uint32_t triangle_count = 0;
    glm::vec3 scene_center{0.0f};  // bounding sphere of the triangles: directional lights cover it
    float scene_radius = 0.0f;
    // Sum over emitters of the power they emit, RGB (W): point 4 pi I, spot 2 pi I x the
    // integral of the squared cone attenuation, directional E x pi r^2 of the covering disc,
    // emissive triangle pi L A (x 2 when double-sided). Range windows are not counted.
    glm::vec3 total_power{0.0f};

    operator VplSourceBuffers() const {
        return {lights,         emissive,      emitter_cdf,    triangle_albedo, punctual_count,
                emissive_count, emitter_count, triangle_count, scene_center,    scene_radius};
    }
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

// The VPL buffers of one tracing: capacity = paths x max_bounces VPLs.
struct VplTracingOutput {
    Buffer vpls;                                // Vpl[capacity]: the first `count` are valid after the pass
    Buffer bounces;                             // uint32_t[capacity]: the bounce (1 = first surface hit) of each VPL
    Buffer count;                               // VplCountBuffer: the number of VPLs, and of paths cut short
    Buffer path_vpls, path_counts, block_vpls;  // scratch of the packing (VplTracingBuffers)
    uint32_t capacity = 0;

    // Throws Error when the options are invalid or the VPL buffer would exceed the device's
    // maxStorageBufferRange.
    static VplTracingOutput create(Context& context, const VplTracingOptions& options);

    operator VplTracingBuffers() const { return {vpls, bounces, count, path_vpls, path_counts, block_vpls}; }
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

}  // namespace vplkit::stages
