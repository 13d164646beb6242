// fit_linear: the normal equations (X^T X) c = X^T t solved by Gauss-Jordan elimination with
// diagonal pivots, the columns scaled to unit length first so that pixel counts (1e5) and
// constants (1) compare when a pivot is judged too small.

#include "vplkit/budget_fit.hpp"

#include "vplkit/error.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace vplkit {

std::vector<double> fit_linear(std::span<const double> features, size_t feature_count, std::span<const double> times) {
    const size_t n = feature_count;
    if (n == 0 || features.size() != times.size() * n) {
        throw Error("fit_linear: " + std::to_string(features.size()) + " feature values for " +
                    std::to_string(times.size()) + " samples of " + std::to_string(n) + " features");
    }
    for (double v : features) {
        if (!std::isfinite(v)) throw Error("fit_linear: a feature value is not finite");
    }
    for (double v : times) {
        if (!std::isfinite(v)) throw Error("fit_linear: a time is not finite");
    }
    // Column scales: a column of zeros keeps scale 1 (its coefficient ends up 0).
    std::vector<double> scale(n, 0.0);
    for (size_t s = 0; s < times.size(); ++s) {
        for (size_t j = 0; j < n; ++j) scale[j] += features[s * n + j] * features[s * n + j];
    }
    for (double& v : scale) v = v > 0.0 ? std::sqrt(v) : 1.0;

    // [X^T X | X^T t] of the scaled columns.
    std::vector<std::vector<double>> a(n, std::vector<double>(n + 1, 0.0));
    for (size_t s = 0; s < times.size(); ++s) {
        for (size_t i = 0; i < n; ++i) {
            const double xi = features[s * n + i] / scale[i];
            for (size_t j = 0; j < n; ++j) a[i][j] += xi * features[s * n + j] / scale[j];
            a[i][n] += xi * times[s];
        }
    }
    // Gauss-Jordan on the diagonal (X^T X is symmetric positive semi-definite, so no row swaps):
    // a column whose diagonal is ~0 once the earlier columns are taken out lies in their span
    // (the scaled columns have unit length, so ~0 is relative): it is dropped, coefficient 0.
    constexpr double kDependent = 1e-10;
    std::vector<bool> dropped(n, false);
    for (size_t col = 0; col < n; ++col) {
        if (a[col][col] < kDependent) {
            dropped[col] = true;
            continue;
        }
        for (size_t r = 0; r < n; ++r) {
            if (r == col || a[r][col] == 0.0) continue;
            const double f = a[r][col] / a[col][col];
            for (size_t j = 0; j <= n; ++j) a[r][j] -= f * a[col][j];
        }
    }
    std::vector<double> c(n, 0.0);
    for (size_t i = 0; i < n; ++i) {
        if (!dropped[i]) c[i] = a[i][n] / a[i][i] / scale[i];
    }
    return c;
}

std::vector<double> fit_linear_nonnegative_slopes(std::span<const double> features, size_t feature_count,
                                                  std::span<const double> times) {
    std::vector<double> active(features.begin(), features.end());
    for (;;) {
        const std::vector<double> c = fit_linear(active, feature_count, times);
        // The most negative slope, weighed by its feature's largest value (its effect on a time).
        size_t worst = 0;
        double worst_effect = 0.0;
        for (size_t j = 1; j < feature_count; ++j) {
            double largest = 0.0;
            for (size_t s = 0; s < times.size(); ++s)
                largest = std::max(largest, std::abs(active[s * feature_count + j]));
            const double effect = c[j] * largest;
            if (effect < worst_effect) {
                worst_effect = effect;
                worst = j;
            }
        }
        if (worst == 0) return c;
        // A column of zeros is dropped by fit_linear (coefficient 0).
        for (size_t s = 0; s < times.size(); ++s) active[s * feature_count + worst] = 0.0;
    }
}

}  // namespace vplkit
