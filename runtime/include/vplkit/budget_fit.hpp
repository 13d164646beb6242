#pragma once
// Least-squares fits of linear models, for the budget's cost model (budget_cost.hpp): a stage's
// GPU time as c0 * f0 + c1 * f1 + ..., the features f given per sample (1 for a constant term).

#include <cstddef>
#include <span>
#include <vector>

namespace vplkit {

// The coefficients c minimizing sum over samples of (features[s] . c - times[s])^2, by the normal
// equations. A feature the samples do not tell apart from the others (constant where the constant
// term is, or proportional to another: the calibration never varied it) gets coefficient 0, so
// the model falls back to the features that were varied. `features` holds samples row by row,
// `feature_count` values each. Throws vplkit::Error when the sizes disagree or a value is not finite.
std::vector<double> fit_linear(std::span<const double> features, size_t feature_count, std::span<const double> times);

// The same with every coefficient but the first (the constant term) kept >= 0: more pixels,
// samples or VPLs never take less time, though noisy timings can fit a negative slope (lavapipe
// under load). A feature whose slope comes out negative is left out (0) and the rest refitted,
// the most negative first, until none is.
std::vector<double> fit_linear_nonnegative_slopes(std::span<const double> features, size_t feature_count,
                                                  std::span<const double> times);

}  // namespace vplkit
