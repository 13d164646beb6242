// The half-difference variance of two independent estimates (budget_noise.hpp).

#include "vplkit/budget_noise.hpp"

#include "vplkit/error.hpp"

#include <algorithm>
#include <cmath>
#include <string>

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
