// atrous*.comp and variance_estimate.comp: a constant image is unchanged, a depth step and a
// crease (normal edge) are not crossed, the image's sum is kept, and each pass against the double
// reference (tests/reference/denoise_reference.cpp) on 64 x 64.
// Tolerances: against the reference 1e-4 relative (+1e-4 absolute on O(1) values): the edge weights
// are exp / pow of float arguments; constant: 1e-6 relative (a normalized float sum).

#include "denoise_setup.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/denoise.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

using namespace vplkit;
using namespace vplkit::test;

namespace {

constexpr uint32_t kSize = 64;

stages::DenoiseOptions test_options() {
    stages::DenoiseOptions options;
    options.scene_scale = 10.0f;  // sigma_plane 0.05
    return options;
}

reference::FilterParameters parameters_of(const stages::DenoiseOptions& o) {
    return {double(o.sigma_plane_fraction) * o.scene_scale, o.sigma_normal, o.sigma_luminance, o.min_temporal_history};
}

// Back plane z = -5 facing the camera; columns x >= 40 a closer face (z = -3); rows y >= 44 a
// crease: the same plane z = -5, normal turned to +x; a 6 x 6 background corner.
PlaneScene edges_scene() {
    return {[](int x, int y) { return (x < 6 && y < 6) ? 0.0f : (x >= 40 ? -3.0f : -5.0f); },
            [](int x, int y) { return (y >= 44 && x < 40) ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1); }};
}

DenoiseGeometry geometry() {
    return plane_geometry(denoise_camera({0, 0, 0}, kSize, kSize), kSize, kSize, edges_scene());
}

DenoiseImage run_atrous(const DenoiseImage& source, const DenoiseGeometry& g, int step,
                        const stages::DenoiseOptions& options) {
    Context& ctx = context();
    auto in = upload_image(ctx, source, "source");
    auto position = upload_image(ctx, g.position, "position");
    auto normal = upload_image(ctx, g.normal, "normal");
    auto out = float4_image(ctx, kSize, kSize, "filtered");
    auto scratch_variance = float4_image(ctx, kSize, kSize, "scratch variance");
    auto scratch_weights = float4_image(ctx, kSize, kSize, "scratch weights");
    PassList passes("a-trous test");
    stages::add_atrous_passes(ctx, passes, in, position, normal, {scratch_variance, scratch_weights}, out, step,
                              options);
    passes.run(ctx);
    return download_image(out);
}

// Noisy irradiance around a per-region level, with the noise's variance in .a.
DenoiseImage noisy(const DenoiseGeometry& g, uint32_t seed, double amplitude) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-amplitude, amplitude);
    DenoiseImage image(kSize, kSize);
    for (int y = 0; y < int(kSize); ++y) {
        for (int x = 0; x < int(kSize); ++x) {
            if (!g.covered(x, y)) continue;
            const double level = x >= 40 ? 3.0 : (y >= 44 ? 0.5 : 1.0);
            image.at(x, y) = {level + u(rng), level + u(rng), level + u(rng), amplitude * amplitude / 3.0};
        }
    }
    return to_float_precision(image);
}

}  // namespace

TEST_CASE("denoise a-trous: against the double reference at steps 1 and 4") {
    const DenoiseGeometry g = geometry();
    const DenoiseImage source = noisy(g, 21, 0.4);
    const auto options = test_options();
    for (int step : {1, 4}) {
        CAPTURE(step);
        const DenoiseImage out = run_atrous(source, g, step, options);
        const DenoiseImage expected = reference::atrous(source, g, step, parameters_of(options));
        CHECK(max_relative_error(out, expected, 1e-4) < 1e-4);
    }
}

TEST_CASE("denoise a-trous: a constant image is unchanged") {
    const DenoiseGeometry g = geometry();
    DenoiseImage constant(kSize, kSize);
    for (int y = 0; y < int(kSize); ++y)
        for (int x = 0; x < int(kSize); ++x)
            if (g.covered(x, y)) constant.at(x, y) = {0.3, 0.6, 0.9, 0.01};
    for (int step : {1, 2, 8}) {
        CAPTURE(step);
        const DenoiseImage out = run_atrous(constant, g, step, test_options());
        CHECK(max_relative_error(out, constant, 1e-12, false) < 1e-6);
    }
}

