#include "flc_reference.hpp"

#include <cmath>
#include <limits>

namespace vplkit::reference {

double flc_level_area(const FlcParameters& p, int k) {
    return p.s0 * std::pow(p.mu, k);
}

double flc_divergence_area(const FlcParameters& p) {
    double inverse = 0.0;
    for (int k = 0; k < p.level_count; ++k) inverse += 1.0 / flc_level_area(p, k);
    return 1.0 / inverse;
}

int flc_level(const FlcParameters& p, double u, double area) {
    // Level k takes the slice [A sum_{j<k} 1/S_j, A sum_{j<=k} 1/S_j) of [0, 1).
    double lower = 0.0;
    for (int k = 0; k < p.level_count; ++k) {
        const double upper = lower + area / flc_level_area(p, k);
        if (u >= lower && u < upper) return k;
        lower = upper;
    }
    return kFlcDiscardedLevel;
}

double flc_level_pmf(const FlcParameters& p, int level, double area) {
    if (level == kFlcDiscardedLevel) return 1.0 - area / flc_divergence_area(p);
    return area / flc_level_area(p, level);
}

double flc_influence_distance(const FlcParameters& p, int k) {
    return p.d0 * std::sqrt(std::pow(p.mu, k));
}

double flc_support_distance(const std::array<double, 3>& x, const std::array<double, 3>& y,
                            const std::array<double, 3>& n) {
    const double v[3] = {x[0] - y[0], x[1] - y[1], x[2] - y[2]};
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (length == 0.0) return 0.0;
    const double cosine = (n[0] * v[0] + n[1] * v[1] + n[2] * v[2]) / length;
    return cosine > 0.0 ? length / cosine : std::numeric_limits<double>::infinity();
}

double flc_partition_weight(const FlcParameters& p, int k, double d) {
    // Hat k peaks at D_k; its neighbours' peaks bound it. Level 0 is flat below D_0, level N
    // stays 1 beyond D_N (every finite distance is covered); behind the plane (d = inf) nothing.
    if (std::isinf(d)) return 0.0;
    const int last = p.level_count - 1;
    const double peak = flc_influence_distance(p, k);
    if (d <= peak) {
        if (k == 0) return 1.0;
        const double start = flc_influence_distance(p, k - 1);
        return d <= start ? 0.0 : (d - start) / (peak - start);
    }
    if (k == last) return 1.0;
    const double end = flc_influence_distance(p, k + 1);
    return d >= end ? 0.0 : (end - d) / (end - peak);
}

double flc_vpl_area_weight(const FlcParameters& p, int k, double d) {
    return flc_level_area(p, k) * flc_partition_weight(p, k, d);
}

}  // namespace vplkit::reference
