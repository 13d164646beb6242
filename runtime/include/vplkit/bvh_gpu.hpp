#pragma once
// A Bvh (vplkit/bvh.hpp) on the GPU. The batch ray-query stage over it is in the stage library
// (stages/trace_rays.hpp, included here for its callers). Other stages bind the two buffers
// themselves: their shaders include vplkit/bvh.glsl, which declares `bvh_nodes` and
// `bvh_triangles`, so their generated Bindings have fields of those names:
//     bindings.bvh_nodes = gpu_bvh.nodes.descriptor();
//     bindings.bvh_triangles = gpu_bvh.triangles.descriptor();
//     bindings.bvh_alpha = gpu_bvh.alpha.descriptor();

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit/stages/trace_rays.hpp"

#include <cstdint>

namespace vplkit {

class Context;

struct GpuBvh {
    Buffer nodes;      // BvhNode[node_count]
    Buffer triangles;  // BvhTriangle[max(triangle_count, 1)]: never empty (Vulkan has no empty buffers)
    Buffer alpha;      // Bvh::alpha, or one zero word
    uint32_t node_count = 0;
    uint32_t triangle_count = 0;       // 0 for an empty scene
    float scene_scale = kBvhMinScale;  // Bvh::scene_scale, for offset_ray_origin
    bool alpha_tests = false;          // Bvh::alpha is not empty

    // As the stages take it.
    operator stages::BvhBuffers() const {
        return {nodes, triangles, node_count, triangle_count, scene_scale, alpha, alpha_tests};
    }
};

// Device-local buffers with the BVH's nodes and triangles. Throws Error when a buffer would
// exceed the device's maxStorageBufferRange (naming both sizes).
GpuBvh upload_bvh(Context& context, const Bvh& bvh);

// The ray-query stage under the names its callers use (it takes a GpuBvh: GpuBvh converts).
using stages::add_trace_rays_pass;
using stages::TraceMode;

}  // namespace vplkit
