#ifndef VPLKIT_TWO_LEVEL_LIGHT_TREE_GLSL
#define VPLKIT_TWO_LEVEL_LIGHT_TREE_GLSL

// The two-level light tree (the RTSLC paper sec. 3.1; built by vplkit/two_level_light_tree.hpp): one
// LightTreeNode array holding a top perfect tree first (root at 0, light_tree.glsl's heap order)
// and after it one bottom perfect tree per mesh light. Top leaf i is a copy of bottom tree i's root
// and LightTreeBottom i says where that tree lives. A sample descends the top tree to leaf i
// (rtslc_traverse_in with base 0), then bottom tree i from its root (base node_base) to leaf j,
// whose light is leaf_lights[light_base + j]: its pmf is the product of both paths' probabilities.

struct LightTreeBottom {
    uint node_base;    // the bottom tree's root: its nodes are items[node_base + n] for heap index n
    uint leaf_count;   // its leaves, a power of two
    uint light_base;   // its leaf j (< light_count) holds light leaf_lights[light_base + j]
    uint light_count;  // its real leaves
};

#endif
