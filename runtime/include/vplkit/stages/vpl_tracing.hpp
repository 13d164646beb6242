#pragma once
// VPL generation by instant radiosity (trace_vpls.comp): light paths from the scene's emitters
// (punctual lights and emissive triangles, chosen by power) traced through the BVH, one VPL
// appended at every diffuse surface hit, cosine-weighted bounces with Russian roulette.
//
//   auto bvh = vplkit::upload_bvh(context, vplkit::build_bvh(vplkit::scene::triangle_positions(scene)));
//   auto sources = vplkit::stages::upload_vpl_sources(context, scene);
//   auto out = vplkit::stages::VplTracingOutput::create(context, options);
//   vplkit::PassList passes;
//   vplkit::stages::add_trace_vpls_pass(context, passes, bvh, sources, options, out);
//   passes.run(context);
//   uint32_t count = vplkit::stages::download_vpl_count(out);   // VPLs 0..count-1 of out.vpls
//
// What a VPL's flux means: the flux its surface re-emits diffusely, i.e. the flux arriving along
// the path times the diffuse reflectance, divided by the number of paths; the VPLs of bounce k
// together estimate, without bias, the flux reflected after k surface interactions (see the
// shader's header). Surfaces reflect diffusely with rho = base colour x (1 - metallic), each
// texture entering as its mean over the image (the mean linear colour of the base colour
// texture, the mean B channel of the metallic-roughness texture): no texture lookup at hits;
// the specular lobe is not followed, and alpha is ignored (opaque).

#include "vplkit/buffer.hpp"

#include <glm/vec3.hpp>

#include <cstdint>

namespace vplkit {
class Context;
class PassList;
struct GpuBvh;
namespace scene {
struct Scene;
}
}  // namespace vplkit

namespace vplkit::stages {

struct VplTracingOptions {
    uint32_t paths = 0;        // light paths, >= 1
    uint32_t max_bounces = 0;  // surface hits per path (VPLs per path at most), >= 1
    uint32_t seed = 0;         // the same seed gives the same set of VPLs
};

// Everything the tracer reads about the scene besides the BVH.
struct VplSources {
    Buffer lights;            // PunctualLight[max(punctual_count, 1)] (lights.glsl)
    Buffer emissive;          // EmitterTriangle[max(emissive_count, 1)] (trace_vpls.comp)
    Buffer emitter_cdf;       // float[max(emitter_count, 1)]
    Buffer triangle_albedo;   // vec4[triangle_count]: diffuse reflectance per scene triangle (rgb)
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
};

// Uploads scene.lights (validated like upload_lights: a bad light throws Error naming it), the
// emissive triangles (scene.emissive_triangles, radiance = Material::emission(), front face,
// both when the material is double-sided), the selection CDF (weight = an emitter's power summed
// over RGB) and the per-triangle diffuse reflectance (see above; textures read from
// scene.textures and scene.images). Reads vertices, indices,
// triangle_materials, materials, emissive_triangles and lights. The BVH must be built from
// scene::triangle_positions(scene) (ids = scene triangle indices). Throws Error for a scene
// without triangles or with a material index out of range.
VplSources upload_vpl_sources(Context& context, const scene::Scene& scene);

// The VPL buffers of one tracing: capacity = paths x max_bounces VPLs.
struct VplTracingOutput {
    Buffer vpls;     // Vpl[capacity]: the first `count` are valid after the pass
    Buffer bounces;  // uint32_t[capacity]: the bounce (1 = first surface hit) of each VPL
    Buffer count;    // VplCountBuffer: the number of VPLs appended, and of paths cut short
    uint32_t capacity = 0;

    // Throws Error when the options are invalid or the VPL buffer would exceed the device's
    // maxStorageBufferRange.
    static VplTracingOutput create(Context& context, const VplTracingOptions& options);
};

// Throws Error for paths or max_bounces 0, max_bounces 2^32 - 1, or paths x max_bounces above 2^32 - 1.
uint32_t vpl_capacity(const VplTracingOptions& options);

// Adds the passes "vpl count clear" and "trace vpls". `output` must hold at least
// vpl_capacity(options) VPLs (Error otherwise).
void add_trace_vpls_pass(Context& context, PassList& passes, const GpuBvh& bvh, const VplSources& sources,
                         const VplTracingOptions& options, VplTracingOutput& output);

struct VplCounts {
    uint32_t vpls = 0;       // appended (at most the capacity)
    // Paths the driver ended early: lavapipe silently stops an invocation's loops after 65535
    // iterations of all of them together (bounces x BVH traversal steps); such a path's later
    // bounces are missing, so the VPL set underestimates the light. 0 on other drivers.
    uint32_t cut_short = 0;
};
// Blocking read of output.count after a run.
VplCounts download_vpl_counts(const VplTracingOutput& output);
// The number of VPLs the last run appended; throws Error when any path was cut short.
uint32_t download_vpl_count(const VplTracingOutput& output);

}  // namespace vplkit::stages
