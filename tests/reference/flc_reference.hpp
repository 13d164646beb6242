#pragma once
// Forward light cuts (the FLC paper) in plain double precision, written from the paper's equations
// independently of shaders/include/vplkit/flc_partition.glsl: the levels' areas (eq. 17), Alg. 1's
// level for a uniform u and its pmf (eq. 3), the influence distances (eq. 18), the support
// distance (eq. 14), the partition of unity f~^k (eq. 16 as its Fig. 6 draws it) and F^k (eq. 10).

#include <array>
#include <cstdint>

namespace vplkit::reference {

struct FlcParameters {
    int level_count = 4;  // N + 1
    double s0 = 1.0;
    double d0 = 1.0;
    double mu = 2.0;
};

inline constexpr int kFlcDiscardedLevel = -1;

double flc_level_area(const FlcParameters& p, int k);          // S_k
double flc_divergence_area(const FlcParameters& p);            // S~_N
int flc_level(const FlcParameters& p, double u, double area);  // Alg. 1, or kFlcDiscardedLevel
double flc_level_pmf(const FlcParameters& p, int level, double area);
double flc_influence_distance(const FlcParameters& p, int k);  // D_k
double flc_support_distance(const std::array<double, 3>& x, const std::array<double, 3>& y,
                            const std::array<double, 3>& n);           // +inf behind the plane
double flc_partition_weight(const FlcParameters& p, int k, double d);  // f~^k(d)
double flc_vpl_area_weight(const FlcParameters& p, int k, double d);   // S_k f~^k(d)

}  // namespace vplkit::reference
