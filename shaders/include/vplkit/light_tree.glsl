#ifndef VPLKIT_LIGHT_TREE_GLSL
#define VPLKIT_LIGHT_TREE_GLSL

// The perfect binary light tree of real-time stochastic lightcuts (the RTSLC paper sec. 3.1): every
// leaf on the last level, no child pointers, a node is a bounding box and a total intensity.
//
// Index convention: heap order, root 0, children of node n at 2n+1 and 2n+2. Level l (root
// level 0) holds nodes [2^l - 1, 2^(l+1) - 1); with leaf_count = 2^L leaves (a power of two)
// leaf i is node leaf_count - 1 + i and the tree has 2 * leaf_count - 1 nodes. Leaf i is the
// i-th VPL of the sorted leaf array (tree/gather_leaves.comp); leaves i >= count are bogus.
//
// Bogus subtrees (only bogus leaves below) have vpl_count 0, intensity 0 and the empty box
// box_min = +FLT_MAX, box_max = -FLT_MAX. That box is the identity of the box union for every
// finite coordinate, so merging needs no branch and a bogus child never widens its parent, and
// it is finite: Vulkan lets a compiler assume no float is Inf or NaN unless the shader asks for
// SignedZeroInfNanPreserve, so an infinite sentinel could be optimized into anything. Anything
// that measures a box (distances, extents) must first skip nodes with vpl_count == 0: the empty
// box has max < min and its extent overflows.
//
// Real VPLs with zero flux are real leaves: vpl_count 1, their position as box, intensity 0.
// The box is geometry and does not depend on the flux; such a VPL is never sampled (weight 0),
// it only keeps its subtree's box honest. A subtree of only zero-flux VPLs is a dead branch
// (intensity 0, real box), which samplers handle as the RTSLC paper sec. 3.2 says.

struct LightTreeNode {
    vec3 box_min;     // smallest corner of the box around the node's real VPLs
    float intensity;  // summed light_tree_intensity() of the node's VPLs
    vec3 box_max;     // largest corner
    uint vpl_count;   // real VPLs below the node (1 or 0 at a leaf); 0 marks a bogus subtree
};                    // 32 bytes, so two nodes fill a 64-byte cache line (the RTSLC paper sec. 4)

const float kLightTreeFloatMax = 3.402823466e+38;  // FLT_MAX: the empty box's corners, negated for box_max

// The scalar a node stores and samplers weigh children by (the RTSLC paper eq. 1: I_j). The sum of the
// RGB flux rather than luminance: errors are measured on the three channels alike (RMSE, relMSE
// in DESIGN.md), and the sum is within a factor sqrt(3) of the channels' Euclidean norm for
// every colour, while luminance gives pure blue 7% of its weight and so undersamples it ~14x.
// It is zero only for black flux. Flux channels must be finite and >= 0 (the VPL generators'
// contract). Written as two explicit additions so the CPU reference can reproduce the rounding.
float light_tree_intensity(vec3 flux) {
    return (flux.r + flux.g) + flux.b;
}

LightTreeNode light_tree_empty_node() {
    return LightTreeNode(vec3(kLightTreeFloatMax), 0.0, vec3(-kLightTreeFloatMax), 0u);
}

bool light_tree_is_bogus(LightTreeNode node) {
    return node.vpl_count == 0u;
}

// The node over `left` and `right` (left first: the intensity sum is rounded in tree order, so a
// tree built level by level and one built by groups of levels are bit for bit the same).
LightTreeNode light_tree_merge(LightTreeNode left, LightTreeNode right) {
    return LightTreeNode(min(left.box_min, right.box_min), left.intensity + right.intensity,
                         max(left.box_max, right.box_max), left.vpl_count + right.vpl_count);
}

uint light_tree_left_child(uint node) { return 2u * node + 1u; }
uint light_tree_right_child(uint node) { return 2u * node + 2u; }
uint light_tree_parent(uint node) { return (node - 1u) >> 1; }  // node > 0
uint light_tree_level(uint node) { return uint(findMSB(node + 1u)); }
uint light_tree_level_start(uint level) { return (1u << level) - 1u; }
uint light_tree_leaf_node(uint leaf_count, uint leaf) { return leaf_count - 1u + leaf; }
uint light_tree_node_leaf(uint leaf_count, uint node) { return node + 1u - leaf_count; }  // node is a leaf

// The first of the 2^depth descendants of `node` that lie `depth` levels below it; they are
// consecutive: (node + 1) * 2^depth - 1, ... , (node + 2) * 2^depth - 2.
uint light_tree_first_descendant(uint node, uint depth) { return ((node + 1u) << depth) - 1u; }

#endif
