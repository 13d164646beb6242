#pragma once
// Error metrics for comparing a rendered image against ground truth (DESIGN.md, "Accuracy vs
// time"): RMSE, relative RMSE, relative MSE and SSIM, plus a difference picture to look at.
//
// Images are linear RGB float, 3 floats per pixel, rows top to bottom (RenderedImage::radiance,
// the PFM files of image_io.hpp). Every function computes in double and throws vplkit::Error when
// the two images differ in size, are empty, or hold a NaN or infinite value (the message names the
// image and the first bad pixel).

#include <cstdint>
#include <span>
#include <vector>

namespace vplkit {

// sqrt(mean over all values of (t - r)^2): every pixel and channel counts once.
double rmse(std::span<const float> test, std::span<const float> reference);

// rmse(test, reference) / mean(reference), the mean over all values. The same definition as
// scripts/pfm_error.py, so numbers from before and after this header compare. Throws when the
// reference's mean is not positive (a black reference has no scale to be relative to).
double relative_rmse(std::span<const float> test, std::span<const float> reference);

// relMSE of the rendering literature: mean over all values of (t - r)^2 / (r^2 + epsilon).
// epsilon keeps near-black values from dominating the mean; 1e-2 is the customary choice, and
// results are only comparable at the same epsilon (report it). Throws unless epsilon > 0.
inline constexpr double kRelativeMseEpsilon = 1e-2;
double relative_mse(std::span<const float> test, std::span<const float> reference,
                    double epsilon = kRelativeMseEpsilon);

// SSIM of Wang, Bovik, Sheikh and Simoncelli, "Image quality assessment: from error visibility to
// structural similarity", IEEE TIP 2004, with the constants of the paper's reference code:
//   SSIM(x, y) = (2 mu_x mu_y + C1) (2 sigma_xy + C2) / ((mu_x^2 + mu_y^2 + C1) (sigma_x^2 + sigma_y^2 + C2)),
//   C1 = (K1 L)^2, C2 = (K2 L)^2, K1 = 0.01, K2 = 0.03,
// the moments weighted by an 11x11 Gaussian window, sigma 1.5, normalized to sum 1 (the paper's
// eq. 14 weights, "fspecial('gaussian', 11, 1.5)"), biased (weighted population) variances.
// Only windows lying wholly inside the image count (no padding, the reference code's 'valid').
// Each of R, G and B is scored on its own and the three mean SSIMs averaged.
//
// Small images: when width or height is below 11 the window shrinks to the largest odd size that
// fits both (so a 7x20 image uses 7x7 windows, a 1xN image 1x1), keeping sigma 1.5 and
// renormalizing the truncated Gaussian. An 11-pixel window is itself a truncated Gaussian, so this
// is the same measure cut closer; results on such images are not comparable with other tools,
// most of which refuse them.
struct SsimOptions {
    // L: the range the values span. 1.0 for images in [0, 1] (tonemapped, display-referred); for
    // linear HDR values pass a scale of the reference, e.g. its maximum, and say so with the result.
    double dynamic_range = 1.0;
    double k1 = 0.01;
    double k2 = 0.03;
};

// The size of the SSIM window used for a width x height image (11, or less for small images).
uint32_t ssim_window_size(uint32_t width, uint32_t height);

// The SSIM of each window, averaged over R, G and B: (width - n + 1) x (height - n + 1) values,
// n = ssim_window_size(width, height), rows top to bottom. values[y * map_width + x] belongs to
// the window whose top-left pixel is (x, y), i.e. centred on pixel (x + n/2, y + n/2).
struct SsimMap {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t window_size = 0;
    std::vector<double> values;
};
SsimMap ssim_map(std::span<const float> test, std::span<const float> reference, uint32_t width, uint32_t height,
                 const SsimOptions& options = {});

// The mean of ssim_map: 1 for identical images, lower the more they differ (can go below 0).
// Throws unless dynamic_range, k1 and k2 are positive (C1, C2 > 0 keep flat or black windows defined).
double ssim(std::span<const float> test, std::span<const float> reference, uint32_t width, uint32_t height,
            const SsimOptions& options = {});

// A picture of where the images differ: |t - r| * scale per channel, clamped to [0, 1], sRGB
// encoded, alpha 255; width * height * 4 bytes, rows top to bottom, ready for write_png. Throws
// unless scale is positive and finite.
std::vector<uint8_t> difference_image_rgba8(std::span<const float> test, std::span<const float> reference,
                                            uint32_t width, uint32_t height, float scale = 10.0f);

}  // namespace vplkit
