// The automatic exposure (vplkit/auto_exposure.hpp): the lit pixels' 95th luminance percentile
// is scaled to kAutoExposureTarget; black and non-finite pixels do not count; the scale is bounded.

#include "vplkit/auto_exposure.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace {

// Grey pixels (r = g = b, so the luminance is the value).
std::vector<float> grey(const std::vector<float>& values) {
    std::vector<float> rgb;
    for (float v : values) rgb.insert(rgb.end(), {v, v, v});
    return rgb;
}

}  // namespace

TEST_CASE("auto exposure: the lit pixels' 95th luminance percentile goes to the target") {
    std::vector<float> values;
    for (int i = 1; i <= 100; ++i) values.push_back(0.01f * float(i));  // 0.01 .. 1.00
    // Black pixels (shadow, background) and non-finite ones are left out: the same exposure.
    std::vector<float> with_black = values;
    with_black.insert(with_black.end(), 300, 0.0f);
    with_black.push_back(std::numeric_limits<float>::quiet_NaN());
    with_black.push_back(INFINITY);
    for (const auto& v : {values, with_black}) {
        const vplkit::AutoExposure e = vplkit::auto_exposure(grey(v));
        CHECK(e.key_luminance == doctest::Approx(0.96f));  // the 96th of 100 sorted values (index 95)
        CHECK(e.exposure == doctest::Approx(vplkit::kAutoExposureTarget / 0.96));
    }
    // Scaling the image scales the exposure inversely: the display is the same.
    std::vector<float> brighter;
    for (float v : values) brighter.push_back(8.0f * v);
    CHECK(vplkit::auto_exposure(grey(brighter)).exposure ==
          doctest::Approx(vplkit::auto_exposure(grey(values)).exposure / 8.0f));
    // Colour: luminance is Rec. 709's.
    const vplkit::AutoExposure green = vplkit::auto_exposure(std::vector<float>{0.0f, 1.0f, 0.0f});
    CHECK(green.key_luminance == doctest::Approx(0.7152f));
}

TEST_CASE("auto exposure: no lit pixel gives 1, a nearly black frame is not amplified without end") {
    CHECK(vplkit::auto_exposure(grey({0.0f, 0.0f, 0.0f})).exposure == 1.0f);
    CHECK(vplkit::auto_exposure(std::vector<float>{}).exposure == 1.0f);
    CHECK(vplkit::auto_exposure(grey({1e-30f})).exposure == float(vplkit::kAutoExposureLimit));
    CHECK(vplkit::auto_exposure(grey({1e30f})).exposure == float(1.0 / vplkit::kAutoExposureLimit));
}
