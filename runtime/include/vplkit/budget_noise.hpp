#pragma once
// The noise of a Monte Carlo frame estimated from the frames themselves, without a reference:
// two estimates a and b of the same image with independent random numbers (two frames of a
// static camera with other sampling numbers, or two halves of one frame's samples) differ by
// noise alone, so E[(a - b)^2] = 2 sigma^2 per value, and sigma^2 = E[(a - b)^2] / 2. The mean of
// that over every value is the frame's noise as a mean squared error: what its RMSE against the
// converged image would be from noise alone (the bias is not in it).

#include <cstdint>
#include <span>

namespace vplkit {

// mean over all values of (a - b)^2 / 2: the variance of one of the two estimates, per value.
// Throws vplkit::Error when the sizes differ, are empty, or a value is not finite.
double half_difference_variance(std::span<const float> a, std::span<const float> b);
// The same over 8-bit values (RenderedImage::rgba8, alpha left out) on the scale 0..1 (/ 255),
// the scale of the bench's RMSE of tonemapped frames.
double half_difference_variance_rgba8(std::span<const uint8_t> a, std::span<const uint8_t> b);

// A variance measured with `measured_samples` samples per pixel, for `samples` instead:
// variance x (measured_samples / samples)^exponent. An average of independent samples has
// exponent 1; the samplers' measured noise falls slower (budget_error.hpp).
double variance_at_samples(double variance, uint32_t measured_samples, uint32_t samples, double exponent = 1.0);

// The exponent of variance = k / spp^exponent through two measurements, clamped to [0.5, 1]
// (1 when a variance is not positive): what two pairs of frames at two spp say.
double spp_exponent(double variance_a, uint32_t spp_a, double variance_b, uint32_t spp_b);

}  // namespace vplkit
