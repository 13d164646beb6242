// Sampled indirect light: sst, rtslc and hybrid in a whole frame, on a 64 x 48 Cornell box with
// the VPLs of 256 light paths x 2 bounces: finite, counted, timed, seeded; against exact on the
// image's total; at half GI resolution; from BRSM VPLs; without VPLs; per frame; sigma_max.
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/stages/upsample.hpp"
#include "vplkit_test/context.hpp"
#include "render_test_scene.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using vplkit::render_test::check_parts_add_up;
using vplkit::render_test::kCornellPoint;

namespace {

constexpr uint32_t kSampledWidth = 64, kSampledHeight = 48;

vplkit::RenderSettings sampled_settings(vplkit::GiMethod method, uint32_t width = kSampledWidth,
                                        uint32_t height = kSampledHeight) {
    vplkit::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.method = method;
    settings.vpl_paths = 256;
    settings.vpl_bounces = 2;
    settings.samples_per_pixel = 8;
    settings.block_size = 8;
    settings.direct_samples = 1;  // the scene has none
    return settings;
}

// Pixels the G-buffer covers (a surface drawn there), from a --vpls-only frame of the same size.
uint32_t covered_pixels(vplkit::Renderer& renderer, const vplkit::scene::Camera& camera,
                        vplkit::RenderSettings settings) {
    settings.vpls_only = true;
    const auto image = renderer.render(camera, settings);
    uint32_t covered = 0;
    for (size_t i = 3; i < image.gbuffer_position.size(); i += 4) covered += image.gbuffer_position[i] > 0.5f ? 1 : 0;
    return covered;
}

double indirect_total(const vplkit::RenderedImage& image) {
    double sum = 0.0;
    for (float v : image.indirect) sum += v;
    return sum;
}

bool all_finite(const std::vector<float>& values) {
    for (float v : values) {
        if (!std::isfinite(v)) return false;
    }
    return true;
}

bool has_timing(const vplkit::RenderedImage& image, const std::string& name) {
    for (const auto& t : image.timings) {
        if (t.name == name) return true;
    }
    return false;
}

constexpr vplkit::GiMethod kSampledMethods[] = {vplkit::GiMethod::sst, vplkit::GiMethod::rtslc,
                                                vplkit::GiMethod::hybrid};

}  // namespace

