// A scene that moves, followed by Renderer::update_pose: the frame at t equals a renderer's made
// on the file loaded at t (a moving object, a moving light), and the plan after a pose makes again
// exactly what depended on what moved, naming why, and reuses the rest.

#include "pose_scene_file.hpp"

#include "vplkit/context.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_pose.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace {

using vplkit::FrameStage;

vplkit::RenderSettings small_settings(vplkit::GiMethod method = vplkit::GiMethod::none) {
    vplkit::RenderSettings settings;
    settings.width = 64;
    settings.height = 64;
    settings.method = method;
    settings.vpl_source = vplkit::VplSource::ir;
    settings.vpl_paths = 256;
    settings.samples_per_pixel = 4;
    return settings;
}

struct Difference {
    double max_abs = 0.0;    // largest difference of a channel
    double max_value = 0.0;  // largest value of the reference
    size_t pixels = 0;       // pixels that differ by more than 1e-4 of the largest value
};

Difference difference(const std::vector<float>& a, const std::vector<float>& b) {
    REQUIRE(a.size() == b.size());
    Difference d;
    for (float v : b) d.max_value = std::max(d.max_value, double(v));
    for (size_t i = 0; i < a.size(); i += 3) {
        double pixel = 0.0;
        for (size_t c = 0; c < 3; ++c) pixel = std::max(pixel, std::fabs(double(a[i + c]) - b[i + c]));
        d.max_abs = std::max(d.max_abs, pixel);
        d.pixels += pixel > 1e-4 * d.max_value ? 1 : 0;
    }
    return d;
}

std::string reason(const vplkit::FramePlan& plan, FrameStage stage) {
    for (const vplkit::PlannedStage& s : plan.stages) {
        if (s.stage == stage) return s.reason;
    }
    return "";
}

bool noted(const vplkit::FramePlan& plan, const std::string& text) {
    return std::any_of(plan.notes.begin(), plan.notes.end(),
                       [&](const std::string& note) { return note.find(text) != std::string::npos; });
}

// Renders the file posed from t = 0 to `time` through update_pose, and the file loaded at `time`
// by a new renderer; compares their direct light and (IR VPLs, exact gather) their indirect light.
void compare_posed_with_loaded(const std::string& animation, double time) {
    vplkit::Context& ctx = vplkit::test::context();
    scene_test::TempDir dir("pose_" + animation);
    const auto path = pose_test::write_moving_scene(dir.path());
    vplkit::scene::LoadOptions options;
    options.animation = animation;
    options.time = 0.0;
    vplkit::scene::PosableScene posable(path, options);
    vplkit::Renderer moving(ctx, posable.scene());
    const auto camera = pose_test::moving_scene_camera();
    const vplkit::RenderSettings settings = small_settings(vplkit::GiMethod::exact);
    const auto before = moving.render(camera, settings);

    const vplkit::scene::PoseChange change = posable.pose(time);
    CHECK(change.vertices == (animation == "slide"));
    CHECK(change.lights == (animation == "swing"));
    const vplkit::PoseUpdate update = moving.update_pose(change);
    const auto posed = moving.render(camera, settings);

    options.time = time;
    const auto loaded_scene = vplkit::scene::load_gltf(path, options);
    REQUIRE(loaded_scene.vertices.size() == posable.scene().vertices.size());
    for (size_t v = 0; v < loaded_scene.vertices.size(); ++v) {
        CHECK(loaded_scene.vertices[v].position == posable.scene().vertices[v].position);
    }
    vplkit::Renderer fresh(ctx, loaded_scene);
    const auto loaded = fresh.render(camera, settings);

    // The pose moved something the image shows.
    CHECK(difference(before.direct, loaded.direct).pixels > 20);
    // Direct light: the same G-buffer and the same lights; shadow rays through a GPU-refitted
    // LBVH instead of the host's SAH tree find the same occluders (the same triangles, boxes
    // that both contain them), so the images agree to float rounding.
    const Difference direct = difference(posed.direct, loaded.direct);
    CAPTURE(update.summary);
    CAPTURE(direct.max_abs);
    CAPTURE(direct.max_value);
    CHECK(direct.max_abs <= 1e-5 * direct.max_value);
    // Indirect light: IR light paths from the same seed through either tree hit the same
    // triangles at the same points up to rounding, so the VPLs and the exact gather agree closely.
    const Difference indirect = difference(posed.indirect, loaded.indirect);
    CAPTURE(indirect.max_abs);
    CHECK(posed.vpl_count == loaded.vpl_count);
    CHECK(indirect.max_abs <= 1e-3 * indirect.max_value);
}

}  // namespace

TEST_CASE("pose: a moving object posed by update_pose renders as the file loaded at that time") {
    compare_posed_with_loaded("slide", 1.3);
}

TEST_CASE("pose: a moving light posed by update_pose renders as the file loaded at that time") {
    compare_posed_with_loaded("swing", 0.7);
}

