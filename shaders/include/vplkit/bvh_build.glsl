#ifndef VPLKIT_BVH_BUILD_GLSL
#define VPLKIT_BVH_BUILD_GLSL

// The GPU BVH build (stages/bvh_gpu_build.hpp; shaders/bvh/bvh_build_*.comp): a linear BVH
// after Karras 2012, "Maximizing Parallelism in the Construction of BVHs, Octrees, and k-d
// Trees", written out in the layout bvh.glsl traverses (depth-first, first child next).
//
// Working tree ("slots"): internal node i of the Karras tree is slot i (0 <= i < n - 1, the
// root is slot 0), the leaf of sorted triangle k is slot n - 1 + k (for n = 1 the single leaf
// is slot 0, the root as well). A slot covers the sorted triangles [first, first + count).
// Output: a slot is either hidden (inside a subtree collapsed into one leaf), an interior node
// or a leaf of the output tree (kind). A slot is kept when it is the root or its parent covers
// more than max_leaf_triangles and lies above max_depth; a kept slot is a leaf when it covers
// at most max_leaf_triangles, or lies at max_depth (a capped leaf: it then takes every
// triangle of its subtree, so the tree never outgrows the traversal's stack).
//
// Alpha-tested triangles (BvhTriangle::alpha != 0) get key bit kBvhBuildMaskedBit above the
// Morton code, so they sort after the opaque ones and, when both kinds exist, the root splits
// exactly between them: node 1 is the opaque subtree, the root's second child the masked one,
// vplkit/bvh.hpp's split layout (BvhBuildInfo::masked_root, for word 0 of bvh_alpha).

// Buffers past a binding's range (maxStorageBufferRange: 128 MiB on lavapipe, which the input
// and output triangles pass at 2.8M triangles, the nodes and links at 2.1M): with the
// specialization constant kBvhBuildAddressed (BvhGpuBuildBuffers::addressed) the per-triangle
// and per-slot buffers (input and output triangles, build nodes and links, output nodes) are
// read and written at the device addresses in the push block's `<binding name>_address` fields,
// as bvh.glsl reads an addressed BVH: each pipeline has one path, and the bindings stay bound
// (one record wide) so that a step's uses still name the buffers. Keys, order and levels (8
// bytes a triangle at most, within the range up to 16.7M triangles) stay bound.
// BVH_BUILD_GETTER(Type, name, Array) defines `Type name_get(uint i)`, record i of binding
// `name` or of the Array at its address (a function, not a ?: of the two loads, whose struct
// types glslang does not reconcile); BVH_BUILD_SET(name, Array, i, .member, value) writes one
// member (value without a top-level comma: a macro argument; an empty member writes the record).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

layout(constant_id = 1) const bool kBvhBuildAddressed = false;

#define BVH_BUILD_GETTER(Type, name, Array)                      \
    Type name##_get(uint index) {                               \
        if (kBvhBuildAddressed) {                               \
            return Array(push.name##_address).items[index];     \
        }                                                       \
        return name.items[index];                               \
    }
#define BVH_BUILD_SET(name, Array, index, member, value)          \
    if (kBvhBuildAddressed) {                                     \
        Array(push.name##_address).items[index] member = (value); \
    } else {                                                      \
        name.items[index] member = (value);                       \
    }

// The caller's triangles (bvh.glsl's BvhTriangle, the same struct: the generated types.hpp
// holds one of each name, and the two must agree).
struct BvhTriangle {
    vec3 v0;
    uint id;
    vec3 v1;
    uint alpha;
    vec3 v2;
};

// One slot's box (unpadded) and children (slots; kBvhBuildNone for a Karras leaf).
struct BvhBuildNode {
    vec3 lo;
    uint left;
    vec3 hi;
    uint right;
};

// One slot's place in the Karras tree and the output tree.
struct BvhBuildLink {
    uint parent;  // slot, kBvhBuildNone for the root
    uint first;   // first sorted triangle
    uint count;   // sorted triangles covered
    uint depth;   // in the Karras tree (root 0): also its depth in the output tree when kept
    uint size;    // output nodes in its output subtree (kept slots only)
    uint axis;    // interior: the axis of the Morton bit that splits it (left child below)
    uint kind;    // kBvhBuildHidden, kBvhBuildInterior or kBvhBuildLeaf
    uint split_bit;  // interior: the key bit its children differ in (kBvhBuildNone: only positions)
};

// What the build reports (read back by the caller), and the bounds its passes share.
struct BvhBuildInfo {
    uint centroid_lo[3];  // box of the triangle centroids, ordered floats (ordered_float.glsl)
    uint centroid_hi[3];
    uint scale;           // the largest vertex coordinate magnitude, float bits (non-negative
                          // floats order as their bits)
    uint lbvh_depth;      // the deepest leaf of the Karras tree, before collapsing and capping
    uint depth;           // the deepest leaf of the output tree (<= max_depth)
    uint node_count;      // output nodes
    uint leaf_count;      // output leaves
    uint largest_leaf;    // triangles in the largest output leaf
    uint capped_leaves;   // leaves at max_depth with more than max_leaf_triangles triangles
    float scene_scale;    // bvh_scene_scale() of the output tree (its padded root box)
    uint masked_root;     // the split layout's masked subtree root (vplkit/bvh.hpp), else 0
    uint unused;
};

layout(buffer_reference, std430, buffer_reference_align = 4) buffer BvhBuildTriangleArray {
    BvhTriangle items[];
};
layout(buffer_reference, std430, buffer_reference_align = 4) buffer BvhBuildNodeArray {
    BvhBuildNode items[];
};
layout(buffer_reference, std430, buffer_reference_align = 4) buffer BvhBuildLinkArray {
    BvhBuildLink items[];
};

const uint kBvhBuildNone = 0xffffffffu;
const uint kBvhBuildMaskedBit = 30u;
const uint kBvhBuildHidden = 0u;
const uint kBvhBuildInterior = 1u;
const uint kBvhBuildLeaf = 2u;
// Equal to vplkit::kBvhLeafFlag and kBvhBoxPadding (vplkit/bvh.hpp).
const uint kBvhBuildLeafFlag = 0x80000000u;
const float kBvhBuildBoxPadding = 9.5367431640625e-7;  // 2^-20
const float kBvhBuildMinScale = 1e-30;
// No walk up parent pointers is longer than the Karras tree is deep: its node prefixes grow by
// at least a bit a level, out of 30 Morton bits and 32 index bits.
const uint kBvhBuildMaxWalk = 64u;

// Box of one triangle.
void bvh_build_triangle_box(BvhTriangle tri, out vec3 lo, out vec3 hi) {
    lo = min(min(tri.v0, tri.v1), tri.v2);
    hi = max(max(tri.v0, tri.v1), tri.v2);
}

#endif
