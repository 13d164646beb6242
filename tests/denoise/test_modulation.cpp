// demodulate.comp, remodulate.comp, firefly_clamp.comp and firefly_spread.comp (the clamp's second
// pass, whose output is `spread`) against the double reference
// (tests/reference/denoise_reference.cpp) on 64 x 64 images, and the clamp's conservation of light.
// Tolerances: demodulation is one float division per channel (relative 1e-6: two roundings);
// the firefly limit sums 24 float luminances (relative 1e-5 of the limit, absolute 1e-6).

#include "denoise_setup.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/denoise.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <random>

using namespace vplkit;
using namespace vplkit::test;

namespace {

constexpr uint32_t kSize = 64;

// Covered everywhere but a 10 x 10 corner (background).
DenoiseImage coverage() {
    DenoiseImage p(kSize, kSize);
    for (int y = 0; y < int(kSize); ++y)
        for (int x = 0; x < int(kSize); ++x) p.at(x, y) = {double(x), double(y), -3.0, (x < 10 && y < 10) ? 0.0 : 1.0};
    return p;
}

DenoiseImage random_image(uint32_t seed, double scale) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, scale);
    DenoiseImage image(kSize, kSize);
    for (auto& t : image.texels) t = {u(rng), u(rng), u(rng), 0.0};
    return to_float_precision(image);
}

}  // namespace

TEST_CASE("denoise demodulate: radiance over albedo, and remodulate gives it back") {
    Context& ctx = context();
    stages::DenoiseOptions options;
    // Albedos on the half-float grid (k / 64), some channels 0 or below albedo_floor (divided by the floor).
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> k(0, 64);
    DenoiseImage albedo(kSize, kSize);
    for (auto& t : albedo.texels) t = {k(rng) / 64.0, k(rng) / 64.0, (k(rng) % 4 == 0) ? 0.0 : k(rng) / 64.0, 1.0};
    const DenoiseImage radiance = random_image(4, 10.0), position = coverage();
    auto radiance_image = upload_image(ctx, radiance, "radiance");
    auto albedo_image = upload_albedo(ctx, albedo, "albedo");
    auto position_image = upload_image(ctx, position, "position");
    auto irradiance_image = float4_image(ctx, kSize, kSize, "irradiance");
    auto back_image = float4_image(ctx, kSize, kSize, "remodulated");
    PassList passes("demodulate test");
    stages::add_demodulate_pass(ctx, passes, radiance_image, albedo_image, position_image, irradiance_image, options);
    stages::add_remodulate_pass(ctx, passes, irradiance_image, albedo_image, back_image, options);
    passes.run(ctx);
    const DenoiseImage irradiance = download_image(irradiance_image);
    const DenoiseImage expected = reference::demodulate(radiance, albedo, position, options.albedo_floor);
    CHECK(max_relative_error(irradiance, expected, 1e-12) < 1e-6);
    // The round trip is the identity on covered pixels (background: 0).
    const DenoiseImage back = download_image(back_image);
    const DenoiseImage expected_back = reference::remodulate(expected, albedo, options.albedo_floor);
    CHECK(max_relative_error(back, expected_back, 1e-12) < 1e-6);
    for (int y = 10; y < int(kSize); ++y)
        for (int c = 0; c < 3; ++c) CHECK(back.at(20, y)[c] == doctest::Approx(radiance.at(20, y)[c]).epsilon(1e-6));
    CHECK(back.at(3, 3)[0] == 0.0);
}

namespace {

struct FireflyImages {
    DenoiseImage clamped, excess, spread;
};

FireflyImages run_firefly_clamp(const DenoiseImage& irradiance, const DenoiseImage& moments, const DenoiseImage& albedo,
                                const DenoiseImage& position, const stages::DenoiseOptions& options) {
    Context& ctx = context();
    auto in = upload_image(ctx, irradiance, "irradiance");
    auto moments_image = upload_image(ctx, moments, "moments");
    auto albedo_image = upload_albedo(ctx, albedo, "albedo");
    auto pos = upload_image(ctx, position, "position");
    auto clamped = float4_image(ctx, kSize, kSize, "clamped");
    auto excess = float4_image(ctx, kSize, kSize, "excess");
    auto spread = float4_image(ctx, kSize, kSize, "spread");
    PassList passes("firefly test");
    stages::add_firefly_clamp_passes(ctx, passes, in, moments_image, albedo_image, pos, clamped, excess, spread,
                                     options);
    passes.run(ctx);
    return {download_image(clamped), download_image(excess), download_image(spread)};
}

// Albedos on the half-float grid, k / 64 for k in [lowest, 64] per channel.
DenoiseImage random_albedo(uint32_t seed, int lowest) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> k(lowest, 64);
    DenoiseImage albedo(kSize, kSize);
    for (auto& t : albedo.texels) t = {k(rng) / 64.0, k(rng) / 64.0, k(rng) / 64.0, 1.0};
    return albedo;
}

