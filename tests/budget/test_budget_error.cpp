// The error model's sum (budget_error.hpp): measured noise scaled by spp and VPLs, bias floors,
// half resolution and svgf, and the configurations it cannot predict.

#include "vplkit/budget_error.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace {

using vplkit::BudgetConfig;
using vplkit::DenoiseMode;
using vplkit::GiMethod;

vplkit::ErrorModel model() {
    vplkit::ErrorModel m;
    m.sampling = {{GiMethod::rtslc, false, 8, 4, 0.004},
                  {GiMethod::hybrid, true, 8, 4, 0.002},
                  {GiMethod::sst, false, 8, 4, 0.006}};
    m.vpl_measured = 4096;
    m.vpl_variance = 0.0001;
    return m;
}

}  // namespace

TEST_CASE("budget: the error model adds noise over spp, the VPL set's noise and the floors") {
    const auto m = model();
    // rtslc (no floor) at 16 spp and 1024 VPLs: 0.004 x 4 / 16 + 0.0001 x 4.
    CHECK(*m.predict_rmse({GiMethod::rtslc, 16, false, DenoiseMode::off, 1024, 8}) ==
          doctest::Approx(std::sqrt(0.001 + 0.0004)));
    // hybrid at half resolution: its floor and half resolution's.
    const double floors = vplkit::kHybridBiasFloor * vplkit::kHybridBiasFloor +
                          vplkit::kHalfResolutionBiasFloor * vplkit::kHalfResolutionBiasFloor;
    CHECK(*m.predict_rmse({GiMethod::hybrid, 4, true, DenoiseMode::off, 4096, 8}) ==
          doctest::Approx(std::sqrt(0.002 + 0.0001 + floors)));
    // svgf: F^2 + r n^2 in place of the sampling noise n^2.
    const double svgf = vplkit::kSvgfBlurFloor * vplkit::kSvgfBlurFloor + vplkit::kSvgfNoiseShare * 0.004;
    CHECK(*m.predict_rmse({GiMethod::rtslc, 4, false, DenoiseMode::svgf, 4096, 8}) ==
          doctest::Approx(std::sqrt(svgf + 0.0001)));
    // sst's noise does not depend on the block size (it builds no cuts).
    CHECK(m.predict_rmse({GiMethod::sst, 4, false, DenoiseMode::off, 4096, 16}));
}

TEST_CASE("budget: the error model scales noise by 1/spp whatever exponent was measured") {
    vplkit::ErrorModel m;
    m.sampling = {{GiMethod::rtslc, false, 8, 4, 0.004, 0.5}};
    // 4 / 64 of the variance, not (4 / 64)^0.5.
    CHECK(*m.predict_rmse({GiMethod::rtslc, 64, false, DenoiseMode::off, 4096, 8}) ==
          doctest::Approx(std::sqrt(0.004 / 16.0)));
}

TEST_CASE("budget: the error model predicts nothing it did not measure") {
    const auto m = model();
    CHECK(!m.predict_rmse({GiMethod::rtslc, 4, true, DenoiseMode::off, 4096, 8}));        // half not measured
    CHECK(!m.predict_rmse({GiMethod::rtslc, 4, false, DenoiseMode::off, 4096, 4}));       // block 4 not measured
    CHECK(!m.predict_rmse({GiMethod::rtslc, 4, false, DenoiseMode::temporal, 4096, 8}));  // not modelled
}
