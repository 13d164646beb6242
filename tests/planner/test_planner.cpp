// The effects planner against scenes made here (the in-repo Cornell boxes with their lights
// changed in memory), and the frames the renderer records from its plans.

#include "vplkit/planner.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_lights.hpp"
#include "vplkit/stages/glossy_lobe.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <set>
#include <string>
#include <vector>

#ifndef VPLKIT_SOURCE_DIR
#error "VPLKIT_SOURCE_DIR must be defined by the build"
#endif

namespace {

using vplkit::FramePlan;
using vplkit::FrameStage;
using vplkit::GiMethod;
using vplkit::RenderSettings;
using vplkit::VplSource;

constexpr const char* kCornellPoint = VPLKIT_SOURCE_DIR "/scenes/cornell_point/cornell_point.gltf";
constexpr const char* kCornellEmissive = VPLKIT_SOURCE_DIR "/scenes/cornell_emissive/cornell_emissive.gltf";
constexpr const char* kManyLights = VPLKIT_SOURCE_DIR "/scenes/many_lights/many_lights.gltf";

const FrameStage kAllStages[] = {FrameStage::gbuffer,       FrameStage::direct_light, FrameStage::direct_emissive,
                                 FrameStage::direct_tree,   FrameStage::vpl_paths,    FrameStage::brsm_vpls,
                                 FrameStage::vpl_sort,      FrameStage::light_tree,   FrameStage::sst,
                                 FrameStage::gi_downsample, FrameStage::gi_exact,     FrameStage::gi_sst,
                                 FrameStage::gi_rtslc,      FrameStage::gi_hybrid,    FrameStage::gi_upsample,
                                 FrameStage::denoise,       FrameStage::compose,      FrameStage::tonemap};

std::set<FrameStage> running(const FramePlan& plan) {
    std::set<FrameStage> out;
    for (const auto& s : plan.stages) {
        CHECK(!s.reason.empty());
        if (s.runs) out.insert(s.stage);
    }
    return out;
}

RenderSettings small(GiMethod method) {
    RenderSettings s;
    s.width = 32;
    s.height = 24;
    s.method = method;
    s.vpl_paths = 128;
    s.brsm.vpl_count = 128;
    s.rsm_resolution = 32;
    s.samples_per_pixel = 4;
    s.direct_samples = 2;
    return s;
}

// Every pass the frame recorded belongs to one running stage, and every running stage recorded
// at least one pass.
void check_frame_matches_plan(const vplkit::scene::Scene& scene, const RenderSettings& settings,
                              const vplkit::RenderedImage& image) {
    std::set<std::string> ran(image.stages_run.begin(), image.stages_run.end());
    std::set<std::string> seen;
    for (const auto& t : image.timings) {
        CAPTURE(t.name);
        int owners = 0;
        for (FrameStage stage : kAllStages) {
            if (vplkit::stage_owns_pass(stage, t) && ran.count(vplkit::stage_name(stage))) {
                ++owners;
                seen.insert(vplkit::stage_name(stage));
            }
        }
        // "gi counters clear" is every sampler's: one of them runs.
        CHECK(owners == 1);
    }
    for (const std::string& stage : ran) {
        CAPTURE(stage);
        CHECK(seen.count(stage) == 1);
    }
    (void)scene;
    (void)settings;
}

}  // namespace

TEST_CASE("planner: a scene without light runs no lighting stage and says the image would be black") {
    auto scene = vplkit::scene::load_gltf(kCornellPoint);
    scene.lights.clear();
    const FramePlan plan = vplkit::plan_frame(scene, small(GiMethod::hybrid), "view");
    CHECK(running(plan) == std::set<FrameStage>{FrameStage::gbuffer, FrameStage::direct_light, FrameStage::compose,
                                                FrameStage::tonemap});
    REQUIRE(plan.notes.size() == 1);
    CHECK(plan.notes[0].find("no light") != std::string::npos);
    CHECK(plan.notes[0].find("black") != std::string::npos);
    // The renderer refuses such a scene by name (bad input), so the plan is what explains it.
    CHECK_THROWS_AS(vplkit::Renderer(vplkit::test::context(), scene), vplkit::Error);
}

