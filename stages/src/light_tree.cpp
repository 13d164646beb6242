#include "vplkit/stages/binding_uses.hpp"
#include "vplkit/stages/dispatch_groups.hpp"
#include "vplkit/stages/light_tree.hpp"

#include "vplkit/barriers.hpp"
#include "vplkit/error.hpp"
#include "vplkit/shaders/light_tree_leaves.hpp"
#include "vplkit/shaders/light_tree_levels.hpp"
#include "vplkit/stages/leaves.hpp"

#include <algorithm>
#include <bit>
#include <string>

namespace vplkit::stages {

namespace {

// The groups of internal levels, leaves first: for each, the complete source level and how many
// levels above it the group builds. Full groups at the bottom, where the levels are wide; the
// remainder goes to the top, where a level is a handful of nodes.
template <class Group>
void for_each_group(uint32_t leaf_count, uint32_t group_levels, Group group) {
    uint32_t source_level = uint32_t(std::countr_zero(leaf_count));
    while (source_level > 0) {
        const uint32_t levels = std::min(group_levels, source_level);
        group(source_level, levels);
        source_level -= levels;
    }
}

// Nodes of the `levels` levels above `source_level`: 2^source - 2^(source - levels).
uint32_t group_threads(uint32_t source_level, uint32_t levels) {
    return (1u << source_level) - (1u << (source_level - levels));
}

void check(const Device& device, uint32_t count, const LightTreeOptions& options) {
    if (count == 0 || count > kLightTreeMaxLeaves) {
        throw Error("light tree: count " + std::to_string(count) + " is outside 1.." +
                    std::to_string(kLightTreeMaxLeaves));
    }
    const Limits& info = device.limits();
    const uint32_t size = options.workgroup_size;
    if (size == 0 || size > info.max_workgroup_invocations || size > info.max_workgroup_size[0]) {
        throw Error("light tree: workgroup size " + std::to_string(size) + " is outside 1.." +
                    std::to_string(std::min(info.max_workgroup_invocations, info.max_workgroup_size[0])) +
                    " (the device's limit)");
    }
    if (options.group_levels > kLightTreeMaxGroupLevels) {
        throw Error("light tree: group_levels " + std::to_string(options.group_levels) + " is outside 0.." +
                    std::to_string(kLightTreeMaxGroupLevels) + " (0: the device's default)");
    }
    // The leaf dispatch is the widest: one thread per leaf (folded into rows past 65,535 workgroups).
    const uint64_t leaf_count = light_tree_leaf_count(count);
    shaders::light_tree_leaves::Pipeline leaves_grid;  // groups() needs only the workgroup size
    leaves_grid.workgroup_size = {size, 1, 1};
    check_dispatch_groups(leaves_grid, "light tree", uint32_t(leaf_count));
    const uint64_t node_bytes = uint64_t(light_tree_node_count(count)) * sizeof(shaders::LightTreeNode);
    const uint64_t leaf_bytes = leaf_count * sizeof(shaders::Vpl);
    if (std::max(node_bytes, leaf_bytes) > info.max_storage_buffer_range) {
        throw Error("light tree: " + std::to_string(count) + " VPLs need " + std::to_string(node_bytes) +
                    " bytes of nodes and " + std::to_string(leaf_bytes) +
                    " bytes of leaves; the device's storage buffer range is " +
                    std::to_string(info.max_storage_buffer_range));
    }
}

}  // namespace

uint32_t light_tree_default_group_levels(const Limits& limits) {
    return limits.cpu ? 1u : 4u;
}

uint32_t light_tree_leaf_count(uint32_t count) {
    return leaf_count(count);
}  // the leaves gather_leaves pads to

uint32_t light_tree_node_count(uint32_t count) {
    return 2 * light_tree_leaf_count(count) - 1;
}

uint32_t light_tree_dispatch_count(uint32_t count, uint32_t group_levels) {
    if (group_levels == 0 || group_levels > kLightTreeMaxGroupLevels) {
        throw Error("light tree: group_levels " + std::to_string(group_levels) + " is outside 1.." +
                    std::to_string(kLightTreeMaxGroupLevels));
    }
    uint32_t dispatches = 1;
    for_each_group(light_tree_leaf_count(count), group_levels, [&dispatches](uint32_t, uint32_t) { ++dispatches; });
    return dispatches;
}

void add_light_tree_levels_pass(Device& device, StepList& passes, const BufferView& nodes, uint32_t count,
                                const LightTreeOptions& options) {
    check(device, count, options);
    passes.name(nodes);  // report the caller's name, not the binding's
    const uint32_t leaf_count = light_tree_leaf_count(count);
    const VkDeviceSize node_bytes = VkDeviceSize(light_tree_node_count(count)) * sizeof(shaders::LightTreeNode);
    if (nodes.size < node_bytes) {
        throw Error("light tree: buffer '" + nodes.name + "' holds fewer than the " +
                    std::to_string(light_tree_node_count(count)) + " nodes of " + std::to_string(count) + " lights");
    }
    shaders::light_tree_levels::Spec levels_spec;
    levels_spec.local_size_x = options.workgroup_size;
    const auto& levels_pipeline = device.pipeline<shaders::light_tree_levels::Pipeline>(levels_spec);
    if (leaf_count == 1) {
        return;  // the root is the only leaf
    }
    shaders::light_tree_levels::Bindings level_bindings;
    level_bindings.nodes = nodes.descriptor(0, node_bytes);
    passes.add("light tree levels", binding_uses<shaders::light_tree_levels::Module>(level_bindings),
               [&levels_pipeline, bindings = level_bindings, leaf_count,
                group_levels = options.group_levels != 0
                                   ? options.group_levels
                                   : light_tree_default_group_levels(device.limits())](VkCommandBuffer cmd) {
                   bool first = true;
                   for_each_group(leaf_count, group_levels, [&](uint32_t source_level, uint32_t levels) {
                       if (!first) {
                           compute_barrier(cmd);  // the next group's source level is this group's top
                       }
                       first = false;
                       shaders::light_tree_levels::Push push{};
                       push.source_level = source_level;
                       push.levels = levels;
                       levels_pipeline.dispatch(cmd, bindings, push, group_threads(source_level, levels));
                   });
               });
}

void add_light_tree_passes(Device& device, StepList& passes, const BufferView& leaves, const BufferView& nodes,
                           const ElementCount& element_count, const LightTreeOptions& options) {
    const uint32_t count = element_count.capacity;
    check(device, count, options);
    passes.names({leaves, nodes});  // report the caller's names, not the bindings'
    const uint32_t leaf_count = light_tree_leaf_count(count);
    const VkDeviceSize leaf_bytes = VkDeviceSize(leaf_count) * sizeof(shaders::Vpl);
    const VkDeviceSize node_bytes = VkDeviceSize(light_tree_node_count(count)) * sizeof(shaders::LightTreeNode);
    if (leaves.size < leaf_bytes) {
        throw Error("light tree: buffer '" + leaves.name + "' holds fewer than the " + std::to_string(leaf_count) +
                    " leaves of " + std::to_string(count) + " VPLs");
    }
    if (nodes.size < node_bytes) {
        throw Error("light tree: buffer '" + nodes.name + "' holds fewer than the " +
                    std::to_string(light_tree_node_count(count)) + " nodes of " + std::to_string(count) + " VPLs");
    }

    shaders::light_tree_leaves::Spec leaves_spec;
    leaves_spec.local_size_x = options.workgroup_size;
    const auto& leaves_pipeline = device.pipeline<shaders::light_tree_leaves::Pipeline>(leaves_spec);

    shaders::light_tree_leaves::Bindings leaf_bindings;
    leaf_bindings.leaves = leaves.descriptor(0, leaf_bytes);
    leaf_bindings.nodes = nodes.descriptor(0, node_bytes);
    leaf_bindings.element_count_words = element_count.descriptor(leaves);
    shaders::light_tree_leaves::Push leaf_push{};
    leaf_push.count = count;
    leaf_push.leaf_count = leaf_count;
    leaf_push.count_word = element_count.push_word();
    add_dispatch<shaders::light_tree_leaves::Module>(passes, "light tree leaves", leaves_pipeline, leaf_bindings,
                                                     leaf_push, leaf_count);
    add_light_tree_levels_pass(device, passes, nodes, count, options);
}

}  // namespace vplkit::stages
