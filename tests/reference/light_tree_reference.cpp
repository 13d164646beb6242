#include "light_tree_reference.hpp"

#include <algorithm>
#include <bit>

namespace vplkit::reference {

uint32_t light_tree_leaf_count(uint32_t count) {
    return count <= 1 ? 1u : std::bit_ceil(count);
}

std::vector<LightTreeNode> light_tree(std::span<const LightTreeVpl> vpls) {
    const uint32_t count = uint32_t(vpls.size());
    const uint32_t leaf_count = light_tree_leaf_count(count);
    std::vector<LightTreeNode> nodes(2 * size_t(leaf_count) - 1);

    for (uint32_t i = 0; i < count; ++i) {
        LightTreeNode& leaf = nodes[leaf_count - 1 + i];
        leaf.empty = false;
        for (int axis = 0; axis < 3; ++axis) {
            leaf.box_min[axis] = vpls[i].position[axis];
            leaf.box_max[axis] = vpls[i].position[axis];
        }
        leaf.intensity = double(vpls[i].flux[0]) + double(vpls[i].flux[1]) + double(vpls[i].flux[2]);
        leaf.vpl_count = 1;
    }

    // Bottom-up, one parent from its two children.
    for (size_t n = leaf_count - 1; n-- > 0;) {
        const LightTreeNode& left = nodes[2 * n + 1];
        const LightTreeNode& right = nodes[2 * n + 2];
        LightTreeNode& node = nodes[n];
        node.height = left.height + 1;
        node.intensity = left.intensity + right.intensity;
        node.vpl_count = left.vpl_count + right.vpl_count;
        node.empty = left.empty && right.empty;
        if (left.empty) {
            node.box_min = right.box_min;
            node.box_max = right.box_max;
        } else if (right.empty) {
            node.box_min = left.box_min;
            node.box_max = left.box_max;
        } else {
            for (int axis = 0; axis < 3; ++axis) {
                node.box_min[axis] = std::min(left.box_min[axis], right.box_min[axis]);
                node.box_max[axis] = std::max(left.box_max[axis], right.box_max[axis]);
            }
        }
    }
    return nodes;
}

}  // namespace vplkit::reference