TEST_CASE(
    "planner: emissive light only with emitters - each method builds only its own tree - resampling only at half "
    "resolution") {
    const auto point = vplkit::scene::load_gltf(kCornellPoint);
    const auto emissive = vplkit::scene::load_gltf(kCornellEmissive);
    REQUIRE(point.emissive_triangles.empty());
    REQUIRE(!emissive.emissive_triangles.empty());
    CHECK(!vplkit::plan_frame(point, small(GiMethod::none), "v").runs(FrameStage::direct_emissive));
    CHECK(vplkit::plan_frame(emissive, small(GiMethod::none), "v").runs(FrameStage::direct_emissive));

    const auto direct = running(vplkit::plan_frame(point, small(GiMethod::none), "v"));
    CHECK(direct == std::set<FrameStage>{FrameStage::gbuffer, FrameStage::direct_light, FrameStage::compose,
                                         FrameStage::tonemap});

    const auto exact = running(vplkit::plan_frame(point, small(GiMethod::exact), "v"));
    CHECK(exact.count(FrameStage::vpl_paths) == 1);
    CHECK(exact.count(FrameStage::vpl_sort) == 0);
    CHECK(exact.count(FrameStage::gi_exact) == 1);

    const auto rtslc = running(vplkit::plan_frame(point, small(GiMethod::rtslc), "v"));
    CHECK(rtslc.count(FrameStage::light_tree) == 1);
    CHECK(rtslc.count(FrameStage::sst) == 0);
    CHECK(rtslc.count(FrameStage::gi_rtslc) == 1);
    for (GiMethod m : {GiMethod::sst, GiMethod::hybrid}) {
        const auto plan = running(vplkit::plan_frame(point, small(m), "v"));
        CHECK(plan.count(FrameStage::sst) == 1);
        CHECK(plan.count(FrameStage::light_tree) == 0);
        CHECK(plan.count(FrameStage::gi_downsample) == 0);
        CHECK(plan.count(FrameStage::gi_upsample) == 0);
    }
    auto half = small(GiMethod::hybrid);
    half.half_resolution_gi = true;
    const auto halved = running(vplkit::plan_frame(point, half, "v"));
    CHECK(halved.count(FrameStage::gi_downsample) == 1);
    CHECK(halved.count(FrameStage::gi_upsample) == 1);
}

TEST_CASE("planner: one bounce from punctual lights is BRSM, multi-bounce or emissive light is light paths") {
    const auto point = vplkit::scene::load_gltf(kCornellPoint);
    const auto emissive = vplkit::scene::load_gltf(kCornellEmissive);
    auto s = small(GiMethod::hybrid);
    s.vpl_bounces = 1;
    CHECK(vplkit::plan_frame(point, s, "v").vpl_source == VplSource::brsm);
    CHECK(vplkit::plan_frame(emissive, s, "v").vpl_source == VplSource::ir);
    s.vpl_bounces = 2;
    CHECK(vplkit::plan_frame(point, s, "v").vpl_source == VplSource::ir);
    s.vpl_source = VplSource::brsm;  // asked for: kept
    CHECK(vplkit::plan_frame(point, s, "v").vpl_source == VplSource::brsm);
}

