#include "vplkit/auto_exposure.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vplkit {

AutoExposure auto_exposure(std::span<const float> rgb) {
    std::vector<float> lit;
    lit.reserve(rgb.size() / 3);
    for (size_t i = 0; i + 2 < rgb.size(); i += 3) {
        const float y = 0.2126f * rgb[i] + 0.7152f * rgb[i + 1] + 0.0722f * rgb[i + 2];
        if (std::isfinite(y) && y > 0.0f) lit.push_back(y);
    }
    AutoExposure out;
    if (lit.empty()) return out;
    const size_t k = std::min(lit.size() - 1, size_t(kAutoExposurePercentile * double(lit.size())));
    std::nth_element(lit.begin(), lit.begin() + std::ptrdiff_t(k), lit.end());
    out.key_luminance = lit[k];
    const double scale = kAutoExposureTarget / double(out.key_luminance);
    out.exposure = float(std::clamp(scale, 1.0 / kAutoExposureLimit, kAutoExposureLimit));
    return out;
}

}  // namespace vplkit
