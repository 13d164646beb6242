#pragma once
// The CDF a shader picks an emitter by: with u = k 2^-24 from rng_next_float (vplkit/rng.glsl),
// entry i is chosen when cdf[i - 1] <= u < cdf[i] (the first entry greater than u). Every entry
// is a multiple of 2^-24 (exact in float), so entry i is chosen with probability exactly
// cdf[i] - cdf[i - 1], and the shader divides by that difference: the pmf is the CDF's, never
// stored a second time. Each positive weight gets at least one step of 2^-24 (a weight whose
// float interval rounded to zero width was never drawn, and its light was lost), zero weights
// get empty intervals, the rest of the 2^24 steps go by weight; the last entry is 1.

#include <cstdint>
#include <vector>

namespace vplkit::stages {

inline constexpr uint32_t kSelectionSteps = 1u << 24;  // rng_next_float's resolution

// Throws vplkit::Error for a negative or non-finite weight, a zero total, or more than 2^24
// positive weights (each needs a step of its own).
std::vector<float> selection_cdf(const std::vector<double>& weights);

}  // namespace vplkit::stages