TEST_CASE("render with sst, rtslc and hybrid: finite, counted, timed, and the seed fixes the image") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    const uint32_t covered = covered_pixels(renderer, scene.camera(), sampled_settings(vplkit::GiMethod::exact));
    REQUIRE(covered > kSampledWidth * kSampledHeight / 2);  // the box fills most of the frame
    REQUIRE(covered < kSampledWidth * kSampledHeight);      // and its open front shows the background
    for (const vplkit::GiMethod method : kSampledMethods) {
        const std::string name = vplkit::gi_method_name(method);
        CAPTURE(name);
        auto settings = sampled_settings(method);
        settings.seed = 3;
        const auto a = renderer.render(scene.camera(), settings);
        CHECK(a.non_finite_pixels == 0);
        CHECK(all_finite(a.indirect));
        CHECK(a.vpl_count > 0);
        CHECK(a.notes.empty());
        CHECK(a.gi_width == kSampledWidth);
        CHECK(a.gi_height == kSampledHeight);
        CHECK(check_parts_add_up(a) > 0);  // the blocks' shadows get light from the walls
        CHECK(*std::max_element(a.indirect.begin(), a.indirect.end()) > 0.0f);
        const vplkit::stages::GiCounts& c = a.gi_counts;
        CHECK(c.dropped_samples == 0);
        CHECK(c.dropped_pixels == 0);
        CHECK(a.dropped_pixels == 0);
        CHECK(c.cut_short == 0);
        // sst: spp traversals from the root per covered pixel; rtslc: one per node of a full cut
        // (the tree has far more than 8 leaves, so every cut has 8 nodes); hybrid: one per node
        // of the pixel's blended cut, which may hold fewer than spp.
        const uint64_t budget = uint64_t(covered) * settings.samples_per_pixel;
        if (method == vplkit::GiMethod::hybrid) {
            CHECK(c.traversals <= budget);
            CHECK(c.traversals > 0);
            CHECK(c.mock_cut_pixels <= covered);
        } else {
            CHECK(c.traversals == budget);
            CHECK(c.mock_cut_pixels == 0);
        }
        CHECK(c.levels > 0);
        CHECK(c.levels_per_traversal() > 0.0);
        MESSAGE(name << ": " << c.traversals << " traversals (covered x spp = " << budget << "), "
                     << c.levels_per_traversal() << " levels per traversal, " << c.dead_branches << " dead branches, "
                     << c.mock_cut_pixels << " mock-cut pixels of " << covered);
        // The sort, the one tree the method reads (the planner leaves the other out) and the
        // method's own passes are timed.
        const bool reads_sst = method != vplkit::GiMethod::rtslc;
        CHECK(has_timing(a, "sort"));
        CHECK(has_timing(a, "build sst") == reads_sst);
        CHECK(has_timing(a, "light tree levels") == !reads_sst);
        if (method == vplkit::GiMethod::sst) CHECK(has_timing(a, "sst gi"));
        if (method == vplkit::GiMethod::rtslc) {
            CHECK(has_timing(a, "rtslc cuts"));
            CHECK(has_timing(a, "rtslc gi"));
        }
        if (method == vplkit::GiMethod::hybrid) {
            CHECK(has_timing(a, "hybrid cuts"));
            CHECK(has_timing(a, "hybrid gi"));
        }
        // The same seed: the same image, bit for bit; another seed: another one.
        const auto b = renderer.render(scene.camera(), settings);
        CHECK(b.indirect == a.indirect);
        CHECK(b.radiance == a.radiance);
        CHECK(b.gi_counts.traversals == a.gi_counts.traversals);
        CHECK(b.gi_counts.levels == a.gi_counts.levels);
        settings.seed = 4;
        const auto other = renderer.render(scene.camera(), settings);
        CHECK(other.indirect != a.indirect);
        CHECK(other.direct == a.direct);
    }
}

TEST_CASE("render: sst, rtslc and hybrid agree with exact on the image's total indirect light") {
    // Per seed, every method renders that seed's VPL set (the tracer's: the same for all four)
    // and its image total is divided by exact's; the ratios are averaged over 8 seeds. rtslc is
    // unbiased for a given VPL set, so only its noise remains; sst is biased by design (a
    // substitute position stands for a cluster) and hybrid's blended cuts need not partition the
    // tree, so their tolerance also bounds a bias here.
    // Measured on lavapipe (64 x 48, 348 VPLs at seed 3, 8 spp, 8 x 8 blocks), mean ratio
    // (sd of one seed's): sst 0.9972 (0.024), rtslc 1.0015 (0.015), hybrid 1.0026 (0.017); one
    // seed's ratio ranged over 0.963..1.030 (sst), 0.976..1.028 (rtslc), 0.980..1.022 (hybrid).
    // Tolerance: rtslc 3% (4 standard errors of the 8-seed mean are 2.2%), sst and hybrid 5%
    // (their bias in this scene is well under 1%: the margin is for noise and other drivers),
    // one seed 10%.
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    const int seeds = 8;
    const double tolerance[3] = {0.05, 0.03, 0.05};  // sst, rtslc, hybrid
    double ratio_sum[3] = {0, 0, 0}, ratio_sq[3] = {0, 0, 0};
    for (int seed = 0; seed < seeds; ++seed) {
        auto settings = sampled_settings(vplkit::GiMethod::exact);
        settings.seed = uint32_t(seed);
        const double exact = indirect_total(renderer.render(scene.camera(), settings));
        REQUIRE(exact > 0.0);
        for (int m = 0; m < 3; ++m) {
            settings.method = kSampledMethods[m];
            const double ratio = indirect_total(renderer.render(scene.camera(), settings)) / exact;
            CAPTURE(seed);
            CAPTURE(std::string(vplkit::gi_method_name(settings.method)));
            CHECK(ratio == doctest::Approx(1.0).epsilon(0.10));
            ratio_sum[m] += ratio;
            ratio_sq[m] += ratio * ratio;
        }
    }
    for (int m = 0; m < 3; ++m) {
        const std::string name = vplkit::gi_method_name(kSampledMethods[m]);
        const double mean = ratio_sum[m] / seeds;
        const double sd = std::sqrt(std::max(0.0, (ratio_sq[m] - seeds * mean * mean) / (seeds - 1)));
        MESSAGE(name << ": mean ratio to exact " << mean << " over " << seeds << " seeds, sd " << sd);
        CAPTURE(name);
        CHECK(mean == doctest::Approx(1.0).epsilon(tolerance[m]));
    }
}

