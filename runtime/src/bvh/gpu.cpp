// Upload of a Bvh.

#include "vplkit/bvh_gpu.hpp"

#include "device_buffers.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/shaders/types.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace vplkit {

GpuBvh upload_bvh(Context& context, const Bvh& bvh) {
    if (bvh.nodes.empty()) {
        throw Error("BVH upload: the BVH has no nodes (not made by build_bvh?)");
    }
    GpuBvh gpu;
    gpu.node_count = uint32_t(bvh.nodes.size());
    gpu.triangle_count = uint32_t(bvh.triangles.size());
    gpu.scene_scale = bvh.scene_scale;
    // An empty scene's leaf references no triangle; the buffer holds one zeroed triangle only
    // because a Vulkan buffer cannot be empty.
    std::vector<shaders::BvhTriangle> empty_scene_triangle(bvh.triangles.empty() ? 1 : 0, shaders::BvhTriangle{});
    const auto& triangles = bvh.triangles.empty() ? empty_scene_triangle : bvh.triangles;
    const uint64_t node_bytes = uint64_t(bvh.nodes.size()) * sizeof(shaders::BvhNode);
    const uint64_t triangle_bytes = uint64_t(triangles.size()) * sizeof(shaders::BvhTriangle);
    // Past a binding's range, the traversal reads them at their addresses (slower on lavapipe).
    const uint64_t range = context.info().max_storage_buffer_range;
    const uint64_t alpha_bytes = uint64_t(std::max<size_t>(bvh.alpha.size(), kBvhHeaderWords)) * sizeof(uint32_t);
    gpu.addressed = node_bytes > range || triangle_bytes > range || alpha_bytes > range;
    gpu.nodes = create_bvh_buffer(context, node_bytes, "nodes", "BVH upload");
    gpu.triangles = create_bvh_buffer(context, triangle_bytes, "triangles", "BVH upload");
    gpu.nodes.upload(bvh.nodes);
    gpu.triangles.upload(triangles);
    gpu.alpha = upload_bvh_alpha(context, gpu.nodes, gpu.triangles, bvh.alpha, "BVH upload");
    gpu.alpha_tests = !bvh.alpha.empty();
    return gpu;
}

}  // namespace vplkit