// Moments of a first frame (n = 1: no history to bound the clamp).
DenoiseImage first_frame_moments() {
    DenoiseImage m(kSize, kSize);
    for (auto& t : m.texels) t = {0.0, 0.0, 1.0, 0.0};
    return m;
}

}  // namespace

TEST_CASE(
    "denoise firefly clamp: firefly_clamp and firefly_spread against the reference, and a lone firefly is cut to the "
    "limit") {
    stages::DenoiseOptions options;
    DenoiseImage irradiance = random_image(7, 1.0);
    // Two planted fireflies in uniform noise (luminance at most its mean + 2.3 sigma).
    irradiance.at(30, 30) = {50.0, 50.0, 50.0, 0.0};
    irradiance.at(12, 40) = {0.0, 80.0, 0.0, 0.0};
    const DenoiseImage position = coverage(), albedo = random_albedo(8, 0);  // some channels 0: the floor
    const FireflyImages out = run_firefly_clamp(irradiance, first_frame_moments(), albedo, position, options);
    const auto expected = reference::firefly_clamp(irradiance, first_frame_moments(), albedo, position,
                                                   options.firefly_k_sigma, options.albedo_floor, 4);
    CHECK(max_relative_error(out.clamped, expected.clamped, 1e-6) < 1e-5);
    // The shares are differences of the input and the clamped value: absolute error ~1e-6 x 80;
    // a neighbour divides them by its divisor (down to the albedo floor): ~1e-6 x 80 / floor.
    CHECK(max_relative_error(out.excess, expected.excess, 1e-3) < 1e-4);
    CHECK(max_relative_error(out.spread, expected.spread, 1e-2) < 1e-4);
    int clamped_pixels = 0, expected_pixels = 0;
    for (size_t i = 0; i < out.excess.texels.size(); ++i) {
        clamped_pixels += out.excess.texels[i][3] > 0.0 ? 1 : 0;
        expected_pixels += expected.excess.texels[i][3] > 0.0 ? 1 : 0;
    }
    CHECK(clamped_pixels == expected_pixels);
    CHECK(out.excess.at(12, 40)[3] > 0.0);
    // Cut to the limit: about the noise's mean + 4 sigma (0.5 + 4 x 0.29 ~ 1.65 at most).
    CHECK(reference::luminance(out.clamped.at(30, 30)) < 2.0);
    CHECK(out.excess.at(30, 30)[3] ==
          doctest::Approx(50.0 - reference::luminance(out.clamped.at(30, 30))).epsilon(1e-5));
}

TEST_CASE("denoise firefly clamp: keeps the frame's light and still limits an isolated spike") {
    // The clamp must not bias an accumulation: what it takes off an outlier goes to the outlier's
    // neighbours, so the remodulated image's sum (irradiance x albedo divisor: what is displayed)
    // is the input's, per channel (the old clamp dropped it, 5% of Sponza's indirect
    // light). Noise in [0, 1] per channel, albedos 1/4..1, a spike of 200 (a tenth of the image's
    // light), a coloured one, one at the image edge and one beside the background corner (fewer
    // neighbours). Sums of 4096 floats of O(1): relative 1e-6.
    stages::DenoiseOptions options;
    DenoiseImage irradiance = random_image(21, 1.0);
    irradiance.at(30, 30) = {200.0, 200.0, 200.0, 0.0};
    irradiance.at(50, 12) = {0.0, 0.0, 90.0, 0.0};
    irradiance.at(63, 63) = {40.0, 40.0, 40.0, 0.0};
    irradiance.at(10, 10) = {40.0, 40.0, 40.0, 0.0};  // beside the 10 x 10 background corner
    const DenoiseImage position = coverage(), albedo = random_albedo(22, 16);
    const FireflyImages out = run_firefly_clamp(irradiance, first_frame_moments(), albedo, position, options);
    const DenoiseImage radiance_in = reference::remodulate(irradiance, albedo, options.albedo_floor);
    const DenoiseImage radiance_out = reference::remodulate(out.spread, albedo, options.albedo_floor);
    double sum_in[3] = {0, 0, 0}, sum_out[3] = {0, 0, 0}, taken = 0.0, total = 0.0;
    for (int y = 0; y < int(kSize); ++y) {
        for (int x = 0; x < int(kSize); ++x) {
            if (position.at(x, y)[3] <= 0.5) continue;
            for (int c = 0; c < 3; ++c) {
                sum_in[c] += radiance_in.at(x, y)[c];
                sum_out[c] += radiance_out.at(x, y)[c];
            }
            taken += out.excess.at(x, y)[3];
            total += reference::luminance(irradiance.at(x, y));
        }
    }
    MESSAGE("luminance moved: " << 100.0 * taken / total
                                << "% of the image's; radiance sums out / in: " << sum_out[0] / sum_in[0] << ", "
                                << sum_out[1] / sum_in[1] << ", " << sum_out[2] / sum_in[2]);
    CHECK(taken > 0.1 * total);  // the spikes were clamped: this is no empty check
    for (int c = 0; c < 3; ++c) {
        CAPTURE(c);
        CHECK(sum_out[c] == doctest::Approx(sum_in[c]).epsilon(1e-6));
    }
    // The spike itself ends at its limit (noise mean + 4 sigma ~ 1.65 at most), its light on its
    // 24 neighbours: at most 200 / 24 ~ 8.3 radiance each (albedo <= 1), far below the spike.
    CHECK(reference::luminance(out.spread.at(30, 30)) < 2.0);
    for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) CHECK(reference::luminance(radiance_out.at(30 + dx, 30 + dy)) < 10.0);
    // Nothing spread onto the background.
    CHECK(out.spread.at(9, 9)[0] == 0.0);
}