TEST_CASE("render at half GI resolution: half-size indirect light, upsampled, close to full resolution") {
    // The same VPLs (seed) at full and at half GI resolution; the half image's total over the
    // full one's. Measured on lavapipe (64 x 48, GI at 32 x 24): exact 0.972..0.982 over 9 seeds
    // (always ~2% low: at this size most covered pixels (1715 of 2304) find no similar half
    // sample within the upsampler's distance and take the nearest one, 13 get none); the sampled
    // methods, noisier at a quarter of the samples, one seed 0.90..1.12, the mean of seeds
    // 10..13 sst 0.956, rtslc 0.985, hybrid 0.990 (of 10..17: 0.987, 0.965, 0.985).
    // Tolerance: exact 5%, the sampled methods' 4-seed mean 10%.
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    const uint32_t covered = covered_pixels(renderer, scene.camera(), sampled_settings(vplkit::GiMethod::exact));
    for (const vplkit::GiMethod method :
         {vplkit::GiMethod::exact, vplkit::GiMethod::sst, vplkit::GiMethod::rtslc, vplkit::GiMethod::hybrid}) {
        const std::string name = vplkit::gi_method_name(method);
        CAPTURE(name);
        const bool exact = method == vplkit::GiMethod::exact;
        const uint32_t seeds = exact ? 1 : 4;
        double ratio_sum = 0.0;
        for (uint32_t seed = 10; seed < 10 + seeds; ++seed) {
            CAPTURE(seed);
            auto settings = sampled_settings(method);
            settings.seed = seed;
            const auto full = renderer.render(scene.camera(), settings);
            settings.half_resolution_gi = true;
            const auto half = renderer.render(scene.camera(), settings);
            CHECK(half.gi_width == vplkit::stages::half_resolution(kSampledWidth));
            CHECK(half.gi_height == vplkit::stages::half_resolution(kSampledHeight));
            CHECK(half.gi_width == kSampledWidth / 2);
            CHECK(half.gi_height == kSampledHeight / 2);
            CHECK(half.width == kSampledWidth);
            CHECK(half.height == kSampledHeight);
            CHECK(half.indirect.size() == full.indirect.size());
            CHECK(half.non_finite_pixels == 0);
            CHECK(all_finite(half.indirect));
            CHECK(half.notes.empty());
            CHECK(half.direct == full.direct);
            CHECK(check_parts_add_up(half) > 0);
            CHECK(has_timing(half, "gbuffer downsample"));
            CHECK(has_timing(half, "upsample"));
            CHECK_FALSE(has_timing(full, "upsample"));
            CHECK(half.upsample_counts.fallback_pixels + half.upsample_counts.empty_pixels <= covered);
            if (!exact) {
                const auto& c = half.gi_counts;
                CHECK(c.dropped_samples == 0);
                CHECK(c.cut_short == 0);
                CHECK(c.traversals > 0);
                CHECK(c.levels_per_traversal() > 0.0);
                // Only the half G-buffer's pixels are shaded: a quarter of the full frame's.
                CHECK(c.traversals <= uint64_t(half.gi_width) * half.gi_height * settings.samples_per_pixel);
                CHECK(c.traversals < full.gi_counts.traversals / 2);
                if (method == vplkit::GiMethod::hybrid) CHECK(c.mock_cut_pixels <= half.gi_width * half.gi_height);
            }
            const double ratio = indirect_total(half) / indirect_total(full);
            ratio_sum += ratio;
            if (exact) {
                MESSAGE("exact: half / full total " << ratio << "; " << half.upsample_counts.fallback_pixels << " of "
                                                    << covered << " covered pixels took the nearest sample, "
                                                    << half.upsample_counts.empty_pixels << " none");
            }
        }
        const double mean = ratio_sum / seeds;
        MESSAGE(name << ": half / full total " << mean << " (mean of " << seeds << " seeds)");
        CHECK(mean == doctest::Approx(1.0).epsilon(exact ? 0.05 : 0.10));
    }
}

