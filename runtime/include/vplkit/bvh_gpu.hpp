#pragma once
// A Bvh (vplkit/bvh.hpp) on the GPU, and the batch ray-query stage over it
// (shaders/bvh/trace_closest.comp, trace_occlusion.comp). Other stages bind the two buffers
// themselves: their shaders include vplkit/bvh.glsl, which declares `bvh_nodes` and
// `bvh_triangles`, so their generated Bindings have fields of those names:
//     bindings.bvh_nodes = gpu_bvh.nodes.descriptor();
//     bindings.bvh_triangles = gpu_bvh.triangles.descriptor();

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/stages/bvh_buffers.hpp"

#include <cstdint>

namespace vplkit {

class Context;
class PassList;

struct GpuBvh {
    Buffer nodes;                 // BvhNode[node_count]
    Buffer triangles;             // BvhTriangle[max(triangle_count, 1)]: never empty (Vulkan has no empty buffers)
    uint32_t node_count = 0;
    uint32_t triangle_count = 0;  // 0 for an empty scene
    float scene_scale = kBvhMinScale;  // Bvh::scene_scale, for offset_ray_origin

    // As the stages take it.
    operator stages::BvhBuffers() const { return {nodes, triangles, node_count, triangle_count, scene_scale}; }
};

// Device-local buffers with the BVH's nodes and triangles. Throws Error when a buffer would
// exceed the device's maxStorageBufferRange (naming both sizes).
GpuBvh upload_bvh(Context& context, const Bvh& bvh);

enum class TraceMode {
    closest_hit,  // results: BvhHit[ray_count] (t, id, barycentrics, triangle; id kBvhNoHit on a miss)
    occlusion,    // results: uint32_t[ray_count], 1 when something lies strictly between tmin and tmax
};

// Adds the pass "trace closest" or "trace occlusion": one query per BvhRay in `rays`.
// Throws Error for ray_count 0, buffers smaller than ray_count elements, or more rays than one
// dispatch can hold (64 * maxComputeWorkGroupCount[0]).
void add_trace_rays_pass(Context& context, PassList& passes, const GpuBvh& bvh, const Buffer& rays,
                         Buffer& results, uint32_t ray_count, TraceMode mode);

}  // namespace vplkit
