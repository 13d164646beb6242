// Error metrics (image_metrics.hpp) against values known in closed form, a separately written
// direct computation of SSIM's local means, and an independent SSIM implementation.

#include "vplkit/error.hpp"
#include "vplkit/image_metrics.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace {

// A test image that is neither constant nor symmetric, so a transposed or mis-indexed window
// shows: multiples of 1/256 in [0, 1) (exact in float, so x + 0.25 is exact too), different per
// channel.
std::vector<float> pattern_image(uint32_t width, uint32_t height) {
    std::vector<float> rgb(size_t(width) * height * 3);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            for (uint32_t c = 0; c < 3; ++c) {
                const uint32_t level = (x * (7 + c) + y * y * (3 + 2 * c) + 41 * c) % 200;
                rgb[(size_t(y) * width + x) * 3 + c] = float(level) / 256.0f;
            }
        }
    }
    return rgb;
}

std::vector<float> constant_image(uint32_t width, uint32_t height, float value) {
    return std::vector<float>(size_t(width) * height * 3, value);
}

// Deterministic noise in [-1, 1] (a plain LCG: the same sequence on every standard library).
std::vector<float> noise_image(uint32_t width, uint32_t height) {
    std::vector<float> rgb(size_t(width) * height * 3);
    uint32_t state = 12345u;
    for (float& v : rgb) {
        state = state * 1664525u + 1013904223u;
        v = float(state >> 8) / float(1u << 24) * 2.0f - 1.0f;
    }
    return rgb;
}

double ssim_constants_c(double k, double dynamic_range) {
    return (k * dynamic_range) * (k * dynamic_range);
}

}  // namespace

TEST_CASE("identical images: zero error and SSIM exactly 1") {
    const uint32_t width = 24, height = 17;
    const std::vector<float> image = pattern_image(width, height);
    CHECK(vplkit::rmse(image, image) == 0.0);
    CHECK(vplkit::relative_rmse(image, image) == 0.0);
    CHECK(vplkit::relative_mse(image, image) == 0.0);
    CHECK(vplkit::ssim(image, image, width, height) == 1.0);

    const vplkit::SsimMap map = vplkit::ssim_map(image, image, width, height);
    CHECK(map.window_size == 11);
    CHECK(map.width == 14);  // windows wholly inside: 24 - 11 + 1
    CHECK(map.height == 7);
    REQUIRE(map.values.size() == 14 * 7);
    for (double v : map.values) CHECK(v == 1.0);
}

TEST_CASE("RMSE and relative RMSE by hand") {
    // Differences -1, -1, -1, 0, 0, -2: squared sum 7 over 6 values; reference mean 8 / 6.
    const std::vector<float> test = {0, 0, 0, 1, 1, 1};
    const std::vector<float> reference = {1, 1, 1, 1, 1, 3};
    CHECK(vplkit::rmse(test, reference) == doctest::Approx(std::sqrt(7.0 / 6.0)).epsilon(1e-15));
    CHECK(vplkit::rmse(reference, test) == doctest::Approx(std::sqrt(7.0 / 6.0)).epsilon(1e-15));
    // scripts/pfm_error.py's definition: divided by the reference's mean, not its RMS.
    CHECK(vplkit::relative_rmse(test, reference) == doctest::Approx(std::sqrt(7.0 / 6.0) / (8.0 / 6.0)).epsilon(1e-15));
}

TEST_CASE("relative MSE on two pixels") {
    // Pixel 0: reference black, test 0.5: each channel 0.25 / (0 + eps). Pixel 1: blue off by 1
    // from 3: 1 / (9 + eps).
    const std::vector<float> test = {0.5f, 0.5f, 0.5f, 1, 2, 4};
    const std::vector<float> reference = {0, 0, 0, 1, 2, 3};
    CHECK(vplkit::kRelativeMseEpsilon == 1e-2);
    CHECK(vplkit::relative_mse(test, reference) ==
          doctest::Approx((3 * 0.25 / 0.01 + 1.0 / 9.01) / 6.0).epsilon(1e-14));
    CHECK(vplkit::relative_mse(test, reference, 0.25) == doctest::Approx((3.0 + 1.0 / 9.25) / 6.0).epsilon(1e-14));
    // Not symmetric: the denominator is the reference's.
    CHECK(vplkit::relative_mse(reference, test) ==
          doctest::Approx((3 * 0.25 / 0.26 + 1.0 / 16.01) / 6.0).epsilon(1e-14));
}

