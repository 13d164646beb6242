#pragma once
// The triangle BVH built on the GPU from the kit's own parts, in the layout every ray query
// traverses (shaders/include/vplkit/bvh.glsl), and its refit when only vertex positions move.
// The host build (vplkit/bvh.hpp, binned SAH) stays the renderer's BVH and the tests' reference.
//
// Build (Karras 2012, "Maximizing Parallelism in the Construction of BVHs, Octrees, and k-d
// Trees"; shaders/bvh/bvh_build_*.comp, layout in shaders/include/vplkit/bvh_build.glsl):
//   1. bounds    the box of the triangle centroids and the largest coordinate magnitude;
//   2. keys      30-bit Morton codes of the centroids, the triangle index as value;
//   3. sort      the kit's radix sort (RadixSorter, 30 key bits: 4 passes of 8 bits), stable,
//                so equal codes stay in input order;
//   4. hierarchy one thread per internal node: its range and split by binary searches on the
//                common prefix of the codes, a code's sorted position breaking ties;
//   5. depths    each node's depth by walking up its parent pointers, and its kind in the
//                output tree: subtrees of at most max_leaf_triangles collapse into one leaf;
//                a node at max_depth becomes a leaf of its whole subtree (a capped leaf);
//   6. leaves    each leaf's triangles copied into leaf order, and its box;
//   7. levels    interior boxes, one dispatch per depth, deepest first (max_depth of them,
//                each reading a 4-byte level word a node, kept in the keys buffer):
//                no atomics-and-flags bottom-up walk, whose memory barriers in divergent flow
//                lavapipe does not honour;
//   8. write     each node's depth-first position (walking up: a right child follows its left
//                sibling's subtree) and its BvhNode there, boxes padded as the host pads them.
// Refit: steps 1, 6, 7 and 8 again, on the same topology, with the caller's new vertices.
//
// Depth: an LBVH is deeper than a SAH tree (one level per Morton bit where triangles cluster,
// plus the bits of positions where codes are equal), and the traversal's stack holds
// kBvhMaxDepth levels. Instead of refusing such trees, nodes at max_depth become leaves of all
// the triangles below them: the traversal stays correct, and BvhBuildInfo::capped_leaves and
// largest_leaf say how many rays pay for long leaves. The info buffer also reports the depth
// the uncapped LBVH would have had (lbvh_depth).
//
// Input: the caller's triangles as BvhTriangle records (v0, v1, v2, id, alpha) in any order,
// already checked as build_bvh checks them (finite, below kBvhMaxCoordinate, no reserved id)
// and without zero-area ones, which the host build leaves out (the runtime's GpuBvhBuild does
// all that). Alpha-tested triangles (alpha != 0) go to a subtree of their own, as
// build_bvh_split puts them (vplkit/bvh.hpp's split layout: node 1 the opaque subtree, the
// root's second child the masked one), when both kinds exist; the build writes that root into
// word 0 of the caller's alpha records (BvhGpuBuildBuffers::alpha; 0 for one tree).

#include "vplkit/bvh.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/device.hpp"
#include "vplkit/stages/radix_sort.hpp"
#include "vplkit/steps.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>

namespace vplkit::stages {

struct BvhGpuBuildOptions {
    uint32_t max_leaf_triangles = kBvhMaxLeafTriangles;  // 1..kBvhMaxLeafTriangles
    uint32_t max_depth = kBvhMaxDepth;                   // 1..kBvhMaxDepth
};

// Sort key bits the sorter must order by (RadixSortOptions::key_bits): the Morton code's 30,
// and above them the bit of alpha-tested triangles (4 passes of 8 bits).
inline constexpr uint32_t kBvhBuildKeyBits = 31;

struct BvhGpuBuildBuffers {
    BufferView input;        // BvhTriangle[count], the caller's order; read (a refit reads the new vertices here)
    BufferView nodes;        // BvhNode[2 count - 1]; written: the tree is its first BvhBuildInfo::node_count
    BufferView triangles;    // BvhTriangle[count]; written, in leaf order
    BufferView info;         // BvhBuildInfo (bvh_build.glsl); written, for the caller to read back
    BufferView build_nodes;  // BvhBuildNode[2 count - 1]; scratch, which a refit reads again
    BufferView build_links;  // BvhBuildLink[2 count - 1]; scratch, which a refit reads again
    BufferView keys;         // uint64_t[count]: the sort keys, then each node's level word; a refit reads it
    BufferView order;        // uint32_t[count]: the input triangle at each leaf-order position; a refit reads it
    // Optional: the caller's alpha-test records (bvh.glsl's bvh_alpha) that the input's alpha
    // fields point into; the build writes word 0 (the masked subtree's root, or 0). The rest of
    // the header (stages::bvh_header: where nodes and triangles are) is the caller's to write.
    BufferView alpha;
    // Read and write input, nodes, triangles, build_nodes and build_links at their device
    // addresses, not through bindings (bvh_build.glsl's kBvhBuildAddressed): required when one of
    // them is larger than maxStorageBufferRange (the build throws otherwise); their buffers then
    // need VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT. keys and order stay bound (the sort binds
    // them), which limits the build to maxStorageBufferRange / 8 triangles (16.7M on lavapipe).
    // Not the default: lavapipe loads through the addresses more slowly.
    bool addressed = false;
};

// Bytes of each buffer for `count` triangles.
struct BvhGpuBuildSizes {
    VkDeviceSize input = 0, nodes = 0, triangles = 0, info = 0, build_nodes = 0, build_links = 0, keys = 0, order = 0;
};
BvhGpuBuildSizes bvh_gpu_build_sizes(uint32_t count);

// Adds the build of the BVH over `count` >= 1 triangles. `sorter` sorts with at least
// kBvhBuildKeyBits key bits, holds count pairs, and outlives the recording. Throws Error for
// bad options, a count of 0 or above kBvhCountMask, a buffer that is too small, one past
// maxStorageBufferRange that must be bound (see `addressed`), or a sorter that does not fit.
void add_bvh_gpu_build_passes(Device& device, StepList& passes, RadixSorter& sorter, const BvhGpuBuildBuffers& buffers,
                              uint32_t count, const BvhGpuBuildOptions& options = {});

// Adds the refit of a tree that add_bvh_gpu_build_passes built over the same buffers and count:
// the input triangles hold new vertices (the same triangles, in the same order), the topology
// stays, every box and the leaf-order triangles are recomputed. `options` as at the build.
void add_bvh_gpu_refit_passes(Device& device, StepList& passes, const BvhGpuBuildBuffers& buffers, uint32_t count,
                              const BvhGpuBuildOptions& options = {});

}  // namespace vplkit::stages
