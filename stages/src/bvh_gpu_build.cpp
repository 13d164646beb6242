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

#include <algorithm>
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

// A view that is bound (not read at its address) must fit a binding's range.
void check_range(const BufferView& view, uint64_t range, const char* what, const char* remedy) {
    if (view.size > range) {
        throw Error(std::string("GPU BVH build: buffer '") + view.name + "' (" + what + ", " +
                    std::to_string(view.size) + " bytes) is larger than a storage binding may be on this device " +
                    "(maxStorageBufferRange " + std::to_string(range) + "): " + remedy);
    }
}

void check_ranges(const BvhGpuBuildBuffers& b, uint64_t range) {
    if (!b.addressed) {
        const char* remedy = "read it at its device address (BvhGpuBuildBuffers::addressed)";
        check_range(b.input, range, "input triangles", remedy);
        check_range(b.nodes, range, "nodes", remedy);
        check_range(b.triangles, range, "triangles", remedy);
        check_range(b.build_nodes, range, "build nodes", remedy);
        check_range(b.build_links, range, "build links", remedy);
    }
    const char* bound = "the sort binds it: too many triangles for this device";
    check_range(b.keys, range, "keys", bound);
    check_range(b.order, range, "order", bound);
}

// A per-triangle or per-slot buffer as its shader takes it: the whole view bound, or, addressed,
// its device address (into `address`) and a binding of one record at the buffer's start, which
// nothing reads but which names the buffer among the step's uses (and needs no offset alignment).
VkDescriptorBufferInfo big_buffer(VkDevice device, const BvhGpuBuildBuffers& b, const BufferView& view,
                                  VkDeviceSize record, shaders::uvec2& address) {
    if (!b.addressed) return view.descriptor();
    VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    info.buffer = view.buffer;
    const VkDeviceAddress at = vkGetBufferDeviceAddress(device, &info) + view.offset;
    address = {uint32_t(at), uint32_t(at >> 32)};
    return {view.buffer, 0, std::min(view.offset + view.size, record)};
}

template <class Pipeline>
const Pipeline& build_pipeline(Device& device, const BvhGpuBuildBuffers& b) {
    typename Pipeline::Spec spec{};
    spec.kBvhBuildAddressed = b.addressed;
    return device.pipeline<Pipeline>(spec);
}

constexpr VkDeviceSize kTriangle = sizeof(shaders::BvhTriangle);
constexpr VkDeviceSize kBuildNode = sizeof(shaders::BvhBuildNode);
constexpr VkDeviceSize kBuildLink = sizeof(shaders::BvhBuildLink);

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
    const auto& pipeline = build_pipeline<shaders::bvh_build_bounds::Pipeline>(device, b);
    shaders::bvh_build_bounds::Push push{};
    push.triangle_count = count;
    shaders::bvh_build_bounds::Bindings bindings;
    bindings.input_triangles = big_buffer(device.device(), b, b.input, kTriangle, push.input_triangles_address);
    bindings.info = b.info.descriptor();
    add_dispatch<shaders::bvh_build_bounds::Module>(passes, "bvh build bounds", pipeline, bindings, push, count);
}