TEST_CASE("denoise a-trous: a depth step and a crease are not crossed") {
    // Each region constant, with a variance so large that the luminance weight is ~1 everywhere:
    // only the geometry weights keep the regions apart.
    const DenoiseGeometry g = geometry();
    DenoiseImage source(kSize, kSize);
    for (int y = 0; y < int(kSize); ++y)
        for (int x = 0; x < int(kSize); ++x)
            if (g.covered(x, y)) {
                const double level = x >= 40 ? 3.0 : (y >= 44 ? 0.5 : 1.0);
                source.at(x, y) = {level, level, level, 1e8};
            }
    for (int step : {1, 2, 4, 8, 16}) {
        CAPTURE(step);
        const DenoiseImage out = run_atrous(source, g, step, test_options());
        double worst = 0.0;
        for (size_t i = 0; i < out.texels.size(); ++i)
            worst = std::max(worst, std::abs(out.texels[i][0] - source.texels[i][0]));
        CHECK(worst < 1e-5);
    }
    // The same without the edges' geometry does blend: the test can fail.
    DenoiseGeometry flat = g;
    for (auto& n : flat.normal.texels) n = {0, 0, 1, 0};
    for (int y = 0; y < int(kSize); ++y)
        for (int x = 40; x < int(kSize); ++x) flat.position.at(x, y) = g.position.at(39, y);
    const DenoiseImage blended = run_atrous(source, flat, 1, test_options());
    CHECK(blended.at(39, 20)[0] > 1.1);
}

TEST_CASE("denoise a-trous: five iterations keep the image mean") {
    // The weights are symmetric and normalized by max(W_p, W_q) with the rest kept by the centre,
    // so every pixel hands out exactly its own light: the sum is kept up to float rounding. SVGF's
    // normalization by W_p alone moved it (0.9995 here, 0.77 on heavy-tailed noise:
    // test_svgf_energy.cpp).
    const DenoiseGeometry g = geometry();
    DenoiseImage image = noisy(g, 22, 0.4);
    double before = 0.0;
    for (const auto& t : image.texels) before += reference::luminance(t);
    const auto options = test_options();
    for (int i = 0; i < 5; ++i) image = run_atrous(image, g, 1 << i, options);
    double after = 0.0, spread = 0.0;
    for (const auto& t : image.texels) after += reference::luminance(t);
    MESSAGE("image mean after / before five a-trous iterations: 1 + " << after / before - 1.0);
    CHECK(after / before == doctest::Approx(1.0).epsilon(1e-6));
    // And the noise fell: the flat region's pixel-to-pixel spread, against the 0.4 / sqrt(3) input.
    for (int x = 10; x < 30; ++x) spread += std::abs(image.at(x, 20)[0] - 1.0);
    CHECK(spread / 20.0 < 0.1);
}

TEST_CASE("denoise variance: spatial where the history is short, temporal elsewhere, against the reference") {
    Context& ctx = context();
    const DenoiseGeometry g = geometry();
    const DenoiseImage accumulated = noisy(g, 23, 0.4);
    DenoiseImage moments(kSize, kSize);
    std::mt19937 rng(24);
    std::uniform_int_distribution<int> n(1, 8);
    for (size_t i = 0; i < moments.texels.size(); ++i) {
        const double l = reference::luminance(accumulated.texels[i]);
        moments.texels[i] = {l, l * l + 0.01 * (i % 7), double(n(rng)), 0.0};
    }
    moments = to_float_precision(moments);
    auto acc = upload_image(ctx, accumulated, "accumulated");
    auto mom = upload_image(ctx, moments, "moments");
    auto position = upload_image(ctx, g.position, "position");
    auto normal = upload_image(ctx, g.normal, "normal");
    auto out = float4_image(ctx, kSize, kSize, "estimated");
    const auto options = test_options();
    PassList passes("variance test");
    stages::add_variance_estimate_pass(ctx, passes, acc, mom, position, normal, out, options);
    passes.run(ctx);
    const DenoiseImage result = download_image(out);
    const DenoiseImage expected = reference::variance_estimate(accumulated, moments, g, parameters_of(options));
    CHECK(max_relative_error(result, expected, 1e-3) < 1e-3);
    int kept = 0;
    for (size_t i = 0; i < result.texels.size(); ++i)
        if (moments.texels[i][2] >= 4 && g.position.texels[i][3] > 0.5)
            kept += result.texels[i][3] == accumulated.texels[i][3];
    CHECK(kept > 1000);
}
