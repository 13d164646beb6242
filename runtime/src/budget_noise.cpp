// The half-difference variance of two independent estimates (budget_noise.hpp).

#include "vplkit/budget_noise.hpp"

#include "vplkit/error.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace vplkit {

double half_difference_variance(std::span<const float> a, std::span<const float> b) {
    if (a.size() != b.size() || a.empty()) {
        throw Error("noise estimate: the two frames have " + std::to_string(a.size()) + " and " +
                    std::to_string(b.size()) + " values (they must be equal and not empty)");
    }
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        if (!std::isfinite(a[i]) || !std::isfinite(b[i])) {
            throw Error("noise estimate: value " + std::to_string(i) + " of the frames is not finite");
        }
        const double d = double(a[i]) - double(b[i]);
        sum += d * d;
    }
    return sum / double(a.size()) / 2.0;
}

double half_difference_variance_rgba8(std::span<const uint8_t> a, std::span<const uint8_t> b) {
    if (a.size() != b.size() || a.empty() || a.size() % 4 != 0) {
        throw Error("noise estimate: the two RGBA8 frames have " + std::to_string(a.size()) + " and " +
                    std::to_string(b.size()) + " bytes (they must be equal, not empty, 4 per pixel)");
    }
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        if (i % 4 == 3) continue;  // alpha
        const double d = (double(a[i]) - double(b[i])) / 255.0;
        sum += d * d;
    }
    return sum / double(a.size() / 4 * 3) / 2.0;
}

double low_pass_half_difference_variance(std::span<const float> a, std::span<const float> b, uint32_t width,
                                         uint32_t height, uint32_t block) {
    const size_t values = size_t(width) * height * 3;
    if (a.size() != values || b.size() != values || values == 0) {
        throw Error("noise estimate: the two frames have " + std::to_string(a.size()) + " and " +
                    std::to_string(b.size()) + " values, not " + std::to_string(values) + " (" + std::to_string(width) +
                    " x " + std::to_string(height) + " x 3)");
    }
    if (block == 0 || block > width || block > height) {
        throw Error("noise estimate: a block of " + std::to_string(block) + " pixels does not fit a " +
                    std::to_string(width) + " x " + std::to_string(height) + " frame");
    }
    const uint32_t blocks_x = width / block, blocks_y = height / block;
    const double pixels = double(block) * block;
    double sum = 0.0;
    for (uint32_t by = 0; by < blocks_y; ++by) {
        for (uint32_t bx = 0; bx < blocks_x; ++bx) {
            double mean[3] = {0.0, 0.0, 0.0};
            for (uint32_t y = by * block; y < (by + 1) * block; ++y) {
                for (uint32_t x = bx * block; x < (bx + 1) * block; ++x) {
                    const size_t i = (size_t(y) * width + x) * 3;
                    for (uint32_t c = 0; c < 3; ++c) {
                        if (!std::isfinite(a[i + c]) || !std::isfinite(b[i + c])) {
                            throw Error("noise estimate: value " + std::to_string(i + c) +
                                        " of the frames is not finite");
                        }
                        mean[c] += double(a[i + c]) - double(b[i + c]);
                    }
                }
            }
            for (double m : mean) sum += (m / pixels) * (m / pixels);
        }
    }
    return sum / (double(blocks_x) * blocks_y * 3) / 2.0;
}

double vpl_set_variance(std::span<const float> a1, std::span<const float> a2, std::span<const float> b1,
                        std::span<const float> b2, uint32_t width, uint32_t height, uint32_t block) {
    if (a2.size() != a1.size() || b1.size() != a1.size() || b2.size() != a1.size()) {
        throw Error("VPL noise estimate: the four frames have other sizes");
    }
    std::vector<float> mean_a(a1.size()), mean_b(a1.size());
    for (size_t i = 0; i < a1.size(); ++i) {
        mean_a[i] = 0.5f * (a1[i] + a2[i]);
        mean_b[i] = 0.5f * (b1[i] + b2[i]);
    }
    const double both = low_pass_half_difference_variance(mean_a, mean_b, width, height, block);
    const double sampling = 0.25 * (low_pass_half_difference_variance(a1, a2, width, height, block) +
                                    low_pass_half_difference_variance(b1, b2, width, height, block));
    return std::max(0.0, both - sampling);
}

uint32_t vpl_noise_block(uint32_t width) {
    return std::clamp((width + 20) / 40, 2u, 16u);
}

double variance_at_samples(double variance, uint32_t measured_samples, uint32_t samples, double exponent) {
    if (measured_samples == 0 || samples == 0) throw Error("noise estimate: zero samples per pixel");
    return variance * std::pow(double(measured_samples) / double(samples), exponent);
}

double spp_exponent(double variance_a, uint32_t spp_a, double variance_b, uint32_t spp_b) {
    if (!(variance_a > 0.0) || !(variance_b > 0.0) || spp_a == spp_b || spp_a == 0 || spp_b == 0) return 1.0;
    const double exponent = std::log(variance_a / variance_b) / std::log(double(spp_b) / double(spp_a));
    return std::clamp(exponent, 0.5, 1.0);
}

}  // namespace vplkit
