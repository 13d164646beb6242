#pragma once
// CPU reference for the Stochastic Substitute Tree build (shaders/tree/build_sst.comp and
// shaders/include/vplkit/sst.glsl), written plainly in double precision with the same
// conventions: heap order, bogus leaves by index, the same tangent frame, fallbacks and
// thresholds. Besides each node it carries a first-order bound on how far a float build of the
// same node may be from it (rounding only), so a test can compare every field without one
// loose tolerance for all scales: the bound follows each node's own magnitudes (position scale,
// distance between child means, normal conditioning).
//
// An independent check of the merge formulas is direct_moments(): the intensity-weighted mean
// and total variance of a set of VPLs computed in two passes over the VPLs themselves, which
// the tree's recursive mean and variance trace must equal (law of total variance; rotating a
// child's variance into the parent frame keeps its trace).

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace vplkit::reference {

using Double3 = std::array<double, 3>;

struct SstLeaf {
    std::array<float, 3> position{};
    std::array<float, 3> normal{};
    std::array<float, 3> flux{};
};

// Thresholds as the GPU gets them (floats).
struct SstThresholds {
    float nu_min = 0.7f;
    float sigma_max = 0.3f;
};

// Absolute error bounds of a float build (first order, before any safety factor).
struct SstErrorBound {
    double mean = 0.0;    // per position component
    double normal = 0.0;  // per normal component
    double nu = 0.0;
    double variance = 0.0;       // per variance component
    double intensity_rel = 0.0;  // relative, of the intensity
    double colour_rel = 0.0;     // relative, of each colour component
};

struct SstNodeRef {
    Double3 mean{};
    double intensity = 0.0;
    Double3 normal{};
    double nu = 0.0;
    Double3 variance{};  // in sst_frame(normal)
    bool suitable = false;
    bool normal_fallback = false;
    Double3 box_lo{};
    Double3 box_hi{};
    uint32_t leaf_count = 0;
    Double3 colour{};

    double sigma_z = 0.0;               // sqrt(variance[2])
    double merged_normal_length = 1.0;  // |a n1 + b n2| before renormalizing (1 at leaves)
    // A discrete decision in this node or below (the normal fallback, the frame's pole guard) is
    // within rounding of its threshold: a float build may have gone the other way (tests avoid
    // such data).
    bool decision_ambiguous = false;
    SstErrorBound error;
};

// Constants of sst.glsl, in double.
inline constexpr double kSstMinMergedNormalLength = 1e-3;
inline constexpr double kSstFramePoleGuard = 1e-4;

double sst_intensity(const std::array<float, 3>& flux);
void sst_frame(const Double3& n, Double3& t, Double3& b);
SstNodeRef sst_leaf_node(const SstLeaf& leaf, const SstThresholds& thresholds);
SstNodeRef sst_empty_node();
SstNodeRef sst_merge(const SstNodeRef& left, const SstNodeRef& right, const SstThresholds& thresholds);

// The whole tree over `leaves` (a power-of-two count L; index >= count is bogus, whatever its
// data): 2L - 1 nodes in heap order, inner nodes 0 .. L - 2 then the L leaves as nodes.
std::vector<SstNodeRef> build_sst(std::span<const SstLeaf> leaves, uint32_t count, const SstThresholds& thresholds);

struct DirectMoments {
    double weight = 0.0;          // summed intensity
    Double3 mean{};               // intensity-weighted mean position
    double total_variance = 0.0;  // sum over w |p - mean|^2 / weight
};
// Two passes over the VPLs; needs a positive summed intensity.
DirectMoments direct_moments(std::span<const SstLeaf> vpls);
// Intensity-weighted variance of the positions along a unit `axis` about `mean`.
double direct_variance_along(std::span<const SstLeaf> vpls, const Double3& mean, const Double3& axis);

}  // namespace vplkit::reference
