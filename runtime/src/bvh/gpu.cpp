// Upload of a Bvh and the batch ray-query pass.

#include "vplkit/bvh_gpu.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/trace_closest.hpp"
#include "vplkit/shaders/trace_occlusion.hpp"

#include <string>
#include <vector>

namespace vplkit {

namespace {

void check_range(const Context& context, uint64_t bytes, const char* what) {
    const uint64_t limit = context.info().max_storage_buffer_range;
    if (bytes > limit) {
        throw Error(std::string("BVH upload: the ") + what + " need " + std::to_string(bytes) +
                    " bytes, more than this device's maxStorageBufferRange of " + std::to_string(limit));
    }
}

}  // namespace

GpuBvh upload_bvh(Context& context, const Bvh& bvh) {
    if (bvh.nodes.empty()) {
        throw Error("BVH upload: the BVH has no nodes (not made by build_bvh?)");
    }
    GpuBvh gpu;
    gpu.node_count = uint32_t(bvh.nodes.size());
    gpu.triangle_count = uint32_t(bvh.triangles.size());
    gpu.scene_scale = bvh.scene_scale;
    const uint64_t node_bytes = uint64_t(bvh.nodes.size()) * sizeof(shaders::BvhNode);
    // An empty scene's leaf references no triangle; the buffer holds one zeroed triangle only
    // because a binding needs a buffer.
    std::vector<shaders::BvhTriangle> empty_scene_triangle(bvh.triangles.empty() ? 1 : 0, shaders::BvhTriangle{});
    const auto& triangles = bvh.triangles.empty() ? empty_scene_triangle : bvh.triangles;
    const uint64_t triangle_bytes = uint64_t(triangles.size()) * sizeof(shaders::BvhTriangle);
    check_range(context, node_bytes, "nodes");
    check_range(context, triangle_bytes, "triangles");
    gpu.nodes = Buffer::create(context, node_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "bvh nodes");
    gpu.triangles = Buffer::create(context, triangle_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device,
                                   "bvh triangles");
    gpu.nodes.upload(bvh.nodes);
    gpu.triangles.upload(triangles);
    return gpu;
}

void add_trace_rays_pass(Context& context, PassList& passes, const GpuBvh& bvh, const Buffer& rays,
                         Buffer& results, uint32_t ray_count, TraceMode mode) {
    const char* name = mode == TraceMode::closest_hit ? "trace closest" : "trace occlusion";
    if (ray_count == 0) {
        throw Error(std::string(name) + ": no rays");
    }
    const uint64_t result_size = mode == TraceMode::closest_hit ? sizeof(shaders::BvhHit) : sizeof(uint32_t);
    if (rays.size() < uint64_t(ray_count) * sizeof(shaders::BvhRay)) {
        throw Error(std::string(name) + ": buffer '" + rays.name() + "' holds fewer than " + std::to_string(ray_count) +
                    " rays");
    }
    if (results.size() < uint64_t(ray_count) * result_size) {
        throw Error(std::string(name) + ": buffer '" + results.name() + "' holds fewer than " +
                    std::to_string(ray_count) + " results");
    }
    const uint64_t group_size = mode == TraceMode::closest_hit ? shaders::trace_closest::kWorkgroupSize[0]
                                                               : shaders::trace_occlusion::kWorkgroupSize[0];
    const uint64_t max_rays = group_size * context.info().max_workgroup_count[0];
    if (ray_count > max_rays) {
        throw Error(std::string(name) + ": " + std::to_string(ray_count) + " rays, one dispatch holds at most " +
                    std::to_string(max_rays) + " on this device");
    }
    const Buffer& nodes = bvh.nodes;
    const Buffer& triangles = bvh.triangles;
    std::vector<Use> uses = {Use::read(nodes), Use::read(triangles), Use::read(rays), Use::write(results)};
    if (mode == TraceMode::closest_hit) {
        const auto& pipeline = context.pipeline<shaders::trace_closest::Pipeline>();
        passes.add(name, std::move(uses), [&pipeline, &nodes, &triangles, &rays, &results, ray_count](VkCommandBuffer cmd) {
            shaders::trace_closest::Bindings bindings;
            bindings.bvh_nodes = nodes.descriptor();
            bindings.bvh_triangles = triangles.descriptor();
            bindings.rays = rays.descriptor();
            bindings.hits = results.descriptor();
            shaders::trace_closest::Push push{};
            push.ray_count = ray_count;
            pipeline.dispatch(cmd, bindings, push, ray_count);
        });
    } else {
        const auto& pipeline = context.pipeline<shaders::trace_occlusion::Pipeline>();
        passes.add(name, std::move(uses), [&pipeline, &nodes, &triangles, &rays, &results, ray_count](VkCommandBuffer cmd) {
            shaders::trace_occlusion::Bindings bindings;
            bindings.bvh_nodes = nodes.descriptor();
            bindings.bvh_triangles = triangles.descriptor();
            bindings.rays = rays.descriptor();
            bindings.occlusion = results.descriptor();
            shaders::trace_occlusion::Push push{};
            push.ray_count = ray_count;
            pipeline.dispatch(cmd, bindings, push, ray_count);
        });
    }
}

}  // namespace vplkit