TEST_CASE("planner: direct light through the light tree above 8 lights, flat below, or as asked, with the reason") {
    const auto point = vplkit::scene::load_gltf(kCornellPoint);
    const auto emissive = vplkit::scene::load_gltf(kCornellEmissive);
    const auto many = vplkit::scene::load_gltf(kManyLights);
    REQUIRE(many.emissive_triangles.size() > vplkit::kDirectTreeMinLights);
    auto reason = [](const FramePlan& plan, FrameStage stage) {
        for (const auto& s : plan.stages) {
            if (s.stage == stage) return s.reason;
        }
        return std::string();
    };
    const auto auto_many = vplkit::plan_frame(many, small(GiMethod::none), "v");
    CHECK(auto_many.direct_sampler == vplkit::DirectSampler::tree);
    CHECK(running(auto_many) == std::set<FrameStage>{FrameStage::gbuffer, FrameStage::direct_light,
                                                     FrameStage::direct_tree, FrameStage::compose,
                                                     FrameStage::tonemap});
    CHECK(reason(auto_many, FrameStage::direct_tree).find("more than 8") != std::string::npos);
    for (const auto* few : {&point, &emissive}) {
        const auto plan = vplkit::plan_frame(*few, small(GiMethod::none), "v");
        CHECK(plan.direct_sampler == vplkit::DirectSampler::flat);
        CHECK(!plan.runs(FrameStage::direct_tree));
        CHECK(reason(plan, FrameStage::direct_tree).find("8 or fewer") != std::string::npos);
    }
    // More samples than the tree's cut holds: auto falls back to the flat sampler and says why.
    auto many_samples = small(GiMethod::none);
    many_samples.direct_samples = 65;
    const auto auto_many_samples = vplkit::plan_frame(many, many_samples, "v");
    CHECK(auto_many_samples.direct_sampler == vplkit::DirectSampler::flat);
    CHECK(reason(auto_many_samples, FrameStage::direct_tree).find("`direct_samples` 65 is above") != std::string::npos);
    auto asked = small(GiMethod::none);
    asked.direct_sampler = vplkit::DirectSampler::tree;
    const auto tree_point = vplkit::plan_frame(point, asked, "v");
    CHECK(tree_point.runs(FrameStage::direct_tree));
    CHECK(reason(tree_point, FrameStage::direct_tree).find("`direct_sampler` tree") != std::string::npos);
    asked.direct_sampler = vplkit::DirectSampler::flat;
    const auto flat_many = vplkit::plan_frame(many, asked, "v");
    CHECK(flat_many.runs(FrameStage::direct_emissive));
    CHECK(!flat_many.runs(FrameStage::direct_tree));
    // Only a sun: nothing for a tree, whatever is asked.
    auto sun_only = point;
    sun_only.lights = {vplkit::scene::parse_sun("0,-1,0,1,1,1,3")};
    asked.direct_sampler = vplkit::DirectSampler::tree;
    const auto sun_plan = vplkit::plan_frame(sun_only, asked, "v");
    CHECK(!sun_plan.runs(FrameStage::direct_tree));
    CHECK(reason(sun_plan, FrameStage::direct_tree).find("no emissive triangle, point or spot light") !=
          std::string::npos);
}

TEST_CASE("planner: the tree and the flat sampler light the many-light box alike (both unbiased)") {
    // The image mean of direct light, 64 x 64 at 16 samples: the two estimators differ only in
    // their noise, which averages out over the image to well below 3%.
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kManyLights);
    vplkit::Renderer renderer(ctx, scene);
    auto settings = small(GiMethod::none);
    settings.width = settings.height = 64;
    settings.direct_samples = 16;
    double means[2] = {0.0, 0.0};
    int i = 0;
    for (auto sampler : {vplkit::DirectSampler::flat, vplkit::DirectSampler::tree}) {
        settings.direct_sampler = sampler;
        const auto image = renderer.render(scene.camera(), settings);
        CHECK(image.direct_sampler == sampler);
        CHECK(image.non_finite_pixels == 0);
        for (float v : image.direct) means[i] += v;
        ++i;
    }
    CHECK(means[0] > 0.0);
    CHECK(means[1] == doctest::Approx(means[0]).epsilon(0.03));
}

TEST_CASE("planner: every frame records exactly the stages its plan runs") {
    vplkit::Context& ctx = vplkit::test::context();
    for (const char* file : {kCornellPoint, kCornellEmissive}) {
        const auto scene = vplkit::scene::load_gltf(file);
        vplkit::Renderer renderer(ctx, scene);
        std::vector<RenderSettings> cases;
        for (GiMethod m : {GiMethod::none, GiMethod::exact, GiMethod::sst, GiMethod::rtslc, GiMethod::hybrid}) {
            cases.push_back(small(m));
        }
        auto half = small(GiMethod::rtslc);
        half.half_resolution_gi = true;
        cases.push_back(half);
        auto one_bounce = small(GiMethod::hybrid);
        one_bounce.vpl_bounces = 1;
        cases.push_back(one_bounce);
        auto forced = small(GiMethod::sst);
        forced.force_all_stages = true;
        cases.push_back(forced);
        auto tree = small(GiMethod::rtslc);
        tree.direct_sampler = vplkit::DirectSampler::tree;
        cases.push_back(tree);
        tree.force_all_stages = true;  // forcing must not add the flat sampler's emitters a second time
        cases.push_back(tree);
        auto denoised = small(GiMethod::hybrid);
        denoised.denoise = vplkit::DenoiseMode::svgf;
        cases.push_back(denoised);
        denoised.half_resolution_gi = true;  // demodulated before upsampling, remodulated by the filter
        cases.push_back(denoised);
        for (size_t i = 0; i < cases.size(); ++i) {
            CAPTURE(file);
            CAPTURE(i);
            cases[i].seed = uint32_t(i);  // a new VPL set each time: nothing reused
            const auto image = renderer.render(scene.camera(), cases[i]);
            CHECK(!image.reused_vpls);
            check_frame_matches_plan(scene, cases[i], image);
        }
    }
}

