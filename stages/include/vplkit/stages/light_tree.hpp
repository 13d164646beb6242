#pragma once
// The perfect binary light tree of real-time stochastic lightcuts (the RTSLC paper sec. 3.1 and 4) over
// the sorted leaf array (gather_leaves.comp): light_tree_leaves.comp writes the leaf level, then
// light_tree_levels.comp builds the internal levels in groups of `group_levels` levels, each
// group in one dispatch straight from the level below it.
//
// Layout (shaders/include/vplkit/light_tree.glsl): heap order, root 0, children 2n+1 and 2n+2,
// leaf i at node leaf_count - 1 + i, where leaf_count = bit_ceil(count) (1 for count 1).
// A node (shaders::LightTreeNode, 32 bytes) holds box_min, intensity (sum of the RGB flux),
// box_max and vpl_count (real VPLs below it). Bogus subtrees have vpl_count 0, intensity 0 and
// the empty box [+FLT_MAX, -FLT_MAX]; no field is ever Inf or NaN for finite input.

#include "vplkit/stages/device.hpp"
#include "vplkit/stages/element_count.hpp"
#include "vplkit/steps.hpp"

#include <cstdint>

namespace vplkit::stages {

// Most levels one group may build (the stack of partial sums in light_tree_levels.comp).
inline constexpr uint32_t kLightTreeMaxGroupLevels = 8;
// Most leaves a tree may have: its 2 * leaf_count - 1 node indices fit in 32 bits.
inline constexpr uint32_t kLightTreeMaxLeaves = 1u << 31;

struct LightTreeOptions {
    // Threads per workgroup of both shaders (one thread per node written).
    uint32_t workgroup_size = 256;
    // Levels built per dispatch, 1..kLightTreeMaxGroupLevels, or 0 for
    // light_tree_default_group_levels(device). A node `d` levels above its group's source level
    // reads 2^d nodes, so a group of g levels reads the source level g times but saves g - 1
    // barriers. The tree is the same, bit for bit, whatever the group size.
    uint32_t group_levels = 0;
};

// The group size add_light_tree_passes uses when LightTreeOptions::group_levels is 0.
// CPU devices: 1 (level by level). Measured on lavapipe (2 cores), where a dispatch costs
// ~30 us and re-reading the source level costs more than the barriers it saves: levels of
// 1M leaves take 16 ms level by level, 21 / 28 / 39 ms in groups of 2 / 3 / 4; only at 4096
// leaves do groups of 2-3 win (0.33 vs 0.45 ms).
// Other devices: 4, not measured yet: on a GPU each barrier drains the whole device while
// the re-reads of a source level mostly hit the cache; the RTSLC paper sec. 4 builds in groups.
uint32_t light_tree_default_group_levels(const Limits& limits);

// Leaves of the tree over `count` VPLs: stages::leaf_count (leaves.hpp), the gather's padding.
uint32_t light_tree_leaf_count(uint32_t count);
// Nodes of the tree over `count` VPLs: 2 * light_tree_leaf_count(count) - 1.
uint32_t light_tree_node_count(uint32_t count);
// Dispatches add_light_tree_passes records with groups of `group_levels` (1..8) levels: one for
// the leaves, one per group. Throws vplkit::Error for a group size out of range.
uint32_t light_tree_dispatch_count(uint32_t count, uint32_t group_levels);

// Adds the passes "light tree leaves" and "light tree levels" (the groups, with compute
// barriers between them). `leaves` holds light_tree_leaf_count(count) Vpls in sorted order, the
// first `count` real; `nodes` receives light_tree_node_count(count) LightTreeNodes. With a GPU
// count, the sizes are those of its capacity and the leaves past the count become empty nodes.
// Throws vplkit::Error for count 0 or above kLightTreeMaxLeaves, bad options, buffers too small,
// or a tree the device cannot dispatch or address in one storage buffer.
void add_light_tree_passes(Device& device, StepList& passes, const BufferView& leaves, const BufferView& nodes,
                           const ElementCount& count, const LightTreeOptions& options = {});

// Adds only the pass "light tree levels" (nothing for one leaf): the internal levels over a leaf
// level someone else wrote into `nodes` (light_tree_node_count(count) nodes; the leaves at
// leaf_count - 1 + i). add_light_tree_passes is the leaves pass followed by this one; the tree over
// a scene's lights (scene_light_tree.hpp) writes its own leaves. Throws as add_light_tree_passes.
void add_light_tree_levels_pass(Device& device, StepList& passes, const BufferView& nodes, uint32_t count,
                                const LightTreeOptions& options = {});

}  // namespace vplkit::stages
