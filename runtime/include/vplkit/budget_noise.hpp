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

// The same over a low-pass of the difference: (a - b) averaged over whole blocks of block x block
// pixels (3 floats a pixel, rows of `width`; a partial block at the right or bottom edge is left
// out), per channel, then the mean over blocks of that mean squared / 2. Noise independent from
// pixel to pixel falls by the block's pixel count; noise that is smooth over a block (a VPL set's
// blotches) stays. Throws vplkit::Error for sizes that do not match width x height x 3, a block of
// 0 or larger than the frame, or a value that is not finite.
double low_pass_half_difference_variance(std::span<const float> a, std::span<const float> b, uint32_t width,
                                         uint32_t height, uint32_t block);

// The VPL set's noise per value, sigma_v^2, from four frames at one spp: `a1`, `a2` share a VPL
// set and differ in their sampling numbers, as do `b1`, `b2` over another VPL set. The low-pass
// half-difference of the pairs' means holds the VPL sets' difference and a quarter of each pair's
// sampling noise, which the pairs' own low-pass half-differences measure and which is subtracted:
// what is left has no square of a sampling noise in it (only products of independent ones), so a
// frame's rare bright samples do not swing it. The low-pass keeps the VPL set's noise while it
// takes most of the sampling noise away (at the pixel level the VPL set's noise is a percent or
// so of the sampling noise's and lost in the estimate's spread). Not below 0. The VPL set's
// blotches are assumed smooth over a block: it reads less where they are not.
double vpl_set_variance(std::span<const float> a1, std::span<const float> a2, std::span<const float> b1,
                        std::span<const float> b2, uint32_t width, uint32_t height, uint32_t block);

// The low-pass block for a frame of `width` pixels: about a fortieth of the width (4 at 160, 8 at
// 320; 2..16), so it covers the same share of the view at every size.
uint32_t vpl_noise_block(uint32_t width);

// A variance measured with `measured_samples` samples per pixel, for `samples` instead:
// variance x (measured_samples / samples)^exponent. An average of independent samples has
// exponent 1; the samplers' measured noise falls slower (budget_error.hpp).
double variance_at_samples(double variance, uint32_t measured_samples, uint32_t samples, double exponent = 1.0);

// The exponent of variance = k / spp^exponent through two measurements, clamped to [0.5, 1]
// (1 when a variance is not positive): what two pairs of frames at two spp say.
double spp_exponent(double variance_a, uint32_t spp_a, double variance_b, uint32_t spp_b);

}  // namespace vplkit
