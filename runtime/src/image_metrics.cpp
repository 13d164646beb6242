#include "vplkit/image_metrics.hpp"

#include "vplkit/error.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace vplkit {

namespace {

constexpr uint32_t kSsimWindowSize = 11;  // Wang et al. 2004, sec. III-C
constexpr double kSsimGaussianSigma = 1.5;

std::string pixel_name(size_t value_index, uint32_t width) {
    const size_t pixel = value_index / 3;
    const char channel = "RGB"[value_index % 3];
    if (width == 0) return "pixel " + std::to_string(pixel) + " channel " + channel;
    return "pixel (" + std::to_string(pixel % width) + ", " + std::to_string(pixel / width) + ") channel " + channel;
}

void check_finite(const char* metric, const char* which, std::span<const float> image, uint32_t width) {
    const auto bad = std::find_if(image.begin(), image.end(), [](float v) { return !std::isfinite(v); });
    if (bad == image.end()) return;
    throw Error(std::string(metric) + ": the " + which + " image's " + pixel_name(size_t(bad - image.begin()), width) +
                " is " + (std::isnan(*bad) ? "NaN" : "infinite"));
}

// The checks every metric makes. width == 0: the caller has no size, only the value counts.
void check_images(const char* metric, std::span<const float> test, std::span<const float> reference, uint32_t width = 0,
                  uint32_t height = 0) {
    if (width != 0 && size_t(width) * height * 3 != reference.size()) {
        throw Error(std::string(metric) + ": a " + std::to_string(width) + "x" + std::to_string(height) +
                    " image has " + std::to_string(size_t(width) * height * 3) + " values, the reference has " +
                    std::to_string(reference.size()));
    }
    if (test.size() != reference.size()) {
        throw Error(std::string(metric) + ": the images differ in size: the test image has " +
                    std::to_string(test.size()) + " values, the reference " + std::to_string(reference.size()));
    }
    if (reference.empty()) throw Error(std::string(metric) + ": the images are empty");
    if (reference.size() % 3 != 0) {
        throw Error(std::string(metric) + ": " + std::to_string(reference.size()) +
                    " values is not a whole number of RGB pixels");
    }
    check_finite(metric, "test", test, width);
    check_finite(metric, "reference", reference, width);
}

double mean_squared_error(std::span<const float> test, std::span<const float> reference) {
    double sum = 0.0;
    for (size_t i = 0; i < reference.size(); ++i) {
        const double d = double(test[i]) - double(reference[i]);
        sum += d * d;
    }
    return sum / double(reference.size());
}

// The normalized 1D Gaussian whose outer product is the SSIM window (separable, so each moment
// costs 2n instead of n^2 multiplies per pixel).
std::vector<double> gaussian_weights(uint32_t size) {
    std::vector<double> weights(size);
    const double centre = double(size / 2);
    double sum = 0.0;
    for (uint32_t i = 0; i < size; ++i) {
        const double d = double(i) - centre;
        weights[i] = std::exp(-d * d / (2.0 * kSsimGaussianSigma * kSsimGaussianSigma));
        sum += weights[i];
    }
    for (double& w : weights) w /= sum;
    return weights;
}

// Adds one channel's SSIM per valid window to `map`. The weighted moments mu_x, mu_y, E[x^2],
// E[y^2], E[xy] come from a horizontal pass over every row, then a vertical one over valid rows.
void add_channel_ssim(std::span<const float> test, std::span<const float> reference, uint32_t channel, uint32_t width,
                      uint32_t height, const std::vector<double>& weights, double c1, double c2, SsimMap& map) {
    const uint32_t n = uint32_t(weights.size());
    const size_t row_pass_size = size_t(map.width) * height;
    std::vector<double> row_x(row_pass_size), row_y(row_pass_size), row_xx(row_pass_size), row_yy(row_pass_size),
        row_xy(row_pass_size);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < map.width; ++x) {
            double sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
            for (uint32_t i = 0; i < n; ++i) {
                const size_t at = (size_t(y) * width + x + i) * 3 + channel;
                const double a = test[at];
                const double b = reference[at];
                const double w = weights[i];
                sx += w * a;
                sy += w * b;
                sxx += w * (a * a);
                syy += w * (b * b);
                sxy += w * (a * b);
            }
            const size_t out = size_t(y) * map.width + x;
            row_x[out] = sx;
            row_y[out] = sy;
            row_xx[out] = sxx;
            row_yy[out] = syy;
            row_xy[out] = sxy;
        }
    }
    for (uint32_t y = 0; y < map.height; ++y) {
        for (uint32_t x = 0; x < map.width; ++x) {
            double mu_x = 0.0, mu_y = 0.0, mean_xx = 0.0, mean_yy = 0.0, mean_xy = 0.0;
            for (uint32_t j = 0; j < n; ++j) {
                const size_t at = size_t(y + j) * map.width + x;
                const double w = weights[j];
                mu_x += w * row_x[at];
                mu_y += w * row_y[at];
                mean_xx += w * row_xx[at];
                mean_yy += w * row_yy[at];
                mean_xy += w * row_xy[at];
            }
            // Wang et al. 2004 eq. 13. sigma_xy and sigma_x^2 go through the same arithmetic so
            // that identical images score exactly 1.
            const double sigma_xx = mean_xx - mu_x * mu_x;
            const double sigma_yy = mean_yy - mu_y * mu_y;
            const double sigma_xy = mean_xy - mu_x * mu_y;
            const double luminance_numerator = 2.0 * mu_x * mu_y + c1;
            const double luminance_denominator = mu_x * mu_x + mu_y * mu_y + c1;
            const double structure_numerator = 2.0 * sigma_xy + c2;
            const double structure_denominator = sigma_xx + sigma_yy + c2;
            map.values[size_t(y) * map.width + x] +=
                (luminance_numerator * structure_numerator) / (luminance_denominator * structure_denominator);
        }
    }
}

