#pragma once
// A Bvh (vplkit/bvh.hpp) on the GPU. The batch ray-query stage over it is in the stage library
// (stages/trace_rays.hpp, included here for its callers). Other stages bind the buffers with
// stages::bind_bvh: their shaders include vplkit/bvh.glsl, which declares `bvh_nodes`,
// `bvh_triangles` and `bvh_alpha`, so their generated Bindings have fields of those names.

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

// Device-local buffers with the BVH's nodes and triangles, and the alpha buffer with the header
// that says where they and the alpha-test records are. Nodes, triangles or alpha-test records
// past maxStorageBufferRange make the GpuBvh `addressed` (read at their device addresses), so
// device memory is the limit. Throws Error naming the buffer and its size when it exceeds the
// device's largest buffer or allocation, or does not fit in the device memory left.
GpuBvh upload_bvh(Context& context, const Bvh& bvh);

// The ray-query stage under the names its callers use (it takes a GpuBvh: GpuBvh converts).
using stages::add_trace_rays_pass;
using stages::TraceMode;

}  // namespace vplkit