TEST_CASE("SSIM of constant images is the luminance term alone") {
    // Both variances and the covariance are 0, so the structure term is C2 / C2.
    for (const double dynamic_range : {1.0, 4.0}) {
        const double c1 = ssim_constants_c(0.01, dynamic_range);
        for (const auto& [a, b] :
             {std::pair{0.25f, 0.75f}, std::pair{0.0f, 0.5f}, std::pair{0.9f, 0.1f}, std::pair{0.0f, 0.0f}}) {
            CAPTURE(dynamic_range);
            CAPTURE(a);
            CAPTURE(b);
            const double expected = (2.0 * a * b + c1) / (double(a) * a + double(b) * b + c1);
            const vplkit::SsimOptions options{.dynamic_range = dynamic_range};
            CHECK(vplkit::ssim(constant_image(20, 13, a), constant_image(20, 13, b), 20, 13, options) ==
                  doctest::Approx(expected).epsilon(1e-12));
            // Small images take a smaller window; for constant images the value must not change.
            CHECK(vplkit::ssim(constant_image(4, 6, a), constant_image(4, 6, b), 4, 6, options) ==
                  doctest::Approx(expected).epsilon(1e-12));
        }
    }
}

TEST_CASE("SSIM is symmetric") {
    const uint32_t width = 19, height = 23;
    const std::vector<float> a = pattern_image(width, height);
    std::vector<float> b = a;
    const std::vector<float> noise = noise_image(width, height);
    for (size_t i = 0; i < b.size(); ++i) b[i] = b[i] * 0.8f + 0.1f * noise[i] + 0.05f;
    const double ab = vplkit::ssim(a, b, width, height);
    const double ba = vplkit::ssim(b, a, width, height);
    CHECK(ab < 0.99);
    CHECK(ab == doctest::Approx(ba).epsilon(1e-14));
}

TEST_CASE("SSIM against the image plus a constant: the luminance term of directly computed local means") {
    // y = x + b leaves the variances and the covariance equal, so each window's SSIM is
    // (2 mu (mu + b) + C1) / (mu^2 + (mu + b)^2 + C1), mu the window's Gaussian-weighted mean.
    // Those means are computed here the plain way (the full 2D window, no separable passes).
    const uint32_t width = 23, height = 15, n = 11;
    const float offset = 0.25f;
    const double dynamic_range = 1.5;
    const double c1 = ssim_constants_c(0.01, dynamic_range);
    const std::vector<float> x = pattern_image(width, height);
    std::vector<float> y = x;
    for (float& v : y) v += offset;  // exact: multiples of 1/256 below 1

    double weights[n][n];
    double weight_sum = 0.0;
    for (uint32_t j = 0; j < n; ++j) {
        for (uint32_t i = 0; i < n; ++i) {
            const double dx = double(i) - 5.0, dy = double(j) - 5.0;
            weights[j][i] = std::exp(-(dx * dx + dy * dy) / (2.0 * 1.5 * 1.5));
            weight_sum += weights[j][i];
        }
    }

    const vplkit::SsimMap map = vplkit::ssim_map(x, y, width, height, {.dynamic_range = dynamic_range});
    REQUIRE(map.width == width - n + 1);
    REQUIRE(map.height == height - n + 1);
    double expected_mean = 0.0;
    for (uint32_t top = 0; top + n <= height; ++top) {
        for (uint32_t left = 0; left + n <= width; ++left) {
            double expected = 0.0;
            for (uint32_t c = 0; c < 3; ++c) {
                double mu = 0.0;
                for (uint32_t j = 0; j < n; ++j) {
                    for (uint32_t i = 0; i < n; ++i) {
                        mu += weights[j][i] / weight_sum * x[(size_t(top + j) * width + left + i) * 3 + c];
                    }
                }
                const double mu_y = mu + offset;
                expected += (2.0 * mu * mu_y + c1) / (mu * mu + mu_y * mu_y + c1) / 3.0;
            }
            CAPTURE(left);
            CAPTURE(top);
            CHECK(map.values[size_t(top) * map.width + left] == doctest::Approx(expected).epsilon(1e-10));
            expected_mean += expected;
        }
    }
    expected_mean /= double(map.values.size());
    CHECK(expected_mean < 0.99);  // the offset must actually cost something for this to test anything
    CHECK(vplkit::ssim(x, y, width, height, {.dynamic_range = dynamic_range}) ==
          doctest::Approx(expected_mean).epsilon(1e-10));
}

