// A calibration on the test device (lavapipe) at 32x32 in the point-lit Cornell box: every
// configuration of its space gets a prediction, the noise it measured is there, the cache gives
// the same model back without rendering, and a changed plan calibrates again.

#include "vplkit/budget_calibration.hpp"

#include "vplkit/budget.hpp"
#include "vplkit/cache_key.hpp"
#include "vplkit/context.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <unistd.h>

#ifndef VPLKIT_SOURCE_DIR
#error "VPLKIT_SOURCE_DIR must be defined by the build"
#endif

namespace {

using vplkit::DenoiseMode;
using vplkit::GiMethod;

constexpr const char* kCornellPoint = VPLKIT_SOURCE_DIR "/scenes/cornell_point/cornell_point.gltf";

vplkit::RenderSettings small() {
    vplkit::RenderSettings s;
    s.width = 32;
    s.height = 32;
    s.vpl_source = vplkit::VplSource::ir;
    s.vpl_paths = 256;
    s.direct_samples = 2;
    return s;
}

// A directory of this process's own, removed before and after.
struct TemporaryDirectory {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("vplkit-budget-test-" + std::to_string(::getpid()));
    TemporaryDirectory() { std::filesystem::remove_all(path); }
    ~TemporaryDirectory() { std::filesystem::remove_all(path); }
};

}  // namespace

TEST_CASE("budget: a calibration at 32x32 predicts every configuration and is cached") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    const TemporaryDirectory cache;
    const vplkit::RenderSettings base = small();
    vplkit::BudgetSpace space = vplkit::default_budget_space(base, vplkit::VplSource::ir);
    space.methods = {GiMethod::rtslc, GiMethod::hybrid};
    space.spp = {1, 4, 16};
    CHECK(space.vpls == std::vector<uint32_t>{64, 256});
    vplkit::BudgetCalibrationOptions options;
    options.cache_dir = cache.path;
    options.scene_id = "cornell_point";

    const auto first = vplkit::calibrate_budget(renderer, ctx.info(), scene, scene.camera(), base, space, options);
    CHECK(!first.from_cache);
    // 2 methods x 2 resolutions x 4 frames, four at 64 spp (two VPL budgets), half size, per method
    // two runs of 3 svgf frames (spp 4 and 16), svgf at half size, and the untimed first frame; and
    // 8 untimed frames before those whose shaders or size differ from the frame before (rtslc half,
    // hybrid full and half, the 64 spp rtslc full after them, half size, rtslc svgf, hybrid svgf,
    // svgf at half size).
    CHECK(first.frames == 35 + 8);
    CHECK(std::filesystem::exists(first.cache_file));
    REQUIRE(first.model.error.sampling.size() == 4);
    for (const auto& m : first.model.error.sampling) {
        CAPTURE(int(m.method));
        CHECK(m.variance > 0.0);
        CHECK(m.variance < 1.0);  // tonemapped values lie in 0..1
        CHECK(m.exponent >= 0.5);
        CHECK(m.exponent <= 1.0);
    }
    CHECK(first.model.error.vpl_measured == 256);
    CHECK(first.model.error.vpl_small == 64);
    CHECK(first.model.error.vpl_small_mse >= 0.0);
    // svgf measured on this scene, per method: it keeps part of the noise, and its floor is an error.
    for (const auto& m : first.model.error.sampling) {
        if (m.half_resolution) continue;
        CAPTURE(int(m.method));
        REQUIRE(m.svgf);
        CHECK(m.svgf->noise_share >= 0.0);
        CHECK(m.svgf->noise_share < 1.0);
        CHECK(m.svgf->floor_variance >= 0.0);
    }

    const auto candidates = vplkit::budget_candidates(first.model, space, scene, base);
    CHECK(candidates.size() == 2 * 3 * 2 * 2 * 2);
    for (const auto& c : candidates) {
        CHECK(c.predicted_ms > 0.0);
        CHECK(c.predicted_rmse > 0.0);
    }
    const auto generous = vplkit::choose_for_budget(candidates, 1e9);
    CHECK(!generous.over_budget);
    CHECK(generous.chosen.config.spp == 16);  // with all the time there is, the most samples
    CHECK(vplkit::choose_for_budget(candidates, 1e-6).over_budget);

    // The same key again: read back, the same predictions, nothing rendered.
    const auto second = vplkit::calibrate_budget(renderer, ctx.info(), scene, scene.camera(), base, space, options);
    CHECK(second.from_cache);
    CHECK(second.frames == 0);
    CHECK(second.key == first.key);
    CHECK(second.model.error.vpl_small_mse == first.model.error.vpl_small_mse);
    for (size_t i = 0; i < first.model.error.sampling.size(); ++i) {
        CHECK(second.model.error.sampling[i].svgf.has_value() == first.model.error.sampling[i].svgf.has_value());
    }
    const auto again = vplkit::budget_candidates(second.model, space, scene, base);
    REQUIRE(again.size() == candidates.size());
    for (size_t i = 0; i < again.size(); ++i) {
        CHECK(again[i].predicted_ms == candidates[i].predicted_ms);
        CHECK(again[i].predicted_rmse == candidates[i].predicted_rmse);
    }

    // Another plan (direct light sampled otherwise, a smaller space): another key, calibrated anew.
    vplkit::RenderSettings other = base;
    other.direct_samples = 4;
    vplkit::BudgetSpace narrow = space;
    narrow.methods = {GiMethod::rtslc};
    narrow.half_resolution = {false};
    narrow.denoise = {DenoiseMode::off};
    const auto third = vplkit::calibrate_budget(renderer, ctx.info(), scene, scene.camera(), other, narrow, options);
    CHECK(!third.from_cache);
    CHECK(third.key != first.key);

    // Another view of the same scene: another key too.
    vplkit::scene::Camera moved = scene.camera();
    moved.position += glm::vec3(0.1f, 0.0f, 0.0f);
    const auto fourth = vplkit::calibrate_budget(renderer, ctx.info(), scene, moved, other, narrow, options);
    CHECK(!fourth.from_cache);
    CHECK(fourth.key != third.key);
}