TEST_CASE("pose: the plan after update_pose remakes what moved, says why, and reuses the rest") {
    vplkit::Context& ctx = vplkit::test::context();
    scene_test::TempDir dir("pose_plan");
    vplkit::scene::LoadOptions options;
    options.time = 0.0;  // both animations
    vplkit::scene::PosableScene posable(pose_test::write_moving_scene(dir.path()), options);
    vplkit::Renderer renderer(ctx, posable.scene());
    auto camera = pose_test::moving_scene_camera();
    vplkit::RenderSettings settings = small_settings(vplkit::GiMethod::rtslc);
    settings.denoise = vplkit::DenoiseMode::temporal;
    settings.direct_sampler = vplkit::DirectSampler::tree;
    auto frame = [&](uint32_t index) {
        settings.frame = index;
        return renderer.render(camera, settings).plan;
    };
    const vplkit::FramePlan first = frame(0);
    CHECK(first.runs(FrameStage::vpl_paths));
    CHECK(first.build_direct_tree);
    CHECK(reason(first, FrameStage::direct_tree).find("first use") != std::string::npos);

    // The camera alone moves: nothing of the scene changed, everything is reused.
    const auto camera_only = renderer.update_pose({false, false, true});
    CHECK(camera_only.bvh == vplkit::BvhUpdate::none);
    CHECK(camera_only.summary.empty());
    CHECK(renderer.scene_version() == vplkit::SceneVersion{});
    camera.position.x += 0.2f;
    const vplkit::FramePlan moved_camera = frame(1);
    CHECK(moved_camera.reuse_vpls);
    CHECK(moved_camera.reuse_trees);
    CHECK(!moved_camera.build_direct_tree);
    CHECK(reason(moved_camera, FrameStage::direct_tree).find("reused: lights unchanged") != std::string::npos);
    CHECK(reason(moved_camera, FrameStage::denoise).find("accumulation with the previous") != std::string::npos);

    // Only the light moves ("swing" at t = 1 with "slide" held still by posing the same block
    // position is not possible: both play, so move the light by hand through the file's pose).
    vplkit::scene::Scene& scene = posable.scene();
    scene.lights[0].position.x += 0.3f;
    const auto lights = renderer.update_pose({false, true, false});
    CHECK(lights.bvh == vplkit::BvhUpdate::none);
    CHECK(lights.lights);
    CHECK(lights.summary.find("lights moved") != std::string::npos);
    const vplkit::FramePlan moved_light = frame(2);
    CHECK(noted(moved_light, "lights moved"));
    CHECK(!moved_light.reuse_vpls);
    CHECK(moved_light.runs(FrameStage::vpl_paths));
    CHECK(reason(moved_light, FrameStage::vpl_paths).find("made again: lights moved") != std::string::npos);
    CHECK(reason(moved_light, FrameStage::light_tree).find("rebuilt: lights moved") != std::string::npos);
    CHECK(moved_light.build_direct_tree);
    CHECK(reason(moved_light, FrameStage::direct_tree).find("rebuilt: lights moved") != std::string::npos);
    CHECK(!moved_light.drop_denoise_history);  // a light move keeps the history (it lags, no trail)

    // Nothing moves: the next frame reuses the VPLs made after the light moved.
    const vplkit::FramePlan still = frame(3);
    CHECK(still.reuse_vpls);
    CHECK(!still.build_direct_tree);

    // The geometry moves (both animations at t = 1: the block and the light).
    const vplkit::scene::PoseChange change = posable.pose(1.0);
    CHECK(change.vertices);
    CHECK(change.lights);
    const auto first_move = renderer.update_pose(change);
    CHECK(first_move.bvh == vplkit::BvhUpdate::rebuild);  // the first move: built on the GPU
    CHECK(first_move.summary.find("geometry moved") != std::string::npos);
    const vplkit::FramePlan moved_geometry = frame(4);
    CHECK(noted(moved_geometry, "BVH built on the GPU"));
    CHECK(reason(moved_geometry, FrameStage::vpl_paths).find("geometry and lights moved") != std::string::npos);
    // The denoiser follows the moved geometry with the G-buffer's motion: its history is kept.
    CHECK(!moved_geometry.drop_denoise_history);
    CHECK(reason(moved_geometry, FrameStage::denoise).find("its history found where it was") != std::string::npos);

    // A second move refits the GPU tree.
    const auto second_move = renderer.update_pose(posable.pose(1.2));
    CHECK(second_move.bvh == vplkit::BvhUpdate::refit);
    CHECK(second_move.bvh_cost_ratio >= 1.0);
    CHECK(second_move.bvh_cost_ratio < vplkit::kBvhRebuildCostRatio);
    const vplkit::FramePlan refitted = frame(5);
    CHECK(noted(refitted, "BVH refitted on the GPU"));
    CHECK(renderer.scene_version() == vplkit::SceneVersion{2, 3});
}

TEST_CASE("pose: a pose that changes the triangles is refused, and the scene left as it was") {
    scene_test::TempDir dir("pose_topology");
    gltf_features::ChannelKeys flatten{0, "scale", "STEP", {0, 1}, {1, 1, 1, 0, 0, 0}};
    const auto path = gltf_features::animated_quad({{"flatten", {flatten}}}).write(dir.path(), "flatten");
    vplkit::scene::LoadOptions options;
    options.time = 0.0;
    vplkit::scene::PosableScene posable(path, options);
    const auto vertices = posable.scene().vertices.size();
    CHECK_THROWS_WITH(posable.pose(1.5), doctest::Contains("a pose moves vertices, it does not change triangles"));
    CHECK(posable.scene().vertices.size() == vertices);
    CHECK_THROWS_WITH(posable.pose(NAN), doctest::Contains("not finite"));
    CHECK(!posable.pose(0.5).any());  // STEP: still the first key's scale
}