TEST_CASE("SSIM matches an independent implementation (scikit-image)") {
    // Reference value from scikit-image 0.19 (Debian python3-skimage):
    //   structural_similarity(x, y, channel_axis=2, gaussian_weights=True, sigma=1.5,
    //                         use_sample_covariance=False, data_range=1.0)
    // on the two images below, built the same way in numpy (float32 arithmetic, then float64).
    // With those options its window is the same 11x11 Gaussian (truncate 3.5 x sigma 1.5 = radius
    // 5) and its mean, over the image cropped by the radius, the mean over the valid windows.
    const uint32_t width = 32, height = 24;
    std::vector<float> x(size_t(width) * height * 3), y(x.size());
    for (uint32_t row = 0; row < height; ++row) {
        for (uint32_t col = 0; col < width; ++col) {
            for (uint32_t c = 0; c < 3; ++c) {
                const size_t at = (size_t(row) * width + col) * 3 + c;
                x[at] = float((col * 7 + row * 13 + c * 5) % 17) / 16.0f;
                y[at] = 0.75f * x[at] + float((col * 3 + row * 5 + c * 11 + (col * row) % 7) % 19) / 72.0f;
            }
        }
    }
    CHECK(vplkit::ssim(x, y, width, height) == doctest::Approx(0.9207915188542762).epsilon(1e-9));
}

TEST_CASE("SSIM falls as noise grows") {
    const uint32_t width = 40, height = 30;
    std::vector<float> clean(size_t(width) * height * 3);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            for (uint32_t c = 0; c < 3; ++c) {
                clean[(size_t(y) * width + x) * 3 + c] =
                    0.2f + 0.6f * float(x + c) / float(width + 2) * float(y + 1) / float(height);
            }
        }
    }
    const std::vector<float> noise = noise_image(width, height);
    const double noise_rms = vplkit::rmse(noise, constant_image(width, height, 0.0f));
    double previous = 1.0;
    for (const float amplitude : {0.003f, 0.01f, 0.03f, 0.1f, 0.3f}) {
        CAPTURE(amplitude);
        std::vector<float> noisy = clean;
        for (size_t i = 0; i < noisy.size(); ++i) noisy[i] += amplitude * noise[i];
        const double value = vplkit::ssim(noisy, clean, width, height);
        CHECK(value < previous);
        CHECK(value > 0.0);
        previous = value;
        // RMSE is linear in the amplitude of the same noise.
        CHECK(vplkit::rmse(noisy, clean) == doctest::Approx(amplitude * noise_rms).epsilon(1e-5));
    }
    CHECK(previous < 0.5);  // the strongest noise is far from the clean image
}

TEST_CASE("SSIM on images smaller than the window") {
    CHECK(vplkit::ssim_window_size(640, 480) == 11);
    CHECK(vplkit::ssim_window_size(11, 11) == 11);
    CHECK(vplkit::ssim_window_size(10, 30) == 9);
    CHECK(vplkit::ssim_window_size(30, 7) == 7);
    CHECK(vplkit::ssim_window_size(1, 5) == 1);

    // A 1x1 window: the mean is the pixel and the variances are exactly 0, so each pixel scores
    // its luminance term.
    const std::vector<float> a = {0.1f, 0.2f, 0.3f, 0.5f, 0.5f, 0.5f, 1.0f, 0.0f, 0.25f};
    const std::vector<float> b = {0.1f, 0.4f, 0.3f, 0.5f, 0.0f, 0.75f, 0.5f, 0.0f, 0.25f};
    const vplkit::SsimMap map = vplkit::ssim_map(a, b, 3, 1);
    REQUIRE(map.window_size == 1);
    REQUIRE(map.values.size() == 3);
    const double c1 = ssim_constants_c(0.01, 1.0);
    for (size_t p = 0; p < 3; ++p) {
        double expected = 0.0;
        for (size_t c = 0; c < 3; ++c) {
            const double s = a[p * 3 + c], t = b[p * 3 + c];
            expected += (2.0 * s * t + c1) / (s * s + t * t + c1) / 3.0;
        }
        CAPTURE(p);
        CHECK(map.values[p] == doctest::Approx(expected).epsilon(1e-14));
    }
}

