#version 460
#extension GL_GOOGLE_include_directive : require
// Test-only: runs every helper of vplkit/light_tree.glsl on every node of a built tree, so the
// host can check the index convention and that merging a node's children gives the node.

#include "vplkit/light_tree.glsl"

layout(local_size_x = 64, local_size_x_id = 0) in;

layout(std430, set = 0, binding = 0) readonly buffer LightTreeNodeBuffer { LightTreeNode items[]; } nodes;

struct LightTreeHelperResult {
    uint level;
    uint level_start;       // light_tree_level_start(level)
    uint left;
    uint right;
    uint parent;            // 0 for the root
    uint first_grandchild;  // light_tree_first_descendant(node, 2)
    uint leaf;              // light_tree_node_leaf() for leaves, 0xffffffff otherwise
    uint leaf_node;         // light_tree_leaf_node(leaf_count, leaf) for leaves
    uint bogus;             // light_tree_is_bogus()
    uint _unused[3];
    LightTreeNode merged;   // light_tree_merge(left child, right child) for internal nodes
};

layout(std430, set = 0, binding = 1) writeonly buffer LightTreeHelperResultBuffer { LightTreeHelperResult items[]; } results;

layout(push_constant) uniform LightTreeHelpersPush {
    uint leaf_count;
} push;

void main() {
    uint node = gl_GlobalInvocationID.x;
    uint node_count = 2u * push.leaf_count - 1u;
    if (node >= node_count) {
        return;
    }
    LightTreeHelperResult r;
    r.level = light_tree_level(node);
    r.level_start = light_tree_level_start(r.level);
    r.left = light_tree_left_child(node);
    r.right = light_tree_right_child(node);
    r.parent = node == 0u ? 0u : light_tree_parent(node);
    r.first_grandchild = light_tree_first_descendant(node, 2u);
    bool is_leaf = node >= push.leaf_count - 1u;
    r.leaf = is_leaf ? light_tree_node_leaf(push.leaf_count, node) : 0xffffffffu;
    r.leaf_node = is_leaf ? light_tree_leaf_node(push.leaf_count, r.leaf) : 0xffffffffu;
    r.bogus = light_tree_is_bogus(nodes.items[node]) ? 1u : 0u;
    r._unused = uint[3](0u, 0u, 0u);
    r.merged = is_leaf ? light_tree_empty_node() : light_tree_merge(nodes.items[r.left], nodes.items[r.right]);
    results.items[node] = r;
}
