// Whole frames with indirect light from the reference methods, on the Cornell box with a point
// light: exact (the parts add up, the seed fixes the image), BRSM (one bounce, finite, refused
// without punctual lights) and BRSM against one-bounce instant radiosity.
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit_test/context.hpp"
#include "render_test_scene.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using vplkit::render_test::check_parts_add_up;
using vplkit::render_test::kCornellPoint;

namespace {

// A tiny frame with exact indirect light: what the indirect-light cases render.
vplkit::RenderSettings small_exact_settings(uint32_t width = 24, uint32_t height = 20) {
    vplkit::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.method = vplkit::GiMethod::exact;
    return settings;
}

}  // namespace

TEST_CASE("render with exact indirect light: the parts add up and the seed fixes the image") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    auto settings = small_exact_settings();
    settings.vpl_paths = 64;
    settings.vpl_bounces = 2;
    settings.seed = 3;
    uint32_t progress_calls = 0;
    settings.progress = [&](uint32_t done, uint32_t total) {
        ++progress_calls;
        CHECK(done <= total);
    };
    const auto a = renderer.render(scene.camera(), settings);
    CHECK(a.non_finite_pixels == 0);
    CHECK(a.dropped_pixels == 0);
    CHECK(a.vpl_count > 0);
    CHECK(progress_calls > 0);
    CHECK(check_parts_add_up(a) > 0);  // the blocks' shadows get light from the walls
    // Same seed, same VPL set and so the same image, up to float rounding: the tracer appends
    // VPLs with an atomic counter, so their order (and the gather's summation order) may change.
    const auto b = renderer.render(scene.camera(), settings);
    for (size_t i = 0; i < a.radiance.size(); ++i) {
        CHECK(b.radiance[i] == doctest::Approx(a.radiance[i]).epsilon(1e-5).scale(1e-9));
    }
    settings.seed = 4;
    const auto c = renderer.render(scene.camera(), settings);
    CHECK(c.indirect != a.indirect);
    CHECK(c.direct == a.direct);
}

TEST_CASE("render with BRSM indirect light: one bounce, finite, the same seed gives the same image") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    auto settings = small_exact_settings();
    settings.vpl_source = vplkit::VplSource::brsm;
    settings.brsm.vpl_count = 64;
    settings.rsm_resolution = 16;
    settings.seed = 3;
    const auto a = renderer.render(scene.camera(), settings);
    CHECK(a.non_finite_pixels == 0);
    CHECK(a.dropped_pixels == 0);
    CHECK(a.vpl_count == 64);
    CHECK(a.notes.empty());
    CHECK(check_parts_add_up(a) > 0);
    // BRSM writes its VPLs in a fixed order: the same seed gives the same image exactly.
    const auto b = renderer.render(scene.camera(), settings);
    CHECK(b.radiance == a.radiance);
    settings.seed = 4;
    CHECK(renderer.render(scene.camera(), settings).indirect != a.indirect);

    // A spot light aimed out of the box's open front, from in front of it, reaches no surface:
    // it gets its share of VPLs, places none, and the frame says so.
    auto with_spot = scene;
    vplkit::scene::Light spot;
    spot.type = vplkit::scene::LightType::spot;
    spot.name = "away";
    spot.position = {0.0f, 1.0f, 3.0f};
    spot.direction = {0.0f, 0.0f, 1.0f};
    spot.outer_cone_angle = 0.3f;
    with_spot.lights.push_back(spot);
    vplkit::Renderer spot_renderer(ctx, with_spot);
    const auto s = spot_renderer.render(with_spot.camera(), settings);
    REQUIRE(s.notes.size() == 1);
    CHECK(s.notes[0].find("'away': its shadow map holds no surface") != std::string::npos);
    CHECK(s.vpl_count < 64);
    CHECK(s.vpl_count > 0);

    // --vpls-only: the VPLs and the G-buffer's positions, no indirect light.
    settings.vpls_only = true;
    const auto v = renderer.render(scene.camera(), settings);
    CHECK(v.vpls.size() == 64);
    CHECK(v.gbuffer_position.size() == size_t(4) * settings.width * settings.height);
    for (float x : v.indirect) CHECK(x == 0.0f);
}

TEST_CASE("render with BRSM: a scene lit only by emissive triangles is refused by name") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(VPLKIT_SOURCE_DIR "/scenes/cornell_emissive/cornell_emissive.gltf");
    vplkit::Renderer renderer(ctx, scene);
    auto settings = small_exact_settings(16, 16);
    settings.vpl_source = vplkit::VplSource::brsm;
    CHECK_THROWS_WITH_AS(renderer.render(scene.camera(), settings), doctest::Contains("use `vpl_source` ir"),
                         vplkit::Error);
}

TEST_CASE("render: BRSM and one-bounce instant radiosity estimate the same indirect light") {
    // Both VPL sets estimate, without bias, the light the surfaces reflect once (BRSM with its
    // defensive term covers every lit texel): over seeds, the image's total indirect radiance must
    // agree. Tolerance: 4 sigma of the difference of the two means, plus 3% for what differs by
    // construction: BRSM places a VPL at a texel's centre for the whole texel's flux (64^2 faces),
    // and the 1/d^2 clamp near creases weighs that placement. A second, bluer point light makes
    // BRSM share its VPLs and place them light by light.
    vplkit::Context& ctx = vplkit::test::context();
    auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::scene::Light blue;
    blue.name = "blue";
    blue.position = {0.5f, 1.0f, 0.4f};  // above the short block
    blue.color = {0.5f, 0.7f, 1.0f};
    blue.intensity = 3.0f;
    scene.lights.push_back(blue);
    vplkit::Renderer renderer(ctx, scene);
    auto settings = small_exact_settings();
    settings.rsm_resolution = 64;
    settings.brsm.vpl_count = 600;
    settings.vpl_paths = 600;
    settings.vpl_bounces = 1;
    auto image_total = [](const vplkit::RenderedImage& image) {
        double sum = 0;
        for (float v : image.indirect) sum += v;
        return sum;
    };
    const int seeds = 8;
    std::vector<double> totals[2];
    for (int source = 0; source < 2; ++source) {
        settings.vpl_source = source == 0 ? vplkit::VplSource::ir : vplkit::VplSource::brsm;
        for (int seed = 0; seed < seeds; ++seed) {
            settings.seed = uint32_t(seed);
            totals[source].push_back(image_total(renderer.render(scene.camera(), settings)));
        }
    }
    double mean[2], variance_of_mean[2];
    for (int s = 0; s < 2; ++s) {
        mean[s] = 0;
        for (double t : totals[s]) mean[s] += t / seeds;
        double var = 0;
        for (double t : totals[s]) var += (t - mean[s]) * (t - mean[s]) / (seeds - 1);
        variance_of_mean[s] = var / seeds;
    }
    const double bound = 4.0 * std::sqrt(variance_of_mean[0] + variance_of_mean[1]) + 0.03 * mean[0];
    MESSAGE("indirect total: ir " << mean[0] << " +- " << std::sqrt(variance_of_mean[0]) << ", brsm " << mean[1]
                                  << " +- " << std::sqrt(variance_of_mean[1]));
    CHECK(mean[0] > 0);
    CHECK(std::abs(mean[1] - mean[0]) <= bound);
}
