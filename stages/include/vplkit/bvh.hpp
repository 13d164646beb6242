#pragma once
// The BVH over the scene's triangles that every visibility query traverses
// (shaders/include/vplkit/bvh.glsl), built on the host (the GPU build: stages/bvh_gpu_build.hpp).
//
// Why a binned SAH build on the host rather than an LBVH on the GPU: the scenes are static, so
// the tree is built once per scene load, and what matters is the cost of the many millions of
// shadow rays traced through it every frame. Shadow rays towards VPLs are incoherent (origins
// and directions spread over the whole scene), so each ray pays for every box it enters, and a
// SAH tree's boxes are the ones that minimize that expected cost, where an LBVH (Karras 2012)
// splits at Morton-code bits wherever they fall (Karras and Aila 2013 use LBVH as the
// fast-to-build, slow-to-trace end of their comparison). A binned build costs O(n log n) and
// is paid once per scene load: Sponza's 262k triangles take 0.35-0.5 s on one core of the
// 2-core development machine (261645 nodes, depth 28). The GPU LBVH (stages/bvh_gpu_build.hpp)
// builds and refits the same layout on the device, for geometry that moves; its trees cost
// 1.2-1.3x this builder's SAH (`vplkit bench bvh`), and this one stays the tests' reference.
//
// Build (Wald 2007, "On fast Construction of SAH-based Bounding Volume Hierarchies"): at each
// node the triangle centroids are binned into `bins` equal slabs per axis, and the split between
// two bins with the least SAH cost (MacDonald and Booth 1990)
//     C = traversal_cost + triangle_cost * (A_left * N_left + A_right * N_right) / A_node
// is taken; a node of at most max_leaf_triangles becomes a leaf when its cost
// triangle_cost * N is not above the best split's. Constants: traversal_cost = triangle_cost = 1
// (a 32-byte node visit and a 48-byte watertight triangle test cost about the same on a GPU,
// where both are dominated by the memory fetch), 32 bins, at most 4 triangles per leaf. The
// choice is not delicate: on Sponza, triangle_cost 0.5 .. 1.5 changes the box and triangle tests
// per ray by under 2%, and 16 or 64 bins by under 5%.
//
// Depth cap: no leaf is deeper than max_depth (<= kBvhMaxDepth, the traversal's stack size), by
// construction: a SAH split is only taken when both children can still be finished by median
// splits within the remaining levels (a node of n triangles needs ceil(log2(n / leaf size))
// more levels); where none can, the node is split at the object median of its longest
// centroid axis, which always fits.
//
// Degenerate triangles (zero area: the cross product of two edges, in double precision, is
// exactly zero) are left out of the tree, and counted: they have no area that a ray could hit,
// while the float test, working on rounded projections, might report a spurious hit on one. Non-finite vertices, and
// coordinates of 2^32 or more in magnitude (the float intersection math would overflow), are refused with an Error
// naming the triangle. The empty scene (no triangles, or only degenerate ones) gives one leaf with no triangles: every
// ray misses it.
//
// Alpha-tested triangles in a subtree of their own (build_bvh_split): bvh.glsl compiles its
// alpha test into the triangle loop only for scenes that have such triangles (kBvhAlphaTest),
// and on lavapipe a branch in a loop costs every iteration under a lane mask whether or not a
// lane takes it, so with one tree every box and triangle a ray visits paid for the test: Sponza
// (3 masked materials, 34778 of its 262087 triangles tested), hybrid GI 3.8-4x the time of a
// copy with the masks set to OPAQUE. With the masked triangles in a second subtree, a ray first
// traverses the opaque subtree with the test compiled out of that loop, then the masked subtree
// with it (a closest-hit ray only up to the opaque hit; a shadow ray only when the opaque
// subtree did not stop it), so it pays for the test only in the few iterations it spends in the
// masked subtree: Sponza's GI then takes 0.95-1.1x the opaque copy's (one tree, with the same
// cheaper alpha test, 1.6-2x; hybrid, 8 spp, 4096 BRSM VPLs, 320x180, lavapipe). Layout:
// nodes[0] is an interior node over both subtrees; its first child, node 1, is the root of the
// opaque subtree (triangles [0, opaque_triangles)), its second child, masked_root, the root of
// the masked subtree (the remaining triangles). Every node is still a valid BVH node, so a
// traversal that ignores the split (from node 0, testing every triangle) gives the same answers.

#include "vplkit/shaders/types.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace vplkit {