TEST_CASE("render with hybrid from BRSM VPLs: finite, counted, the seed fixes the image") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    auto settings = sampled_settings(vplkit::GiMethod::hybrid);
    settings.vpl_source = vplkit::VplSource::brsm;
    settings.brsm.vpl_count = 256;
    settings.rsm_resolution = 32;
    settings.seed = 3;
    const uint32_t covered = covered_pixels(renderer, scene.camera(), settings);
    const auto a = renderer.render(scene.camera(), settings);
    CHECK(a.vpl_count == 256);
    CHECK(a.notes.empty());
    CHECK(a.non_finite_pixels == 0);
    CHECK(all_finite(a.indirect));
    CHECK(check_parts_add_up(a) > 0);
    CHECK(a.gi_counts.dropped_samples == 0);
    CHECK(a.gi_counts.cut_short == 0);
    CHECK(a.gi_counts.traversals > 0);
    CHECK(a.gi_counts.traversals <= uint64_t(covered) * settings.samples_per_pixel);
    CHECK(a.gi_counts.levels_per_traversal() > 0.0);
    CHECK(a.gi_counts.mock_cut_pixels <= covered);
    CHECK(has_timing(a, "hybrid gi"));
    // BRSM writes its VPLs in a fixed order: the same seed gives the same image exactly.
    const auto b = renderer.render(scene.camera(), settings);
    CHECK(b.radiance == a.radiance);
    settings.seed = 4;
    CHECK(renderer.render(scene.camera(), settings).indirect != a.indirect);
    // And it agrees with exact on the same (seed's) BRSM VPLs. Measured on lavapipe, hybrid /
    // exact image total for seeds 0..7: 0.983, 0.988, 0.999, 0.979, 0.988, 0.999, 0.984, 0.998
    // (~1% low on average). Tolerance: the mean of seeds 0..3 within
    // 5%, each within 10%.
    double ratio_sum = 0.0;
    for (uint32_t seed = 0; seed < 4; ++seed) {
        CAPTURE(seed);
        settings.seed = seed;
        settings.method = vplkit::GiMethod::exact;
        const double exact = indirect_total(renderer.render(scene.camera(), settings));
        REQUIRE(exact > 0.0);
        settings.method = vplkit::GiMethod::hybrid;
        const double ratio = indirect_total(renderer.render(scene.camera(), settings)) / exact;
        CHECK(ratio == doctest::Approx(1.0).epsilon(0.10));
        ratio_sum += ratio;
    }
    MESSAGE("BRSM VPLs: hybrid / exact total " << ratio_sum / 4 << " (mean of 4 seeds)");
    CHECK(ratio_sum / 4 == doctest::Approx(1.0).epsilon(0.05));
}

