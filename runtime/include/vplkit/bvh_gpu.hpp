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

// The BVH's buffers, owned (stages/bvh_buffers.hpp's BvhSet; converts to the BvhBuffers the
// stages take). upload_bvh and GpuBvhBuild fill every field.
struct GpuBvh : stages::BvhSet<Buffer> {};

// Device-local buffers with the BVH's nodes and triangles. Throws Error when a buffer would
// exceed the device's maxStorageBufferRange (naming both sizes).
GpuBvh upload_bvh(Context& context, const Bvh& bvh);

// The ray-query stage under the names its callers use (it takes a GpuBvh: GpuBvh converts).
using stages::add_trace_rays_pass;
using stages::TraceMode;

}  // namespace vplkit
