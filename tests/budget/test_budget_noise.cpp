// The noise estimate from two frames (budget_noise.hpp) against the true variance of a synthetic
// Monte Carlo estimator: each pixel the mean of `spp` exponential samples around its own mean (a
// heavy-ish tail, variance mean^2 per sample), so the true variance of a frame is known exactly.

#include "vplkit/budget_noise.hpp"

#include "vplkit/error.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

constexpr uint32_t kPixels = 64 * 64;

// The pixel means: a ramp from 0.1 to 1.1, RGB equal.
double pixel_mean(uint32_t pixel) {
    return 0.1 + double(pixel) / double(kPixels);
}

// One frame of the estimator with `spp` samples per pixel drawn from `seed`.
std::vector<float> estimate(uint32_t spp, uint32_t seed) {
    std::mt19937_64 rng(seed);
    std::vector<float> frame(kPixels * 3);
    for (uint32_t p = 0; p < kPixels; ++p) {
        std::exponential_distribution<double> sample(1.0 / pixel_mean(p));
        for (uint32_t c = 0; c < 3; ++c) {
            double sum = 0.0;
            for (uint32_t s = 0; s < spp; ++s) sum += sample(rng);
            frame[p * 3 + c] = float(sum / spp);
        }
    }
    return frame;
}

// The true variance per value: an exponential sample's variance is its mean squared, / spp.
double true_variance(uint32_t spp) {
    double sum = 0.0;
    for (uint32_t p = 0; p < kPixels; ++p) sum += pixel_mean(p) * pixel_mean(p);
    return sum / kPixels / spp;
}

}  // namespace

TEST_CASE("budget: the half-difference of two independent frames estimates the true variance") {
    // Two sample counts: the estimate follows the variance down by 1/spp. 12288 values, so the
    // estimate's own relative error is a few percent (exponential samples' fourth moment).
    for (uint32_t spp : {1u, 16u}) {
        CAPTURE(spp);
        const double measured = vplkit::half_difference_variance(estimate(spp, 1), estimate(spp, 2));
        CHECK(measured == doctest::Approx(true_variance(spp)).epsilon(0.06));
    }
}

TEST_CASE("budget: a variance measured at one sample count predicts another's") {
    const double at_4 = vplkit::half_difference_variance(estimate(4, 3), estimate(4, 4));
    const double predicted_32 = vplkit::variance_at_samples(at_4, 4, 32);
    const double measured_32 = vplkit::half_difference_variance(estimate(32, 5), estimate(32, 6));
    CHECK(predicted_32 == doctest::Approx(measured_32).epsilon(0.08));
    CHECK(predicted_32 == doctest::Approx(true_variance(32)).epsilon(0.06));
}

TEST_CASE("budget: frames with the same random numbers show no noise") {
    // The estimate needs independent frames: the same seed twice reads 0 (why calibration frames
    // take other frame counters).
    CHECK(vplkit::half_difference_variance(estimate(4, 7), estimate(4, 7)) == 0.0);
}

TEST_CASE("budget: the 8-bit noise estimate is on the 0..1 scale and leaves alpha out") {
    // Every colour value differs by 51 (0.2), alpha by 255: (0.2)^2 / 2 = 0.02.
    const std::vector<uint8_t> a{0, 0, 0, 0, 100, 100, 100, 255};
    const std::vector<uint8_t> b{51, 51, 51, 255, 49, 49, 49, 0};
    CHECK(vplkit::half_difference_variance_rgba8(a, b) == doctest::Approx(0.02));
}

TEST_CASE("budget: the noise estimate refuses frames of other sizes and non-finite values") {
    const std::vector<float> a{1.0f, 2.0f, 3.0f};
    const std::vector<float> b{1.0f, 2.0f};
    CHECK_THROWS_AS(vplkit::half_difference_variance(a, b), vplkit::Error);
    const std::vector<float> c{1.0f, std::numeric_limits<float>::quiet_NaN(), 3.0f};
    CHECK_THROWS_WITH_AS(vplkit::half_difference_variance(a, c), doctest::Contains("not finite"), vplkit::Error);
    CHECK_THROWS_AS(vplkit::variance_at_samples(1.0, 0, 4), vplkit::Error);
}

TEST_CASE("budget: the spp exponent through two measurements, clamped to [0.5, 1]") {
    CHECK(vplkit::spp_exponent(1.0, 4, 0.25, 16) == doctest::Approx(1.0));
    CHECK(vplkit::spp_exponent(1.0, 4, 0.5, 16) == doctest::Approx(0.5));
    CHECK(vplkit::spp_exponent(1.0, 4, std::pow(0.25, 0.7), 16) == doctest::Approx(0.7));
    CHECK(vplkit::spp_exponent(1.0, 4, 0.9, 16) == 0.5);   // flatter than any sampler: clamped
    CHECK(vplkit::spp_exponent(1.0, 4, 0.01, 16) == 1.0);  // steeper than independent samples
    CHECK(vplkit::spp_exponent(0.0, 4, 0.25, 16) == 1.0);  // no noise measured: 1/spp
    // The synthetic estimator's independent samples read about 1.
    const double at_4 = vplkit::half_difference_variance(estimate(4, 11), estimate(4, 12));
    const double at_16 = vplkit::half_difference_variance(estimate(16, 13), estimate(16, 14));
    CHECK(vplkit::spp_exponent(at_4, 4, at_16, 16) == doctest::Approx(1.0).epsilon(0.06));
    CHECK(vplkit::variance_at_samples(1.0, 4, 64, 0.5) == doctest::Approx(0.25));
}
