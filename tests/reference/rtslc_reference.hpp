#pragma once
// CPU reference for real-time stochastic lightcuts (shaders/include/vplkit/rtslc.glsl,
// shaders/gi/rtslc_cut.comp), written plainly in double precision: the child probabilities of
// the RTSLC paper eqs. 1-2, the cut-selection bound and the cut itself, and the exact unshadowed sum
// over every VPL the estimator's mean must equal (vpl_reference's evaluation).

#include "vpl_reference.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace vplkit::reference {

// A light tree node as the shaders read it (light_tree.glsl), widened to double.
struct RtslcNode {
    Vec3 box_min{}, box_max{};
    double intensity = 0.0;
    uint32_t vpl_count = 0;  // 0: bogus (its box is never measured)
};

struct RtslcShading {
    Vec3 position{}, normal{}, wo{}, base_color{};
    double roughness = 0.5, metallic = 0.0;
};

// The lightcuts cosine bound over the box, as gi_box_cosine_bound computes it (corners in a
// frame around n, b.z over the closest x^2 + y^2).
double rtslc_box_cosine_bound(const Vec3& x, const Vec3& n, const Vec3& lo, const Vec3& hi);
// The BRDF luminance towards the box centre (n when the centre is not above the surface),
// lifted as gi_material_weight lifts it, at least 1e-8 (rtslc_material_weight).
double rtslc_material_weight(const RtslcShading& s, const RtslcNode& node);
// F I: 0 for a bogus node, zero intensity, or a box behind the surface.
double rtslc_node_importance(const RtslcShading& s, const RtslcNode& node);
// F I / max(d_min^2, eps^2).
double rtslc_node_bound(const RtslcShading& s, const RtslcNode& node, double min_distance);

struct RtslcChildProbability {
    double left = 0.0;  // the exact (unrounded) probability of the left child
    bool dead = false;  // both children weigh 0
};

// the RTSLC paper eqs. 1-2 with the squared distances clamped below by eps^2: p = (p_min + p_max) / 2,
// p_min = w_l^min / (w_l^min + w_r^min) with w = F I / max(d^2, eps^2).
RtslcChildProbability rtslc_child_probability(const RtslcShading& s, const RtslcNode& left, const RtslcNode& right,
                                              double min_distance);

struct RtslcCut {
    std::vector<uint32_t> nodes;  // in no particular order
    // The smallest relative gap, over the splits, between the bound of the node split and the
    // next largest candidate's (1 when there was no competitor, 0 for an exact tie): below
    // ~1e-4 float rounding on the GPU may choose the other node.
    double closest_call = 1.0;
};

// The cut rtslc_cut.comp selects at shading point s: from the root, split the non-leaf node of
// largest bound (ties: smaller node index) into its real children until cut_size nodes or only
// leaves remain. `nodes` holds 2 leaf_count - 1 nodes in heap order.
RtslcCut rtslc_select_cut(std::span<const RtslcNode> nodes, uint32_t leaf_count, const RtslcShading& s,
                          double min_distance, uint32_t cut_size);

// The real leaves (indices into the sorted leaf array) below `node`.
std::vector<uint32_t> rtslc_leaves_below(std::span<const RtslcNode> nodes, uint32_t leaf_count, uint32_t node);

// The sum over every VPL of vpl_contribution without visibility: the mean of the estimator
// with shadow rays off.
Vec3 rtslc_unshadowed_sum(const ShadingPoint& x, const Vec3& camera, std::span<const VplDesc> vpls,
                          double min_distance);

}  // namespace vplkit::reference
