#include "tonemap_reference.hpp"

#include <algorithm>
#include <cmath>

namespace vplkit::reference {

double tonemap_channel(double linear, double exposure) {
    const double x = std::max(linear, 0.0) * exposure;
    const double a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
    const double curve = std::clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
    return curve <= 0.0031308 ? 12.92 * curve : 1.055 * std::pow(curve, 1.0 / 2.4) - 0.055;
}

std::array<uint8_t, 4> tonemap(const std::array<float, 3>& rgb, double exposure) {
    if (!std::isfinite(rgb[0]) || !std::isfinite(rgb[1]) || !std::isfinite(rgb[2])) {
        return {255, 0, 255, 255};
    }
    std::array<uint8_t, 4> out{0, 0, 0, 255};
    for (int c = 0; c < 3; ++c) {
        out[c] = uint8_t(std::lround(tonemap_channel(rgb[c], exposure) * 255.0));
    }
    return out;
}

}  // namespace vplkit::reference
