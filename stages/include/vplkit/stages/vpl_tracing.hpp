#pragma once
// VPL generation by instant radiosity (trace_vpls.comp): light paths from the scene's emitters
// (punctual lights and emissive triangles, chosen by power) traced through the BVH, one VPL
// appended at every diffuse surface hit, cosine-weighted bounces with Russian roulette.
//
//   auto bvh = vplkit::upload_bvh(context, vplkit::build_bvh(vplkit::scene::triangle_positions(scene)));
//   auto sources = vplkit::stages::upload_vpl_sources(context, scene);     // runtime: vpl_tracing_buffers.hpp
//   auto out = vplkit::stages::VplTracingOutput::create(context, options);  // runtime: vpl_tracing_buffers.hpp
//   vplkit::PassList passes;
//   vplkit::stages::add_trace_vpls_passes(context, passes, bvh, sources, options, out);
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

#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <type_traits>

namespace vplkit::stages {

struct VplTracingOptions {
    uint32_t paths = 0;        // light paths, >= 1
    uint32_t max_bounces = 0;  // surface hits per path (VPLs per path at most), >= 1
    uint32_t seed = 0;         // the same seed gives the same VPLs in the same order
};

// Everything the tracer reads about the scene besides the BVH (all read only). The runtime
// fills them from a scene (vplkit/vpl_tracing_buffers.hpp: upload_vpl_sources), a renderer from
// its own lights and triangles (renderer_vpl_sources.hpp: vpl_sources_from_renderer). A buffer
// whose count is 0 may be an empty view (no buffer): no dummy record is needed.
template <class BufferT>
struct VplSourceSet {
    BufferT lights;           // PunctualLight[punctual_count] (lights.glsl)
    BufferT emissive;         // EmitterTriangle[emissive_count] (trace_vpls.comp)
    BufferT emitter_cdf;      // float[emitter_count]: selection_cdf of the emitters' powers
    BufferT triangle_albedo;  // vec4[triangle_count]: diffuse reflectance per scene triangle (rgb), >= 1
    uint32_t punctual_count = 0;
    uint32_t emissive_count = 0;
    // punctual_count + emissive_count, or 0 when no emitter has any power (then no path is traced).
    uint32_t emitter_count = 0;
    uint32_t triangle_count = 0;
    glm::vec3 scene_center{0.0f};  // bounding sphere of the triangles: directional lights cover it
    float scene_radius = 0.0f;

    operator VplSourceSet<BufferView>() const requires(!std::is_same_v<BufferT, BufferView>) {
        return {lights,         emissive,      emitter_cdf,    triangle_albedo, punctual_count,
                emissive_count, emitter_count, triangle_count, scene_center,    scene_radius};
    }
};
// What the tracer reads, as views; the runtime's VplSources owns them (vplkit/vpl_tracing_buffers.hpp).
using VplSourceBuffers = VplSourceSet<BufferView>;

// What one tracing writes. The VPLs come out ordered by path, then bounce: the seed fixes the
// order as well as the set.
template <class BufferT>
struct VplTracingSet {
    BufferT vpls;     // Vpl[capacity]: the first `count` are valid after the pass
    BufferT bounces;  // uint32_t[capacity]: the bounce (1 = first surface hit) of each VPL
    BufferT count;    // VplCountBuffer: the number of VPLs, and of paths cut short
    // Scratch: each path's VPLs at fixed slots (Vpl[capacity]), its VPL count (uint32_t[paths]),
    // and per block of vpl_tracing_block_size paths its VPLs, then its first output slot.
    BufferT path_vpls;
    BufferT path_counts;
    BufferT block_vpls;

    operator VplTracingSet<BufferView>() const requires(!std::is_same_v<BufferT, BufferView>) {
        return {vpls, bounces, count, path_vpls, path_counts, block_vpls};
    }
};
// As views; the runtime's VplTracingOutput owns them.
using VplTracingBuffers = VplTracingSet<BufferView>;

// Paths per block of the packing (the workgroup size of vpl_block_counts.comp and compact_vpls.comp).
uint32_t vpl_tracing_block_size();

// Throws Error for paths or max_bounces 0, max_bounces 2^32 - 1, or paths x max_bounces above 2^32 - 1.
uint32_t vpl_capacity(const VplTracingOptions& options);

// Bytes of each VplTracingBuffers buffer for `options` (capacity = vpl_capacity(options)).
struct VplTracingRequirements {
    uint32_t capacity = 0;
    uint64_t vpls_bytes = 0;
    uint64_t bounces_bytes = 0;
    uint64_t count_bytes = 0;
    uint64_t path_vpls_bytes = 0;
    uint64_t path_counts_bytes = 0;
    uint64_t block_vpls_bytes = 0;
};
VplTracingRequirements vpl_tracing_requirements(const VplTracingOptions& options);

// Adds the passes "vpl count clear", "trace vpls" (each path's VPLs to its fixed slots), then
// "vpl block counts", "vpl block offsets" and "compact vpls" (a stable compaction by path): reads
// the BVH and `sources`, writes `output` (count cleared first). Every buffer of `output` must
// hold what vpl_tracing_requirements(options) says, each source buffer its count's records, and
// triangle_count must be >= 1 (Error otherwise); paths must fit one dispatch (Error). The VPL
// count is word 0 of output.count: ElementCount::on_gpu(output.count, 0, capacity) hands it to
// the key, leaf and tree passes without a read-back.
void add_trace_vpls_passes(Device& device, StepList& passes, const BvhBuffers& bvh, const VplSourceBuffers& sources,
                           const VplTracingOptions& options, const VplTracingBuffers& output);

// The packing alone (add_trace_vpls_passes records it after "trace vpls"): "vpl block counts",
// "vpl block offsets", "compact vpls". Reads output.path_vpls (path p's k-th VPL at slot
// p x max_bounces + k) and output.path_counts, writes output.vpls and output.bounces in path
// order, then bounce, and output.count's VPL count (its cut_short is left as it is).
void add_pack_vpls_passes(Device& device, StepList& passes, const VplTracingOptions& options,
                          const VplTracingBuffers& output);

}  // namespace vplkit::stages