// Steps 6 to 8, shared by the build and the refit.
void add_boxes_and_write(Device& device, StepList& passes, const BvhGpuBuildBuffers& b, uint32_t count,
                         const BvhGpuBuildOptions& options) {
    const uint32_t slots = 2 * count - 1;
    const VkDevice vk = device.device();
    const auto& leaves = build_pipeline<shaders::bvh_build_leaves::Pipeline>(device, b);
    shaders::bvh_build_leaves::Push leaf_push{};
    leaf_push.triangle_count = count;
    shaders::bvh_build_leaves::Bindings leaf_bindings;
    leaf_bindings.input_triangles = big_buffer(vk, b, b.input, kTriangle, leaf_push.input_triangles_address);
    leaf_bindings.order = b.order.descriptor();
    leaf_bindings.nodes = big_buffer(vk, b, b.build_nodes, kBuildNode, leaf_push.nodes_address);
    leaf_bindings.links = big_buffer(vk, b, b.build_links, kBuildLink, leaf_push.links_address);
    leaf_bindings.triangles = big_buffer(vk, b, b.triangles, kTriangle, leaf_push.triangles_address);
    add_dispatch<shaders::bvh_build_leaves::Module>(passes, "bvh build leaves", leaves, leaf_bindings, leaf_push,
                                                    slots);

    // Interior nodes lie above max_depth (a node there is a leaf); none exist for one triangle.
    if (count > 1) {
        const auto& level = build_pipeline<shaders::bvh_build_level::Pipeline>(device, b);
        shaders::bvh_build_level::Push level_push{};
        level_push.internal_count = count - 1;
        shaders::bvh_build_level::Bindings level_bindings;
        level_bindings.nodes = big_buffer(vk, b, b.build_nodes, kBuildNode, level_push.nodes_address);
        level_bindings.links = big_buffer(vk, b, b.build_links, kBuildLink, level_push.links_address);
        level_bindings.levels = b.keys.descriptor();
        for (uint32_t depth = options.max_depth; depth-- > 0;) {
            level_push.depth = depth;
            add_dispatch<shaders::bvh_build_level::Module>(passes, "bvh build level " + std::to_string(depth), level,
                                                           level_bindings, level_push, count - 1);
        }
    }

    const auto& write = build_pipeline<shaders::bvh_build_write::Pipeline>(device, b);
    shaders::bvh_build_write::Push write_push{};
    write_push.triangle_count = count;
    shaders::bvh_build_write::Bindings write_bindings;
    write_bindings.nodes = big_buffer(vk, b, b.build_nodes, kBuildNode, write_push.nodes_address);
    write_bindings.links = big_buffer(vk, b, b.build_links, kBuildLink, write_push.links_address);
    write_bindings.info = b.info.descriptor();
    write_bindings.bvh_nodes = big_buffer(vk, b, b.nodes, sizeof(shaders::BvhNode), write_push.bvh_nodes_address);
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
    check_ranges(b, device.limits().max_storage_buffer_range);
    name_views(passes, b);
    if (sorter.options().key_bits < kBvhBuildKeyBits || sorter.max_count() < count) {
        throw Error("GPU BVH build: the sorter orders " + std::to_string(sorter.options().key_bits) +
                    " key bits of up to " + std::to_string(sorter.max_count()) + " pairs; the build needs " +
                    std::to_string(kBvhBuildKeyBits) + " bits of " + std::to_string(count));
    }
    const uint32_t slots = 2 * count - 1;

    add_clear(passes, b.info, true);
    add_bounds(device, passes, b, count);

    const VkDevice vk = device.device();
    const auto& keys = build_pipeline<shaders::bvh_build_keys::Pipeline>(device, b);
    shaders::bvh_build_keys::Push key_push{};
    key_push.triangle_count = count;
    shaders::bvh_build_keys::Bindings key_bindings;
    key_bindings.input_triangles = big_buffer(vk, b, b.input, kTriangle, key_push.input_triangles_address);
    key_bindings.info = b.info.descriptor();
    key_bindings.keys = b.keys.descriptor();
    key_bindings.order = b.order.descriptor();
    add_dispatch<shaders::bvh_build_keys::Module>(passes, "bvh build keys", keys, key_bindings, key_push, count);

    sorter.add_pass(passes, b.keys, b.order, count, "bvh build sort");

    const auto& hierarchy = build_pipeline<shaders::bvh_build_hierarchy::Pipeline>(device, b);
    shaders::bvh_build_hierarchy::Push hierarchy_push{};
    hierarchy_push.triangle_count = count;
    shaders::bvh_build_hierarchy::Bindings hierarchy_bindings;
    hierarchy_bindings.keys = b.keys.descriptor();
    hierarchy_bindings.nodes = big_buffer(vk, b, b.build_nodes, kBuildNode, hierarchy_push.nodes_address);
    hierarchy_bindings.links = big_buffer(vk, b, b.build_links, kBuildLink, hierarchy_push.links_address);
    add_dispatch<shaders::bvh_build_hierarchy::Module>(passes, "bvh build hierarchy", hierarchy, hierarchy_bindings,
                                                       hierarchy_push, slots);

    const auto& depths = build_pipeline<shaders::bvh_build_depths::Pipeline>(device, b);
    shaders::bvh_build_depths::Push depth_push{};
    depth_push.triangle_count = count;
    depth_push.max_leaf_triangles = options.max_leaf_triangles;
    depth_push.max_depth = options.max_depth;
    shaders::bvh_build_depths::Bindings depth_bindings;
    depth_bindings.links = big_buffer(vk, b, b.build_links, kBuildLink, depth_push.links_address);
    depth_bindings.info = b.info.descriptor();
    depth_bindings.levels = b.keys.descriptor();
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
    check_ranges(b, device.limits().max_storage_buffer_range);
    name_views(passes, b);
    add_clear(passes, b.info, false);
    add_bounds(device, passes, b, count);
    add_boxes_and_write(device, passes, b, count, options);
}

}  // namespace vplkit::stages
