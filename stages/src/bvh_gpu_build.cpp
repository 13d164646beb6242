// The GPU BVH build and refit (see vplkit/stages/bvh_gpu_build.hpp).

#include "vplkit/stages/bvh_gpu_build.hpp"

#include "vplkit/error.hpp"
#include "vplkit/shaders/bvh_build_bounds.hpp"
#include "vplkit/shaders/bvh_build_depths.hpp"
#include "vplkit/shaders/bvh_build_hierarchy.hpp"
#include "vplkit/shaders/bvh_build_keys.hpp"
#include "vplkit/shaders/bvh_build_leaves.hpp"
#include "vplkit/shaders/bvh_build_level.hpp"
#include "vplkit/shaders/bvh_build_write.hpp"
#include "vplkit/stages/binding_uses.hpp"

#include <cstddef>
#include <string>

namespace vplkit::stages {

namespace {

void validate(const BvhGpuBuildOptions& options, uint32_t count) {
    if (options.max_leaf_triangles < 1 || options.max_leaf_triangles > kBvhMaxLeafTriangles) {
        throw Error("GPU BVH build: max_leaf_triangles = " + std::to_string(options.max_leaf_triangles) +
                    " is outside 1.." + std::to_string(kBvhMaxLeafTriangles));
    }
    if (options.max_depth < 1 || options.max_depth > kBvhMaxDepth) {
        throw Error("GPU BVH build: max_depth = " + std::to_string(options.max_depth) + " is outside 1.." +
                    std::to_string(kBvhMaxDepth) + " (the traversal stack size)");
    }
    if (count == 0 || count >= kBvhCountMask) {
        throw Error("GPU BVH build: " + std::to_string(count) + " triangles, not in 1.." +
                    std::to_string(kBvhCountMask - 1));
    }
}

void check_size(const BufferView& view, VkDeviceSize bytes, const char* what) {
    if (!view || view.size < bytes) {
        throw Error(std::string("GPU BVH build: buffer '") + view.name + "' (" + what + ") holds " +
                    std::to_string(view ? view.size : 0) + " bytes, needs " + std::to_string(bytes));
    }
}

void check_buffers(const BvhGpuBuildBuffers& b, uint32_t count) {
    const BvhGpuBuildSizes s = bvh_gpu_build_sizes(count);
    check_size(b.input, s.input, "input triangles");
    check_size(b.nodes, s.nodes, "nodes");
    check_size(b.triangles, s.triangles, "triangles");
    check_size(b.info, s.info, "info");
    check_size(b.build_nodes, s.build_nodes, "build nodes");
    check_size(b.build_links, s.build_links, "build links");
    check_size(b.keys, s.keys, "keys");
    check_size(b.order, s.order, "order");
    if (b.alpha) {
        check_size(b.alpha, sizeof(uint32_t), "alpha records");
    }
}

// Clears what the bounds pass reduces into (an empty centroid box, scale 0) and, for a build,
// the statistics the depth and write passes gather.
// Reports the caller's names, not the bindings' (StepList::name).
void name_views(StepList& passes, const BvhGpuBuildBuffers& b) {
    passes.names({b.input, b.nodes, b.triangles, b.info, b.build_nodes, b.build_links, b.keys, b.order, b.alpha});
}

void add_clear(StepList& passes, const BufferView& info, bool statistics) {
    passes.add("bvh build clear", {Use::transfer_dst(info)}, [info, statistics](VkCommandBuffer cmd) {
        const VkDeviceSize lo = offsetof(shaders::BvhBuildInfo, centroid_lo);
        const VkDeviceSize hi = offsetof(shaders::BvhBuildInfo, centroid_hi);
        vkCmdFillBuffer(cmd, info.buffer, info.offset + lo, 3 * sizeof(uint32_t), 0xffffffffu);
        const VkDeviceSize end =
            statistics ? sizeof(shaders::BvhBuildInfo) : offsetof(shaders::BvhBuildInfo, lbvh_depth);
        vkCmdFillBuffer(cmd, info.buffer, info.offset + hi, end - hi, 0u);
    });
}

void add_bounds(Device& device, StepList& passes, const BvhGpuBuildBuffers& b, uint32_t count) {
    const auto& pipeline = device.pipeline<shaders::bvh_build_bounds::Pipeline>();
    shaders::bvh_build_bounds::Bindings bindings;
    bindings.input_triangles = b.input.descriptor();
    bindings.info = b.info.descriptor();
    shaders::bvh_build_bounds::Push push{};
    push.triangle_count = count;
    add_dispatch<shaders::bvh_build_bounds::Module>(passes, "bvh build bounds", pipeline, bindings, push, count);
}

// Steps 6 to 8, shared by the build and the refit.
void add_boxes_and_write(Device& device, StepList& passes, const BvhGpuBuildBuffers& b, uint32_t count,
                         const BvhGpuBuildOptions& options) {
    const uint32_t slots = 2 * count - 1;
    const auto& leaves = device.pipeline<shaders::bvh_build_leaves::Pipeline>();
    shaders::bvh_build_leaves::Bindings leaf_bindings;
    leaf_bindings.input_triangles = b.input.descriptor();
    leaf_bindings.order = b.order.descriptor();
    leaf_bindings.nodes = b.build_nodes.descriptor();
    leaf_bindings.links = b.build_links.descriptor();
    leaf_bindings.triangles = b.triangles.descriptor();
    shaders::bvh_build_leaves::Push leaf_push{};
    leaf_push.triangle_count = count;
    add_dispatch<shaders::bvh_build_leaves::Module>(passes, "bvh build leaves", leaves, leaf_bindings, leaf_push,
                                                    slots);

    // Interior nodes lie above max_depth (a node there is a leaf); none exist for one triangle.
    if (count > 1) {
        const auto& level = device.pipeline<shaders::bvh_build_level::Pipeline>();
        shaders::bvh_build_level::Bindings level_bindings;
        level_bindings.nodes = b.build_nodes.descriptor();
        level_bindings.links = b.build_links.descriptor();
        level_bindings.levels = b.keys.descriptor();
        for (uint32_t depth = options.max_depth; depth-- > 0;) {
            shaders::bvh_build_level::Push level_push{};
            level_push.internal_count = count - 1;
            level_push.depth = depth;
            add_dispatch<shaders::bvh_build_level::Module>(passes, "bvh build level " + std::to_string(depth), level,
                                                           level_bindings, level_push, count - 1);
        }
    }

    const auto& write = device.pipeline<shaders::bvh_build_write::Pipeline>();
    shaders::bvh_build_write::Bindings write_bindings;
    write_bindings.nodes = b.build_nodes.descriptor();
    write_bindings.links = b.build_links.descriptor();
    write_bindings.info = b.info.descriptor();
    write_bindings.bvh_nodes = b.nodes.descriptor();
    shaders::bvh_build_write::Push write_push{};
    write_push.triangle_count = count;
    add_dispatch<shaders::bvh_build_write::Module>(passes, "bvh build write", write, write_bindings, write_push, slots);
}

}  // namespace

BvhGpuBuildSizes bvh_gpu_build_sizes(uint32_t count) {
    const VkDeviceSize n = count;
    const VkDeviceSize slots = n > 0 ? 2 * n - 1 : 0;
    BvhGpuBuildSizes s;
    s.input = n * sizeof(shaders::BvhTriangle);
    s.nodes = slots * sizeof(shaders::BvhNode);
    s.triangles = n * sizeof(shaders::BvhTriangle);
    s.info = sizeof(shaders::BvhBuildInfo);
    s.build_nodes = slots * sizeof(shaders::BvhBuildNode);
    s.build_links = slots * sizeof(shaders::BvhBuildLink);
    s.keys = n * sizeof(uint64_t);
    s.order = n * sizeof(uint32_t);
    return s;
}

void add_bvh_gpu_build_passes(Device& device, StepList& passes, RadixSorter& sorter, const BvhGpuBuildBuffers& b,
                              uint32_t count, const BvhGpuBuildOptions& options) {
    validate(options, count);
    check_buffers(b, count);
    name_views(passes, b);
    if (sorter.options().key_bits < kBvhBuildKeyBits || sorter.max_count() < count) {
        throw Error("GPU BVH build: the sorter orders " + std::to_string(sorter.options().key_bits) +
                    " key bits of up to " + std::to_string(sorter.max_count()) + " pairs; the build needs " +
                    std::to_string(kBvhBuildKeyBits) + " bits of " + std::to_string(count));
    }
    const uint32_t slots = 2 * count - 1;

    add_clear(passes, b.info, true);
    add_bounds(device, passes, b, count);

    const auto& keys = device.pipeline<shaders::bvh_build_keys::Pipeline>();
    shaders::bvh_build_keys::Bindings key_bindings;
    key_bindings.input_triangles = b.input.descriptor();
    key_bindings.info = b.info.descriptor();
    key_bindings.keys = b.keys.descriptor();
    key_bindings.order = b.order.descriptor();
    shaders::bvh_build_keys::Push key_push{};
    key_push.triangle_count = count;
    add_dispatch<shaders::bvh_build_keys::Module>(passes, "bvh build keys", keys, key_bindings, key_push, count);

    sorter.add_pass(passes, b.keys, b.order, count, "bvh build sort");

    const auto& hierarchy = device.pipeline<shaders::bvh_build_hierarchy::Pipeline>();
    shaders::bvh_build_hierarchy::Bindings hierarchy_bindings;
    hierarchy_bindings.keys = b.keys.descriptor();
    hierarchy_bindings.nodes = b.build_nodes.descriptor();
    hierarchy_bindings.links = b.build_links.descriptor();
    shaders::bvh_build_hierarchy::Push hierarchy_push{};
    hierarchy_push.triangle_count = count;
    add_dispatch<shaders::bvh_build_hierarchy::Module>(passes, "bvh build hierarchy", hierarchy, hierarchy_bindings,
                                                       hierarchy_push, slots);

    const auto& depths = device.pipeline<shaders::bvh_build_depths::Pipeline>();
    shaders::bvh_build_depths::Bindings depth_bindings;
    depth_bindings.links = b.build_links.descriptor();
    depth_bindings.info = b.info.descriptor();
    depth_bindings.levels = b.keys.descriptor();
    shaders::bvh_build_depths::Push depth_push{};
    depth_push.triangle_count = count;
    depth_push.max_leaf_triangles = options.max_leaf_triangles;
    depth_push.max_depth = options.max_depth;
    add_dispatch<shaders::bvh_build_depths::Module>(passes, "bvh build depths", depths, depth_bindings, depth_push,
                                                    slots);

    add_boxes_and_write(device, passes, b, count, options);

    if (b.alpha) {
        // Word 0 of the alpha records: the masked subtree's root (bvh.glsl's bvh_masked_root).
        const BufferView info = b.info, alpha = b.alpha;
        passes.add("bvh build masked root", {Use::transfer_src(info), Use::transfer_dst(alpha)},
                   [info, alpha](VkCommandBuffer cmd) {
                       const VkBufferCopy copy{info.offset + offsetof(shaders::BvhBuildInfo, masked_root), alpha.offset,
                                               sizeof(uint32_t)};
                       vkCmdCopyBuffer(cmd, info.buffer, alpha.buffer, 1, &copy);
                   });
    }
}

void add_bvh_gpu_refit_passes(Device& device, StepList& passes, const BvhGpuBuildBuffers& b, uint32_t count,
                              const BvhGpuBuildOptions& options) {
    validate(options, count);
    check_buffers(b, count);
    name_views(passes, b);
    add_clear(passes, b.info, false);
    add_bounds(device, passes, b, count);
    add_boxes_and_write(device, passes, b, count, options);
}

}  // namespace vplkit::stages
