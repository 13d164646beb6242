#pragma once
// CPU reference for the hybrid method's shallow cut (shaders/gi/hybrid_cut.comp), in double:
// the expected contribution of the thesis sec. 5.1.2 (eq. 5.2 corner cosine x material x intensity
// / clamped squared distance to the node's mean) and the greedy split of sec. 5.1.1.

#include "vpl_reference.hpp"

#include <cstdint>
#include <functional>
#include <vector>

namespace vplkit::reference {

// What the cut needs of a tree node (heap index; leaves are nodes L - 1 ..).
struct CutNode {
    Vec3 mean{};
    double intensity = 0.0;  // luminance
    Vec3 box_lo{}, box_hi{};
    uint32_t leaf_count = 0;  // real VPLs below; 0: padding
};

// the thesis eq. 5.2: the clamped cosine to the box's eight corners, averaged.
double average_corner_cosine(const Vec3& x, const Vec3& n, const Vec3& lo, const Vec3& hi);

// The expected contribution's numerator a (material x cosine x intensity) and its squared
// distance d2 (clamped below by min_distance^2).
double expected_contribution(const ShadingPoint& x, const Vec3& wo, const CutNode& node, double min_distance,
                             double& d2);

// The cut of at most cut_size nodes, in the order of their first leaf.
std::vector<uint32_t> hybrid_cut(const ShadingPoint& x, const Vec3& wo, const std::function<CutNode(uint32_t)>& node,
                                 uint32_t leaf_count, uint32_t cut_size, double min_distance);

}  // namespace vplkit::reference
