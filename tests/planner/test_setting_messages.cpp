// The runtime's messages name its own settings, never a command-line flag: a setting is its
// RenderSettings member in backquotes ("`vpl_source` ir", render_settings.hpp), and the CLI turns
// those into flags (samples/vplkit/setting_flags.cpp; tests/cli checks the flags it prints).

#include "vplkit/denoiser.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_lights.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <limits>
#include <string>

namespace {

using vplkit::FrameStage;
using vplkit::GiMethod;
using vplkit::RenderSettings;

constexpr const char* kCornellPoint = VPLKIT_SOURCE_DIR "/scenes/cornell_point/cornell_point.gltf";
constexpr const char* kManyLights = VPLKIT_SOURCE_DIR "/scenes/many_lights/many_lights.gltf";

bool names_a_flag(const std::string& text) {
    return text.find("--") != std::string::npos;
}

std::string reason(const vplkit::FramePlan& plan, FrameStage stage) {
    for (const auto& s : plan.stages) {
        if (s.stage == stage) return s.reason;
    }
    return "missing";
}

}  // namespace

TEST_CASE("setting messages: every plan reason names settings in the runtime's terms") {
    const auto point = vplkit::scene::load_gltf(kCornellPoint);
    const auto many = vplkit::scene::load_gltf(kManyLights);
    auto check_words = [](const vplkit::FramePlan& plan) {
        for (const auto& s : plan.stages) {
            CAPTURE(vplkit::stage_name(s.stage));
            CHECK_FALSE(names_a_flag(s.reason));
        }
        CHECK_FALSE(names_a_flag(plan.glossy_reason));
        for (const std::string& note : plan.notes) CHECK_FALSE(names_a_flag(note));
    };
    RenderSettings direct;
    const auto direct_plan = vplkit::plan_frame(point, direct, "v");
    check_words(direct_plan);
    CHECK(reason(direct_plan, FrameStage::vpl_paths) == "direct light only (`method` direct): no VPLs");
    CHECK(reason(direct_plan, FrameStage::flc_vpls) == "direct light only (`method` direct): no VPLs");

    RenderSettings forced;
    forced.method = GiMethod::sst;
    forced.force_all_stages = true;
    forced.glossy_branch = vplkit::GlossyBranch::off;
    const auto forced_plan = vplkit::plan_frame(point, forced, "v");
    check_words(forced_plan);
    CHECK(reason(forced_plan, FrameStage::direct_emissive) == "forced on (`force_all_stages`); no emissive triangle");
    CHECK(reason(forced_plan, FrameStage::light_tree) == "forced on (`force_all_stages`); the method does not read it");
    CHECK(reason(forced_plan, FrameStage::gi_exact) == "`method` sst");
    CHECK(reason(forced_plan, FrameStage::flc_vpls) == "`method` sst");
    CHECK(reason(forced_plan, FrameStage::denoise) == "`denoise` off");
    CHECK(forced_plan.glossy_reason == "forced off (`glossy_branch` off)");
    forced.glossy_branch = vplkit::GlossyBranch::automatic;
    CHECK(vplkit::plan_frame(point, forced, "v").glossy_reason == "forced on (`force_all_stages`)");
    forced.glossy_branch = vplkit::GlossyBranch::on;
    CHECK(vplkit::plan_frame(point, forced, "v").glossy_reason == "forced on (`glossy_branch` on)");

    RenderSettings samples;  // more than the tree's cut holds: flat, and why
    samples.direct_samples = 65;
    const auto samples_plan = vplkit::plan_frame(many, samples, "v");
    check_words(samples_plan);
    CHECK(reason(samples_plan, FrameStage::direct_tree).find(", but `direct_samples` 65 is above") !=
          std::string::npos);
    RenderSettings few;  // few lights: flat, and how to ask for the tree
    const auto few_plan = vplkit::plan_frame(point, few, "v");
    check_words(few_plan);
    CHECK(reason(few_plan, FrameStage::direct_tree).find("(`direct_sampler` tree to sample them") != std::string::npos);
    RenderSettings tree2;
    tree2.direct_sampler = vplkit::DirectSampler::tree2;
    const auto tree2_plan = vplkit::plan_frame(many, tree2, "v");
    check_words(tree2_plan);
    CHECK(reason(tree2_plan, FrameStage::direct_tree).rfind("`direct_sampler` tree2 asked for (", 0) == 0);
}

TEST_CASE("setting messages: refused settings are named as RenderSettings spells them") {
    RenderSettings flc;
    flc.method = GiMethod::flc;
    auto refused = [](RenderSettings s, const char* expected) {
        CAPTURE(expected);
        try {
            vplkit::validate_gi_settings(s);
            FAIL("accepted");
        } catch (const vplkit::Error& e) {
            const std::string text = e.what();
            CHECK(text.find(expected) != std::string::npos);
            CHECK_FALSE(names_a_flag(text));
        }
    };
    auto s = flc;
    s.flc_levels = 0;
    refused(s, "flc: `flc_levels` 0 is outside 1..");
    s = flc;
    s.flc_mu = 1.0f;
    refused(s, "flc: `flc_mu` 1");
    s = flc;
    s.flc_vpls_per_point = 0.0f;
    refused(s, "flc: `flc_vpls_per_point` 0");
    s = flc;
    s.flc_emitter_samples = 0;
    refused(s, "flc: `flc_emitter_samples`");
    s = flc;
    s.flc_subtiles = 0;
    refused(s, "flc: `flc_subtiles` 0 is outside 1..");
    s = flc;
    s.half_resolution_gi = true;
    refused(s, "flc: `half_resolution_gi` is not available");
    RenderSettings thresholds;  // checked for every method
    thresholds.sst.nu_min = std::numeric_limits<float>::quiet_NaN();
    refused(thresholds, "`sst.nu_min` must be finite");
    thresholds = RenderSettings{};
    thresholds.sigma_max_scene_fraction = -1.0f;
    refused(thresholds, "`sigma_max_scene_fraction` must be finite and >= 0");
}

TEST_CASE("setting messages: the renderer and the denoiser refuse in the runtime's terms") {
    vplkit::Context& ctx = vplkit::test::context();
    // No light at all: the scene's lights are what to change.
    auto dark = vplkit::scene::load_gltf(kCornellPoint);
    dark.lights.clear();
    REQUIRE(dark.emissive_triangles.empty());
    try {
        vplkit::Renderer renderer(ctx, dark);
        FAIL("accepted");
    } catch (const vplkit::Error& e) {
        const std::string text = e.what();
        CHECK(text.find("its image would be black; add a light (`scene.lights`)") != std::string::npos);
        CHECK_FALSE(names_a_flag(text));
    }
    // The denoiser with no filter asked for.
    auto denoiser = vplkit::Denoiser::create(ctx, 8, 8);
    auto gbuffer = vplkit::GbufferImages::create(ctx, 8, 8);
    vplkit::PassList passes("denoise off");
    try {
        denoiser.add_passes(ctx, passes, vplkit::DenoiseMode::off, gbuffer, gbuffer.albedo, {}, false);
        FAIL("accepted");
    } catch (const vplkit::Error& e) {
        const std::string text = e.what();
        CHECK(text == "denoiser: no filter asked for (`denoise` off)");
    }
}
