#pragma once
// The BVH every ray-casting stage reads (shaders/include/vplkit/bvh.glsl): BvhNode[node_count]
// and BvhTriangle[max(triangle_count, 1)], as built by vplkit::build_bvh (runtime: bvh.hpp) and
// uploaded by the caller, and the alpha-test records (Bvh::alpha). Shaders that include bvh.glsl
// bind them as `bvh_nodes`, `bvh_triangles` and `bvh_alpha`.

#include "vplkit/stages/views.hpp"

#include <cstdint>
#include <type_traits>

namespace vplkit::stages {

// One definition for views (BvhBuffers, what the stages take) and owned buffers (the runtime's
// GpuBvh, vplkit/bvh_gpu.hpp): a set of buffers that convert to BufferView converts to the views.
template <class BufferT>
struct BvhSet {
    BufferT nodes;      // BvhNode[node_count]
    BufferT triangles;  // BvhTriangle[max(triangle_count, 1)]: never empty (Vulkan has no empty buffers)
    uint32_t node_count = 0;
    uint32_t triangle_count = 0;  // 0 for an empty scene (triangles then holds one unused record)
    float scene_scale = 1e-30f;   // Bvh::scene_scale: the largest coordinate magnitude, for ray-origin offsets
    // Bvh::alpha (at least one word: a zero when every triangle is opaque). Its word 0 is the
    // masked subtree's root of a split tree (vplkit/bvh.hpp), else 0: a foreign renderer's own
    // records keep word 0 at 0 unless it builds that layout.
    BufferT alpha;
    // Whether some triangle has an alpha-test record: false compiles the test out of the
    // traversal (bvh_spec), so opaque scenes trace as fast as without alpha tests.
    bool alpha_tests = true;

    operator BvhSet<BufferView>() const requires(!std::is_same_v<BufferT, BufferView>) {
        return {nodes, triangles, node_count, triangle_count, scene_scale, alpha, alpha_tests};
    }
};
using BvhBuffers = BvhSet<BufferView>;

// A shader's specialization with bvh.glsl's kBvhAlphaTest set from `bvh` (the shader must include
// bvh.glsl and call its traversal, else its Spec has no such member).
template <typename Spec>
Spec bvh_spec(const BvhBuffers& bvh, Spec spec = {}) {
    spec.kBvhAlphaTest = bvh.alpha_tests ? 1u : 0u;
    return spec;
}

// Binds `bvh` to a shader's bvh.glsl bindings (`bvh_nodes`, `bvh_triangles`, `bvh_alpha`).
template <typename Bindings>
void bind_bvh(Bindings& b, const BvhBuffers& bvh) {
    b.bvh_nodes = bvh.nodes.descriptor();
    b.bvh_triangles = bvh.triangles.descriptor();
    b.bvh_alpha = bvh.alpha.descriptor();
}

}  // namespace vplkit::stages