// sRGB transfer function (IEC 61966-2-1), as tonemap.glsl encodes display output.
double linear_to_srgb(double linear) {
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

}  // namespace

double rmse(std::span<const float> test, std::span<const float> reference) {
    check_images("rmse", test, reference);
    return std::sqrt(mean_squared_error(test, reference));
}

double relative_rmse(std::span<const float> test, std::span<const float> reference) {
    check_images("relative_rmse", test, reference);
    double sum = 0.0;
    for (float r : reference) sum += r;
    const double reference_mean = sum / double(reference.size());
    if (!(reference_mean > 0.0)) {
        throw Error("relative_rmse: the reference's mean is " + std::to_string(reference_mean) +
                    "; the error can only be relative to a positive mean");
    }
    return std::sqrt(mean_squared_error(test, reference)) / reference_mean;
}

double relative_mse(std::span<const float> test, std::span<const float> reference, double epsilon) {
    if (!(epsilon > 0.0) || !std::isfinite(epsilon)) {
        throw Error("relative_mse: epsilon must be positive and finite, got " + std::to_string(epsilon));
    }
    check_images("relative_mse", test, reference);
    double sum = 0.0;
    for (size_t i = 0; i < reference.size(); ++i) {
        const double r = reference[i];
        const double d = double(test[i]) - r;
        sum += d * d / (r * r + epsilon);
    }
    return sum / double(reference.size());
}

uint32_t ssim_window_size(uint32_t width, uint32_t height) {
    const uint32_t fits = std::min({kSsimWindowSize, width, height});
    if (fits == 0) throw Error("ssim: a " + std::to_string(width) + "x" + std::to_string(height) + " image is empty");
    return fits % 2 == 1 ? fits : fits - 1;
}

SsimMap ssim_map(std::span<const float> test, std::span<const float> reference, uint32_t width, uint32_t height,
                 const SsimOptions& options) {
    if (width == 0 || height == 0) {
        throw Error("ssim: a " + std::to_string(width) + "x" + std::to_string(height) + " image is empty");
    }
    check_images("ssim", test, reference, width, height);
    // C1 and C2 keep the two ratios defined where the means or the variances are 0 (black or flat
    // windows), so neither may be 0.
    const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
    if (!positive(options.dynamic_range) || !positive(options.k1) || !positive(options.k2)) {
        throw Error("ssim: needs dynamic_range, k1 and k2 positive and finite (got L " +
                    std::to_string(options.dynamic_range) + ", k1 " + std::to_string(options.k1) + ", k2 " +
                    std::to_string(options.k2) + ")");
    }
    const double c1 = (options.k1 * options.dynamic_range) * (options.k1 * options.dynamic_range);
    const double c2 = (options.k2 * options.dynamic_range) * (options.k2 * options.dynamic_range);

    SsimMap map;
    map.window_size = ssim_window_size(width, height);
    map.width = width - map.window_size + 1;
    map.height = height - map.window_size + 1;
    map.values.assign(size_t(map.width) * map.height, 0.0);
    const std::vector<double> weights = gaussian_weights(map.window_size);
    for (uint32_t channel = 0; channel < 3; ++channel) {
        add_channel_ssim(test, reference, channel, width, height, weights, c1, c2, map);
    }
    for (double& v : map.values) v /= 3.0;  // after the sum, so three exact 1s stay exactly 1
    return map;
}

double ssim(std::span<const float> test, std::span<const float> reference, uint32_t width, uint32_t height,
            const SsimOptions& options) {
    const SsimMap map = ssim_map(test, reference, width, height, options);
    double sum = 0.0;
    for (double v : map.values) sum += v;
    return sum / double(map.values.size());
}

std::vector<uint8_t> difference_image_rgba8(std::span<const float> test, std::span<const float> reference,
                                            uint32_t width, uint32_t height, float scale) {
    if (!(scale > 0.0f) || !std::isfinite(scale)) {
        throw Error("difference_image_rgba8: scale must be positive and finite, got " + std::to_string(scale));
    }
    if (width == 0 || height == 0) {
        throw Error("difference_image_rgba8: a " + std::to_string(width) + "x" + std::to_string(height) +
                    " image is empty");
    }
    check_images("difference_image_rgba8", test, reference, width, height);
    const size_t pixels = size_t(width) * height;
    std::vector<uint8_t> rgba(pixels * 4);
    for (size_t p = 0; p < pixels; ++p) {
        for (size_t c = 0; c < 3; ++c) {
            const double difference = std::abs(double(test[p * 3 + c]) - double(reference[p * 3 + c]));
            const double shown = std::clamp(difference * double(scale), 0.0, 1.0);
            rgba[p * 4 + c] = uint8_t(std::lround(linear_to_srgb(shown) * 255.0));
        }
        rgba[p * 4 + 3] = 255;
    }
    return rgba;
}

}  // namespace vplkit
