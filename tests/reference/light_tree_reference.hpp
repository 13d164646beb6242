#pragma once
// CPU reference for the perfect light tree (shaders/tree/light_tree_*.comp), written plainly in
// double precision: heap order (root 0, children 2n+1 and 2n+2), leaves on the last level, the
// `count` real VPLs first and bogus leaves up to the next power of two.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace vplkit::reference {

struct LightTreeVpl {
    std::array<float, 3> position{};
    std::array<float, 3> flux{};
};

struct LightTreeNode {
    bool empty = true;                // no real VPL below: no box
    std::array<double, 3> box_min{};  // meaningful only when !empty
    std::array<double, 3> box_max{};
    double intensity = 0.0;  // sum over the real VPLs below of flux r + g + b
    uint32_t vpl_count = 0;  // real VPLs below
    uint32_t height = 0;     // levels below the node (0 at a leaf)
};

// Leaves: `count` rounded up to a power of two (1 for count 1).
uint32_t light_tree_leaf_count(uint32_t count);

// The tree over `vpls` (all real), 2 * light_tree_leaf_count(vpls.size()) - 1 nodes.
// Zero-flux VPLs are real: they count and take part in the boxes.
std::vector<LightTreeNode> light_tree(std::span<const LightTreeVpl> vpls);

}  // namespace vplkit::reference