TEST_CASE("planner: stages planned out because they add nothing leave the image unchanged") {
    // The point-lit box has no emissive triangle, and hybrid reads no light tree: forcing both
    // on (direct emissive light, the light tree) must give the same image, bit for bit.
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    auto planned = small(GiMethod::hybrid);
    const auto a = renderer.render(scene.camera(), planned);
    auto forced = planned;
    forced.force_all_stages = true;
    const auto b = renderer.render(scene.camera(), forced);
    CHECK(a.stages_run.size() < b.stages_run.size());
    CHECK(a.rgba8 == b.rgba8);
    CHECK(a.radiance == b.radiance);
}

TEST_CASE("planner: a static frame rendered twice rebuilds no VPLs and no tree the second time") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    for (VplSource source : {VplSource::ir, VplSource::brsm}) {
        CAPTURE(int(source));
        auto s = small(GiMethod::hybrid);
        s.vpl_source = source;
        s.seed = 40 + uint32_t(source);
        const auto first = renderer.render(scene.camera(), s);
        const auto second = renderer.render(scene.camera(), s);
        CHECK(!first.reused_vpls);
        CHECK(second.reused_vpls);
        CHECK(second.reused_trees);
        for (const auto& t : second.timings) {
            CAPTURE(t.name);
            for (FrameStage stage : {FrameStage::vpl_paths, FrameStage::brsm_vpls, FrameStage::vpl_sort,
                                     FrameStage::sst, FrameStage::light_tree}) {
                CHECK(!vplkit::stage_owns_pass(stage, t));
            }
        }
        CHECK(second.rgba8 == first.rgba8);
        CHECK(second.vpl_count == first.vpl_count);
        // Another method over the same VPLs reuses them but builds the tree it reads.
        auto other = s;
        other.method = GiMethod::rtslc;
        const auto third = renderer.render(scene.camera(), other);
        CHECK(third.reused_vpls);
        CHECK(!third.reused_trees);
        // Another seed is another VPL set.
        auto reseeded = s;
        reseeded.seed += 100;
        CHECK(!renderer.render(scene.camera(), reseeded).reused_vpls);
    }
    // Light paths do not depend on the camera; BRSM VPLs do.
    auto moved = scene.camera();
    moved.position += glm::vec3(0.05f, 0.0f, 0.0f);
    for (VplSource source : {VplSource::ir, VplSource::brsm}) {
        auto s = small(GiMethod::hybrid);
        s.vpl_source = source;
        s.seed = 7;
        renderer.render(scene.camera(), s);
        CHECK(renderer.render(moved, s).reused_vpls == (source == VplSource::ir));
    }
}