TEST_CASE("render with sampled indirect light when no VPL is placed: a note and no indirect light") {
    // The scene's only light is a spot aimed out of the box's open front from in front of it:
    // its light paths meet nothing, so no VPL is placed.
    vplkit::Context& ctx = vplkit::test::context();
    auto scene = vplkit::scene::load_gltf(kCornellPoint);
    scene.lights.clear();
    vplkit::scene::Light spot;
    spot.type = vplkit::scene::LightType::spot;
    spot.name = "away";
    spot.position = {0.0f, 1.0f, 3.0f};
    spot.direction = {0.0f, 0.0f, 1.0f};
    spot.outer_cone_angle = 0.3f;
    scene.lights.push_back(spot);
    vplkit::Renderer renderer(ctx, scene);
    for (const vplkit::GiMethod method : kSampledMethods) {
        for (const bool half : {false, true}) {
            const std::string name = vplkit::gi_method_name(method);
            CAPTURE(name);
            CAPTURE(half);
            auto settings = sampled_settings(method);
            settings.half_resolution_gi = half;
            const auto image = renderer.render(scene.camera(), settings);
            CHECK(image.vpl_count == 0);
            REQUIRE(image.notes.size() == 1);
            CHECK(image.notes[0].find("no VPLs were placed") != std::string::npos);
            CHECK(image.non_finite_pixels == 0);
            // The samplers ran over trees of padding alone (the frame reads no count back
            // before they run): every traversal found no light, none was dropped.
            CHECK(image.gi_counts.dropped_samples == 0);
            CHECK(std::count_if(image.indirect.begin(), image.indirect.end(), [](float v) { return v != 0.0f; }) == 0);
        }
    }
    // BRSM VPLs: the spot's shadow map sees nothing, so the light has none, and the frame none.
    auto settings = sampled_settings(vplkit::GiMethod::hybrid);
    settings.vpl_source = vplkit::VplSource::brsm;
    settings.brsm.vpl_count = 64;
    settings.rsm_resolution = 16;
    const auto image = renderer.render(scene.camera(), settings);
    CHECK(image.vpl_count == 0);
    REQUIRE(image.notes.size() == 2);
    CHECK(image.notes[0].find("'away': its shadow map holds no surface") != std::string::npos);
    CHECK(image.notes[1].find("no VPLs were placed") != std::string::npos);
    CHECK(image.non_finite_pixels == 0);
    CHECK(std::count_if(image.indirect.begin(), image.indirect.end(), [](float v) { return v != 0.0f; }) == 0);
    // A bad sampling option is refused although no VPL would ever reach the stage that checks it.
    auto bad = sampled_settings(vplkit::GiMethod::rtslc);
    bad.interleave = 3;
    CHECK_THROWS_WITH_AS(renderer.render(scene.camera(), bad), doctest::Contains("interleave 3"), vplkit::Error);
}

TEST_CASE("render: the frame counter gives sst, rtslc and hybrid other random numbers each frame, the same VPLs") {
    // Temporal accumulation averages frames: frames that drew the same numbers would average to
    // one frame's noise. The same seed and frame repeat the image bit for bit.
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    for (const vplkit::GiMethod method : kSampledMethods) {
        const std::string name = vplkit::gi_method_name(method);
        CAPTURE(name);
        auto settings = sampled_settings(method);
        settings.seed = 5;
        const auto frame0 = renderer.render(scene.camera(), settings);
        settings.frame = 1;
        const auto frame1 = renderer.render(scene.camera(), settings);
        CHECK(frame1.reused_vpls);  // the VPLs follow the seed, not the frame
        CHECK(frame1.indirect != frame0.indirect);
        size_t differing = 0, lit = 0;
        for (size_t i = 0; i < frame0.indirect.size(); ++i) {
            lit += frame0.indirect[i] > 0.0f;
            differing += frame0.indirect[i] != frame1.indirect[i];
        }
        CHECK(differing > lit / 2);  // most lit pixels, not a few
        const auto again = renderer.render(scene.camera(), settings);
        CHECK(again.indirect == frame1.indirect);
    }
}

TEST_CASE("render: sigma_max is a fraction of the scene's size unless given absolutely") {
    // The thesis' absolute 0.3 was chosen for its ~25 m Sponza; in a 2 m room it merges clusters
    // as thick as 15% of the room, whose substitutes lost light (README, Energy).
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    auto settings = sampled_settings(vplkit::GiMethod::hybrid);
    const auto relative = renderer.render(scene.camera(), settings);
    const float expected = vplkit::kSigmaMaxSceneFraction * renderer.bvh().scene_scale;
    CHECK(relative.sst_sigma_max == expected);
    settings.sigma_max_scene_fraction.reset();
    settings.sst.sigma_max = expected;
    const auto absolute = renderer.render(scene.camera(), settings);
    CHECK(absolute.sst_sigma_max == expected);
    CHECK(absolute.indirect == relative.indirect);
    settings.sst.sigma_max = 0.3f;
    CHECK(renderer.render(scene.camera(), settings).sst_sigma_max == 0.3f);
    settings.sigma_max_scene_fraction = -1.0f;
    CHECK_THROWS_AS(renderer.render(scene.camera(), settings), vplkit::Error);
}