// The traversal stack size of bvh.glsl (kBvhStackSize): no leaf is deeper (root at depth 0).
inline constexpr uint32_t kBvhMaxDepth = 32;
inline constexpr uint32_t kBvhMaxLeafTriangles = 4;
// BvhNode::meta of a leaf: kBvhLeafFlag | triangle count; of an interior node: the split axis.
inline constexpr uint32_t kBvhLeafFlag = 0x80000000u;
inline constexpr uint32_t kBvhCountMask = 0x7fffffffu;
// BvhHit::id and BvhHit::triangle of a miss; not allowed as a triangle id.
inline constexpr uint32_t kBvhNoHit = 0xffffffffu;
// Vertex coordinates must be smaller than this in magnitude (2^32).
inline constexpr float kBvhMaxCoordinate = 4294967296.0f;
// Boxes are padded outward by this fraction of the scene scale (see bvh.glsl: it covers the
// traversal's raised direction components and the rounding of the slab distances).
inline constexpr float kBvhBoxPadding = 1.0f / 1048576.0f;  // 2^-20
// offset_ray_origin in bvh.glsl: the offset is this times max(scene scale, |p|_max).
inline constexpr float kBvhOriginOffset = 1.0f / 65536.0f;  // 2^-16
// The scene scale never falls below this (empty scenes).
inline constexpr float kBvhMinScale = 1e-30f;
// Words at the start of the alpha buffer that hold the header bvh.glsl reads (where the nodes,
// triangles and alpha-test records are; stages::bvh_header), before any alpha-test record.
inline constexpr uint32_t kBvhHeaderWords = 12;

struct BvhBuildOptions {
    uint32_t bins = 32;                                  // 2..256 per axis
    uint32_t max_leaf_triangles = kBvhMaxLeafTriangles;  // 1..kBvhMaxLeafTriangles
    uint32_t max_depth = kBvhMaxDepth;                   // 1..kBvhMaxDepth
    float traversal_cost = 1.0f;                         // > 0
    float triangle_cost = 1.0f;                          // > 0
};

struct Bvh {
    // Depth-first: nodes[0] is the root, an interior node's first child follows it.
    std::vector<shaders::BvhNode> nodes;
    // In leaf order; empty for an empty scene (upload_bvh still makes a non-empty buffer).
    std::vector<shaders::BvhTriangle> triangles;
    // The alpha-test records of bvh_alpha_test.glsl (BvhTriangle::alpha points into them) after
    // kBvhHeaderWords words of header (of which the host sets word 0, the masked subtree's root;
    // the upload the rest); empty when every triangle is opaque (build_bvh leaves it so;
    // vplkit::add_alpha_tests fills it).
    std::vector<uint32_t> alpha;

    uint32_t input_triangles = 0;       // triangles given to build_bvh
    uint32_t degenerate_triangles = 0;  // of those, left out for zero area
    uint32_t leaf_count = 0;
    uint32_t depth = 0;          // of the deepest leaf (the root is at depth 0)
    uint32_t median_splits = 0;  // SAH splits replaced by median splits to respect max_depth
    // The largest coordinate magnitude of the (padded) root box, at least kBvhMinScale: what
    // bvh_scene_scale() in bvh.glsl returns, the scale offsets and tolerances are relative to.
    float scene_scale = kBvhMinScale;
    // Expected cost of a random ray that meets the root box (the SAH of the whole tree, in the
    // units of the build options' costs).
    double sah_cost = 0.0;
    // The split layout (build_bvh_split, see above): the masked subtree's root, 0 when the tree
    // is not split (no masked triangle, or only masked ones); the opaque subtree's triangle count.
    uint32_t masked_root = 0;
    uint32_t opaque_triangles = 0;
};

// Builds the BVH of `vertices.size() / 3` triangles (vertices 3i, 3i+1, 3i+2 are triangle i,
// world space). `triangle_ids`, when not empty, gives each triangle the id the traversal reports
// (one per triangle, none equal to kBvhNoHit); otherwise a triangle's id is its index i.
// Throws vplkit::Error for a vertex count that is not a multiple of 3, a wrong number of ids,
// a reserved id, a non-finite or out-of-range vertex (naming the triangle), or bad options.
Bvh build_bvh(std::span<const glm::vec3> vertices, std::span<const uint32_t> triangle_ids = {},
              const BvhBuildOptions& options = {});

// build_bvh with the triangles where masked[i] != 0 (one flag per triangle) in a subtree of their
// own (the split layout above), each subtree at most max_depth - 1 deep below the common root.
// When no triangle or every triangle is masked, or the deeper subtree would not fit below the
// common root within max_depth, the result is build_bvh's (masked_root = 0). Throws what
// build_bvh throws, and for a wrong number of flags.
Bvh build_bvh_split(std::span<const glm::vec3> vertices, std::span<const uint8_t> masked,
                    std::span<const uint32_t> triangle_ids = {}, const BvhBuildOptions& options = {});

inline bool bvh_is_leaf(const shaders::BvhNode& node) {
    return (node.meta & kBvhLeafFlag) != 0;
}
inline uint32_t bvh_leaf_triangles(const shaders::BvhNode& node) {
    return node.meta & kBvhCountMask;
}

}  // namespace vplkit