TEST_CASE("difference picture: |t - r| times the scale, clamped, sRGB encoded") {
    // Pixel 0: no difference. Pixel 1: 3/64 x 10 = 0.46875 -> sRGB 0.71439 -> 182. Pixel 2: a
    // difference of 0.5 is clamped to white. Pixel 3: 1/512 x 10 = 0.01953125 -> sRGB 0.14967 -> 38,
    // the reference larger than the test (the absolute value).
    const std::vector<float> test = {0.25f, 0.25f, 0.25f, 0.25f + 3.0f / 64.0f, 0.25f, 0.25f, 0.0f, 0.0f, 1.0f,
                                     0.5f,  0.5f,  0.5f};
    const std::vector<float> reference = {
        0.25f, 0.25f, 0.25f, 0.25f, 0.25f, 0.25f, 0.0f, 0.0f, 0.5f, 0.5f, 0.5f + 1.0f / 512.0f, 0.5f};
    const std::vector<uint8_t> rgba = vplkit::difference_image_rgba8(test, reference, 2, 2);
    const std::vector<uint8_t> expected = {0, 0, 0, 255, 182, 0, 0, 255, 0, 0, 255, 255, 0, 38, 0, 255};
    CHECK(rgba == expected);
    // Scale 1: pixel 3's 1/512 is on sRGB's linear segment, 12.92 x 1/512 x 255 = 6.4 -> 6.
    const std::vector<uint8_t> unscaled = vplkit::difference_image_rgba8(test, reference, 2, 2, 1.0f);
    CHECK(unscaled[3 * 4 + 1] == 6);
}

TEST_CASE("metrics refuse mismatched, empty and non-finite images") {
    const std::vector<float> two_pixels = {0, 0, 0, 1, 1, 1};
    const std::vector<float> three_pixels = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    CHECK_THROWS_WITH_AS(vplkit::rmse(two_pixels, three_pixels), doctest::Contains("differ in size"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::relative_mse(three_pixels, two_pixels), doctest::Contains("differ in size"),
                         vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::rmse({}, {}), doctest::Contains("empty"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::rmse(std::vector<float>{1, 2}, std::vector<float>{1, 2}),
                         doctest::Contains("not a whole number of RGB pixels"), vplkit::Error);
    // The stated size must match the data.
    CHECK_THROWS_WITH_AS(vplkit::ssim(three_pixels, three_pixels, 2, 2), doctest::Contains("a 2x2 image has 12 values"),
                         vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::ssim({}, {}, 0, 4), doctest::Contains("0x4 image is empty"), vplkit::Error);

    // The first bad value is named by pixel and channel, and which image holds it.
    const uint32_t width = 4, height = 3;
    std::vector<float> bad = pattern_image(width, height);
    const std::vector<float> good = pattern_image(width, height);
    bad[(1 * width + 2) * 3 + 1] = std::numeric_limits<float>::quiet_NaN();
    bad[(2 * width + 3) * 3 + 0] = std::numeric_limits<float>::infinity();
    CHECK_THROWS_WITH_AS(vplkit::ssim(bad, good, width, height),
                         doctest::Contains("the test image's pixel (2, 1) channel G is NaN"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::difference_image_rgba8(good, bad, width, height),
                         doctest::Contains("the reference image's pixel (2, 1) channel G is NaN"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::rmse(good, bad), doctest::Contains("reference image's pixel 6 channel G is NaN"),
                         vplkit::Error);
    bad[(1 * width + 2) * 3 + 1] = 0.0f;
    CHECK_THROWS_WITH_AS(vplkit::relative_rmse(bad, good), doctest::Contains("pixel 11 channel R is infinite"),
                         vplkit::Error);

    // Parameters out of range.
    CHECK_THROWS_WITH_AS(vplkit::relative_rmse(good, constant_image(width, height, 0.0f)),
                         doctest::Contains("relative to a positive mean"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::relative_mse(good, good, 0.0), doctest::Contains("epsilon must be positive"),
                         vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::ssim(good, good, width, height, {.dynamic_range = 0.0}),
                         doctest::Contains("needs dynamic_range, k1 and k2 positive"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::ssim(good, good, width, height, {.k1 = 0.0}),
                         doctest::Contains("needs dynamic_range, k1 and k2 positive"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::difference_image_rgba8(good, good, width, height, 0.0f),
                         doctest::Contains("scale must be positive"), vplkit::Error);
}