TEST_CASE("planner: a material smoother than the limit turns the glossy branch on and is named, a matte scene off") {
    auto scene = vplkit::scene::load_gltf(kCornellPoint);  // every material roughness 1
    for (GiMethod method : {GiMethod::sst, GiMethod::rtslc, GiMethod::hybrid}) {
        const FramePlan matte = vplkit::plan_frame(scene, small(method), "view");
        CHECK_FALSE(matte.glossy_branch);
        CHECK(matte.glossy_reason.find("no material smoother") != std::string::npos);
    }
    // A factor below the limit.
    auto glossy = scene;
    glossy.materials[1].roughness_factor = 0.2f;
    const FramePlan by_factor = vplkit::plan_frame(glossy, small(GiMethod::hybrid), "view");
    CHECK(by_factor.glossy_branch);
    CHECK(by_factor.glossy_reason.find("'" + glossy.materials[1].name + "' (0.2)") != std::string::npos);
    CHECK(by_factor.summary().find("glossy branch on") != std::string::npos);
    // A factor of 1 with a texture whose smallest roughness texel (green) is 51 / 255 = 0.2.
    auto textured = scene;
    vplkit::scene::Image image;
    image.name = "roughness";
    image.width = 2;
    image.height = 1;
    image.rgba = {0, 255, 0, 255, 0, 51, 0, 255};
    image.linear = true;
    textured.images.push_back(image);
    textured.textures.push_back({uint32_t(textured.images.size() - 1), {}});
    textured.materials[0].metallic_roughness_texture = int32_t(textured.textures.size() - 1);
    const auto found = vplkit::glossy_materials(textured, vplkit::stages::kGlossyMaxRoughness);
    REQUIRE(found.size() == 1);
    CHECK(found[0].name == textured.materials[0].name);
    CHECK(found[0].min_roughness == doctest::Approx(0.2f));
    CHECK(vplkit::plan_frame(textured, small(GiMethod::sst), "view").glossy_branch);
    // No tree sampling, or Lambertian materials (--brdf lambert): off.
    CHECK_FALSE(vplkit::plan_frame(glossy, small(GiMethod::exact), "view").glossy_branch);
    CHECK_FALSE(vplkit::plan_frame(glossy, small(GiMethod::none), "view").glossy_branch);
    vplkit::scene::use_lambertian_materials(glossy);
    CHECK_FALSE(vplkit::plan_frame(glossy, small(GiMethod::rtslc), "view").glossy_branch);
    // Forced either way, with the reason.
    auto forced_off = small(GiMethod::hybrid);
    forced_off.glossy_branch = vplkit::GlossyBranch::off;
    const FramePlan off = vplkit::plan_frame(textured, forced_off, "view");
    CHECK_FALSE(off.glossy_branch);
    CHECK(off.glossy_reason.find("forced off") != std::string::npos);
}

TEST_CASE("planner: a matte scene's frame is bit-identical with the glossy branch forced on") {
    // The branch is compiled out of the planned frame (no material smoother than the limit); forced
    // on, no receiver is smooth enough to choose a lobe, so every sample runs as without it.
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(ctx, scene);
    for (GiMethod method : {GiMethod::sst, GiMethod::rtslc, GiMethod::hybrid}) {
        CAPTURE(vplkit::gi_method_name(method));
        auto planned = small(method);
        const auto a = renderer.render(scene.camera(), planned);
        auto forced = planned;
        forced.glossy_branch = vplkit::GlossyBranch::on;
        const auto b = renderer.render(scene.camera(), forced);
        CHECK(a.plan_summary.find("glossy branch on") == std::string::npos);
        CHECK(b.plan_summary.find("glossy branch on") != std::string::npos);
        CHECK(a.rgba8 == b.rgba8);
        CHECK(a.radiance == b.radiance);
    }
}

TEST_CASE("planner: the denoiser is left out where it cannot help, and says why") {
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    auto reason_of = [&](const RenderSettings& settings, bool history) {
        const FramePlan plan = vplkit::plan_frame(scene, settings, "view", {"", false, false, "", history});
        for (const auto& s : plan.stages)
            if (s.stage == FrameStage::denoise) return std::pair{s.runs, s.reason};
        return std::pair{false, std::string("missing")};
    };
    auto exact = small(GiMethod::exact);
    exact.denoise = vplkit::DenoiseMode::svgf;
    CHECK(reason_of(exact, true) == std::pair{false, std::string("exact is the ground truth: nothing to filter")});
    auto off = small(GiMethod::hybrid);
    CHECK(reason_of(off, true) == std::pair{false, std::string("`denoise` off")});
    auto temporal = small(GiMethod::hybrid);
    temporal.denoise = vplkit::DenoiseMode::temporal;
    CHECK(reason_of(temporal, false).second.find("no history yet") != std::string::npos);
    CHECK(reason_of(temporal, true) == std::pair{true, std::string("temporal: accumulation with the previous frames")});
}