TEST_CASE("denoise firefly clamp: a converged pixel's own statistics bound the clamp") {
    // A highlight the spatial test calls an outlier (luminance 50 in noise [0, 1]), with a history
    // of n = 256 frames of variance 4 (standard error 2 / 16 = 0.125): pulled down by at most 4 x
    // 0.125 = 0.5, not to the spatial limit; the same pixel with n = 3 (below min_history 4) is cut
    // to the spatial limit. Against the reference as well.
    stages::DenoiseOptions options;
    DenoiseImage irradiance = random_image(31, 1.0);
    irradiance.at(30, 30) = {50.0, 50.0, 50.0, 0.0};
    const DenoiseImage position = coverage(), albedo = random_albedo(32, 16);
    for (double n : {256.0, 3.0}) {
        CAPTURE(n);
        DenoiseImage moments(kSize, kSize);
        for (auto& t : moments.texels) t = {0.5, 0.25 + 4.0, n, 0.0};  // variance 4 everywhere
        const FireflyImages out = run_firefly_clamp(irradiance, moments, albedo, position, options);
        const auto expected = reference::firefly_clamp(irradiance, moments, albedo, position, options.firefly_k_sigma,
                                                       options.albedo_floor, options.min_temporal_history);
        CHECK(max_relative_error(out.clamped, expected.clamped, 1e-6) < 1e-5);
        CHECK(max_relative_error(out.spread, expected.spread, 1e-2) < 1e-4);
        const double kept = reference::luminance(out.clamped.at(30, 30));
        if (n == 256.0) {
            CHECK(kept == doctest::Approx(50.0 - 4.0 * 0.125).epsilon(1e-5));
        } else {
            CHECK(kept < 2.0);
        }
    }
}

TEST_CASE("denoise options: bad values are refused by name") {
    Context& ctx = context();
    auto a = float4_image(ctx, 4, 4, "a");
    auto b = float4_image(ctx, 4, 4, "b");
    auto small = float4_image(ctx, 4, 3, "small");
    PassList passes;
    stages::DenoiseOptions options;
    options.max_history = 0;
    CHECK_THROWS_WITH_AS(stages::add_firefly_clamp_passes(ctx, passes, a, a, a, b, a, b, a, options),
                         doctest::Contains("max_history"), Error);
    CHECK_THROWS_WITH_AS(stages::add_firefly_clamp_passes(ctx, passes, a, a, a, small, b, a, b, {}),
                         doctest::Contains("'small'"), Error);
    auto c = float4_image(ctx, 4, 4, "c");
    auto d = float4_image(ctx, 4, 4, "d");
    CHECK_THROWS_WITH_AS(stages::add_atrous_passes(ctx, passes, a, a, a, {c, d}, b, 0, {}), doctest::Contains("step"),
                         Error);
    CHECK_THROWS_WITH_AS(stages::add_atrous_passes(ctx, passes, a, a, a, {c, b}, b, 1, {}),
                         doctest::Contains("scratch image 'b' is also its source or output"), Error);
}