TEST_CASE("budget: plan_for_budget chooses, applies the choice, and re-plans when the times drift") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    const TemporaryDirectory cache;
    vplkit::BudgetCalibrationOptions options;
    options.cache_dir = cache.path;
    options.scene_id = "cornell_point";
    vplkit::BudgetSpace space = vplkit::default_budget_space(small(), vplkit::VplSource::ir);
    space.methods = {GiMethod::rtslc};
    space.spp = {1, 2, 4, 8, 16, 32, 64};
    space.half_resolution = {false};
    space.denoise = {DenoiseMode::off};
    // Bad budgets are refused before any frame.
    CHECK_THROWS_AS(vplkit::plan_for_budget(renderer, ctx.info(), scene, scene.camera(), small(), 0.0, options, space),
                    vplkit::Error);
    CHECK(!std::filesystem::exists(cache.path));

    auto plan = vplkit::plan_for_budget(renderer, ctx.info(), scene, scene.camera(), small(), 1e9, options, space);
    CHECK(plan.choice.chosen.config.spp == 64);
    CHECK(plan.settings.method == GiMethod::rtslc);
    CHECK(plan.settings.samples_per_pixel == 64);
    CHECK(plan.settings.vpl_paths == plan.choice.chosen.config.vpls);
    // The frames run 100x slower than calibrated: the budget, at the 64 spp frame's predicted
    // time, now fits a cheaper one.
    plan.choice.budget_ms = plan.choice.chosen.predicted_ms;
    for (int i = 0; i < 5; ++i) plan.drift.record(plan.choice.chosen.predicted_ms * 100.0);
    CHECK(plan.drift.scale() == doctest::Approx(100.0));
    vplkit::replan_for_budget(plan);
    CHECK((plan.choice.over_budget || plan.choice.chosen.config.spp < 64));
    CHECK(plan.settings.samples_per_pixel == plan.choice.chosen.config.spp);
}

TEST_CASE("budget: the space refuses methods without a noise to trade, and bad knobs") {
    vplkit::BudgetSpace space = vplkit::default_budget_space(small(), vplkit::VplSource::ir);
    space.methods = {GiMethod::flc};
    CHECK_THROWS_WITH_AS(vplkit::validate_budget_space(space), doctest::Contains("`method` flc"), vplkit::Error);
    space = vplkit::default_budget_space(small(), vplkit::VplSource::ir);
    space.spp = {0};
    CHECK_THROWS_AS(vplkit::validate_budget_space(space), vplkit::Error);
    space = vplkit::default_budget_space(small(), vplkit::VplSource::ir);
    space.denoise = {DenoiseMode::temporal};
    CHECK_THROWS_WITH_AS(vplkit::validate_budget_space(space), doctest::Contains("temporal"), vplkit::Error);
    space = vplkit::default_budget_space(small(), vplkit::VplSource::ir);
    space.block_sizes.clear();
    CHECK_THROWS_AS(vplkit::validate_budget_space(space), vplkit::Error);
}

TEST_CASE("budget: cache files are named by FNV-1a of their key (the published 64-bit test vectors)") {
    CHECK(vplkit::fnv1a_hex("") == "cbf29ce484222325");
    CHECK(vplkit::fnv1a_hex("a") == "af63dc4c8601ec8c");
    CHECK(vplkit::fnv1a_hex("foobar") == "85944171f73967e8");
}
