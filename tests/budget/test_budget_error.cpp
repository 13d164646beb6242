// The error model's sum (budget_error.hpp): measured noise scaled by spp and VPLs, bias floors,
// half resolution and svgf, and the configurations it cannot predict.

#include "vplkit/budget_error.hpp"

#include "vplkit/budget_noise.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

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
    m.vpl_small = 1024;
    m.vpl_small_mse = 0.0003;
    return m;
}

}  // namespace

TEST_CASE("budget: the error model adds noise over spp, the VPL budget's error and the floors") {
    const auto m = model();
    // rtslc (no floor) at 16 spp and 1024 VPLs: 0.004 x 4 / 16 + the smaller budget's 0.0003.
    CHECK(*m.predict_rmse({GiMethod::rtslc, 16, false, DenoiseMode::off, 1024, 8}) ==
          doctest::Approx(std::sqrt(0.001 + 0.0003)));
    // 2048 VPLs: (4096 / 2048 - 1) / (4096 / 1024 - 1) = 1/3 of it; the settings' 4096: none.
    CHECK(*m.predict_rmse({GiMethod::rtslc, 16, false, DenoiseMode::off, 2048, 8}) ==
          doctest::Approx(std::sqrt(0.001 + 0.0001)));
    CHECK(*m.predict_rmse({GiMethod::rtslc, 16, false, DenoiseMode::off, 4096, 8}) ==
          doctest::Approx(std::sqrt(0.001)));
    // hybrid at half resolution: its floor and half resolution's.
    const double floors = vplkit::kHybridBiasFloor * vplkit::kHybridBiasFloor +
                          vplkit::kHalfResolutionBiasFloor * vplkit::kHalfResolutionBiasFloor;
    CHECK(*m.predict_rmse({GiMethod::hybrid, 4, true, DenoiseMode::off, 4096, 8}) ==
          doctest::Approx(std::sqrt(0.002 + floors)));
    // svgf not measured: the Cornell constants, F^2 + r n^2 in place of the sampling noise n^2.
    const double svgf = vplkit::kSvgfBlurFloor * vplkit::kSvgfBlurFloor + vplkit::kSvgfNoiseShare * 0.004;
    CHECK(*m.predict_rmse({GiMethod::rtslc, 4, false, DenoiseMode::svgf, 1024, 8}) ==
          doctest::Approx(std::sqrt(svgf + 0.0003)));
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

namespace {

constexpr int kSide = 96;

// A frame with a ramp and a step (what a blur smears), and Gaussian noise of `sigma` per value.
std::vector<float> noisy(double sigma, uint32_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> noise(0.0, sigma);
    std::vector<float> out(kSide * kSide * 3);
    for (int p = 0; p < kSide * kSide; ++p) {
        const int x = p % kSide;
        const double truth = 0.2 + 0.5 * x / kSide + (x >= kSide / 2 ? 0.8 : 0.0);
        for (int c = 0; c < 3; ++c) out[p * 3 + c] = float(truth + (sigma > 0.0 ? noise(rng) : 0.0));
    }
    return out;
}

// A 3 x 3 box filter, edges clamped: it keeps 1/9 of independent noise inside the frame.
std::vector<float> box(const std::vector<float>& in) {
    std::vector<float> out(in.size());
    for (int y = 0; y < kSide; ++y) {
        for (int x = 0; x < kSide; ++x) {
            for (int c = 0; c < 3; ++c) {
                double sum = 0.0;
                for (int dy = -1; dy <= 1; ++dy) {
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int sx = std::clamp(x + dx, 0, kSide - 1), sy = std::clamp(y + dy, 0, kSide - 1);
                        sum += in[(sy * kSide + sx) * 3 + c];
                    }
                }
                out[(y * kSide + x) * 3 + c] = float(sum / 9.0);
            }
        }
    }
    return out;
}

}  // namespace

TEST_CASE("budget: svgf's floor and kept noise measured from filtered and raw frames") {
    // A box filter stands for svgf: its floor is what it does to the noiseless frame, its kept share
    // ~1/9 (a little more at the clamped edges). Measured as the calibration does: raw pairs at two
    // noise levels, each filtered frame against a reference with far less noise.
    const double sigma0 = 0.2, sigma1 = 0.1, sigma_reference = 0.02;
    const auto reference = noisy(sigma_reference, 1), reference2 = noisy(sigma_reference, 2);
    const double reference_noise = vplkit::half_difference_variance(reference, reference2);
    auto filtered_error = [&](const std::vector<float>& raw) {
        const auto filtered = box(raw);
        return vplkit::half_difference_variance(filtered, reference) +
               vplkit::half_difference_variance(filtered, reference2) - reference_noise;
    };
    const auto x0 = noisy(sigma0, 3), x0b = noisy(sigma0, 4), x1 = noisy(sigma1, 5), x1b = noisy(sigma1, 6);
    const auto effect = vplkit::svgf_effect(vplkit::half_difference_variance(x0, x0b), filtered_error(x0),
                                            vplkit::half_difference_variance(x1, x1b), filtered_error(x1));
    REQUIRE(effect);
    const double floor = 2.0 * vplkit::half_difference_variance(box(noisy(0.0, 0)), noisy(0.0, 0));
    CHECK(effect->noise_share == doctest::Approx(1.0 / 9.0).epsilon(0.1));
    CHECK(effect->floor_variance == doctest::Approx(floor).epsilon(0.1));
    // Through two points: e = F^2 + r n^2.
    const auto exact = vplkit::svgf_effect(0.04, 0.001 + 0.1 * 0.04, 0.01, 0.001 + 0.1 * 0.01);
    REQUIRE(exact);
    CHECK(exact->noise_share == doctest::Approx(0.1));
    CHECK(exact->floor_variance == doctest::Approx(0.001));
    // Nothing unless the raw noise fell from spp0 to spp1; the share within [0, 1], the floor not below 0.
    CHECK(!vplkit::svgf_effect(0.01, 0.01, 0.01, 0.005));
    CHECK(vplkit::svgf_effect(0.04, 0.1, 0.01, 0.0)->noise_share == 1.0);
    CHECK(vplkit::svgf_effect(0.04, 0.1, 0.01, 0.0)->floor_variance == 0.0);
    CHECK(vplkit::svgf_effect(0.04, 0.001, 0.01, 0.002)->noise_share == 0.0);
}

TEST_CASE("budget: the error model uses the method's measured svgf effect, at either resolution") {
    auto m = model();
    m.sampling[0].svgf = vplkit::SvgfEffect{0.0004, 0.2};  // rtslc, full resolution
    CHECK(*m.predict_rmse({GiMethod::rtslc, 4, false, DenoiseMode::svgf, 4096, 8}) ==
          doctest::Approx(std::sqrt(0.0004 + 0.2 * 0.004)));
    // hybrid measured at half resolution: its full-resolution frames take it too.
    m.sampling[1].svgf = vplkit::SvgfEffect{0.0001, 0.5};
    m.sampling.push_back({GiMethod::hybrid, false, 8, 4, 0.003});
    CHECK(*m.predict_rmse({GiMethod::hybrid, 4, false, DenoiseMode::svgf, 4096, 8}) ==
          doctest::Approx(std::sqrt(0.0001 + 0.5 * 0.003 + vplkit::kHybridBiasFloor * vplkit::kHybridBiasFloor)));
    // sst not measured: the constants.
    CHECK(m.svgf_for({GiMethod::sst, 4, false, DenoiseMode::svgf, 4096, 8}).noise_share == vplkit::kSvgfNoiseShare);
}
