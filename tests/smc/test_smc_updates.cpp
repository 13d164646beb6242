// The shaders these updates drive each have a per-shader test against a double-precision CPU
// reference (tests/reference/smc_reference.cpp) in the other files of this folder:
// test_smc_camera_rays.cpp, test_smc_validate.cpp (smc_validate, smc_revalidate),
// test_smc_gather_candidates.cpp, test_smc_radiosity.cpp, test_smc_density.cpp,
// test_smc_select.cpp (smc_selection_keys, smc_select, smc_replace) and test_smc_vpls.cpp.
// Here they run together, checked by the invariants of their output below.
//
// Whole SMC updates (the SMC paper Alg. 1) through the Renderer on the in-repo Cornell box (point
// light), small: 32x32 pixels, a budget of 256 VPLs, 8 camera rays per candidate, 4 radiosity
// paths. What is checked is exact bookkeeping (counts, which slots changed), not statistics:
// - every VPL finite, with a unit normal (1e-4), on a scene triangle (1e-4 of the scene scale:
//   hit points from barycentrics are off by a few ulps), flux >= 0;
// - |Y| never exceeds the budget, and the set is full after the warm-up;
// - while the camera orbits, a full set changes in at most M_max slots per update;
// - a static camera empties the invalid set: after a move, the invalid VPLs left fall by at
//   least min(M_max, left) per update, so they are gone within ceil(left / M_max) updates;
// - every GI method renders from the set (finite pixels, some indirect light);
// - the planner never reuses an SMC set and says so;
// - energy: in the closed sphere of scenes/enclosure_sphere (a 1 cd point light at its centre,
//   albedo 0.5) a VPL's radiosity is known in closed form, B(y) = 0.5 cos / d^2 (one bounce: the
//   estimate has no variance), so flux / B is the area it stands for; summed, the mesh's area,
//   within 5% (kNN on 1024 VPLs, k = 5; eq. 7's k instead of k + 1/2 gave +13%);
// - a posed scene (the animated box's tall block turned 15 degrees, its light swung): the VPLs on
//   the block move with it, so after the pose every VPL still lies on a surface of the posed
//   scene and the block keeps at least 80% of its VPLs (they died before: left in the air, no
//   light, replaced M_max a frame).

#include "vplkit/context.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_pose.hpp"
#include "vplkit_test/context.hpp"
#include "geometry_reference.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#ifndef VPLKIT_SOURCE_DIR
#error "VPLKIT_SOURCE_DIR must be defined by the build"
#endif

namespace {

using vplkit::GiMethod;
using vplkit::VplSource;

constexpr const char* kCornellPoint = VPLKIT_SOURCE_DIR "/scenes/cornell_point/cornell_point.gltf";
constexpr const char* kSphere = VPLKIT_SOURCE_DIR "/scenes/enclosure_sphere/enclosure_sphere.gltf";
constexpr const char* kAnimatedBox = VPLKIT_SOURCE_DIR "/scenes/animated_box/animated_box.gltf";

vplkit::RenderSettings smc_settings(uint32_t max_moves = 8, uint32_t warmup = 4) {
    vplkit::RenderSettings s;
    s.width = 32;
    s.height = 32;
    s.method = GiMethod::none;
    s.vpls_only = true;
    s.vpl_source = VplSource::smc;
    s.smc.budget = 256;
    s.smc.max_moves = max_moves;
    s.smc.resample_ratio = 8;
    s.smc.radiosity_samples = 4;
    s.smc_warmup = warmup;
    s.seed = 5;
    return s;
}

// The scene's camera turned about the box's vertical axis through its centre by `degrees`.
vplkit::scene::Camera orbit(const vplkit::scene::Scene& scene, float degrees) {
    vplkit::scene::Camera c = scene.camera();
    const glm::vec3 centre = scene.bounds.center();
    const float a = glm::radians(degrees);
    const glm::vec3 d = c.position - centre;
    const glm::vec3 turned{d.x * std::cos(a) + d.z * std::sin(a), d.y, -d.x * std::sin(a) + d.z * std::cos(a)};
    vplkit::scene::Camera turned_camera = vplkit::scene::look_at(centre + turned, centre, {0.0f, 1.0f, 0.0f}, c.yfov);
    turned_camera.aspect = c.aspect;
    turned_camera.znear = c.znear;
    turned_camera.zfar = c.zfar;
    return turned_camera;
}

double nearest_triangle(const vplkit::scene::Scene& scene, glm::vec3 p) {
    double best = 1e30;
    for (size_t t = 0; t < scene.triangle_count(); ++t) {
        const glm::dvec3 a = scene.vertices[scene.indices[3 * t]].position;
        const glm::dvec3 b = scene.vertices[scene.indices[3 * t + 1]].position;
        const glm::dvec3 c = scene.vertices[scene.indices[3 * t + 2]].position;
        best = std::min(best, vplkit::reference::point_triangle_distance(glm::dvec3(p), a, b, c));
    }
    return best;
}

}  // namespace

TEST_CASE("smc: every VPL is finite, has a unit normal and lies on a surface and the budget holds") {
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(vplkit::test::context(), scene);
    const auto s = smc_settings();
    const float scale = glm::length(scene.bounds.extent());
    for (int frame = 0; frame < 2; ++frame) {
        const auto image = renderer.render(orbit(scene, 10.0f * frame), s);
        REQUIRE(image.smc);
        CHECK(image.vpl_count == image.smc->vpls);
        CHECK(image.vpl_count <= s.smc.budget);
        CHECK(image.vpl_count == s.smc.budget);  // the box reflects everywhere: the warm-up fills it
        REQUIRE(image.vpls.size() == image.vpl_count);
        double flux = 0.0;
        for (const auto& v : image.vpls) {
            CHECK(std::isfinite(v.position.x + v.position.y + v.position.z));
            CHECK(std::isfinite(v.flux.x + v.flux.y + v.flux.z));
            CHECK(std::min({v.flux.x, v.flux.y, v.flux.z}) >= 0.0f);
            CHECK(glm::length(v.normal) == doctest::Approx(1.0).epsilon(1e-4));
            CHECK(nearest_triangle(scene, v.position) < 1e-4 * scale);
            flux += v.flux.x + v.flux.y + v.flux.z;
        }
        CHECK(flux > 0.0);
    }
}

TEST_CASE("smc: a full set changes in at most M_max slots per update while the camera orbits") {
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(vplkit::test::context(), scene);
    const uint32_t max_moves = 6;
    const auto s = smc_settings(max_moves);
    auto previous = renderer.render(orbit(scene, 0.0f), s);
    REQUIRE(previous.vpl_count == s.smc.budget);
    uint32_t moved_total = 0;
    for (int frame = 1; frame <= 4; ++frame) {
        const auto image = renderer.render(orbit(scene, 8.0f * frame), s);
        REQUIRE(image.smc);
        REQUIRE(image.vpl_count == s.smc.budget);
        uint32_t changed = 0;
        for (size_t i = 0; i < image.vpls.size(); ++i) {
            if (image.vpls[i].position != previous.vpls[i].position) ++changed;
        }
        CAPTURE(frame);
        CHECK(changed <= max_moves);
        CHECK(image.smc->removed <= max_moves);
        CHECK(image.smc->moved == image.smc->removed);  // a full set: every VPL in replaces one out
        CHECK(changed == image.smc->moved);
        moved_total += changed;
        previous = image;
    }
    CHECK(moved_total > 0);  // the orbit invalidates VPLs: the set does move
}

TEST_CASE("smc: a static camera empties the invalid set") {
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(vplkit::test::context(), scene);
    const uint32_t max_moves = 16;
    const auto s = smc_settings(max_moves);
    // Converged from the start: every anchor was drawn from this view.
    const auto first = renderer.render(scene.camera(), s);
    REQUIRE(first.smc);
    const auto again = renderer.render(scene.camera(), s);
    CHECK(again.smc->invalid == 0);
    CHECK(again.smc->still_invalid == 0);
    // After a move, the invalid VPLs left go, M_max (or all that remain) per update.
    const auto view = orbit(scene, 35.0f);
    auto image = renderer.render(view, s);
    // Invalid VPLs go first (then weak valid ones, up to M_min): those left are the rest.
    auto invalid_left = [](const vplkit::SmcCounts& c) {
        return c.still_invalid - std::min(c.still_invalid, c.removed);
    };
    uint32_t left = invalid_left(*image.smc);
    CHECK(image.smc->invalid > 0);  // the move invalidated some
    const uint32_t updates = (left + max_moves - 1) / max_moves + 1;
    for (uint32_t u = 0; u < updates && left > 0; ++u) {
        image = renderer.render(view, s);
        CAPTURE(u);
        CHECK(image.smc->still_invalid <= left);
        left = invalid_left(*image.smc);
    }
    CHECK(left == 0);
    image = renderer.render(view, s);
    CHECK(image.smc->still_invalid == 0);
}

TEST_CASE("smc: every GI method renders from the SMC set") {
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::Renderer renderer(vplkit::test::context(), scene);
    auto s = smc_settings(16, 2);
    s.vpls_only = false;
    for (GiMethod method : {GiMethod::exact, GiMethod::sst, GiMethod::rtslc, GiMethod::hybrid}) {
        CAPTURE(vplkit::gi_method_name(method));
        s.method = method;
        s.samples_per_pixel = 4;
        const auto image = renderer.render(scene.camera(), s);
        CHECK(image.non_finite_pixels == 0);
        CHECK(image.vpl_count == s.smc.budget);
        double indirect = 0.0;
        for (float v : image.indirect) indirect += v;
        CHECK(indirect > 0.0);
        CHECK(std::find(image.stages_run.begin(), image.stages_run.end(), "smc vpls") != image.stages_run.end());
    }
}

TEST_CASE("smc: the planner never reuses an SMC set") {
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    auto s = smc_settings();
    s.vpls_only = false;
    s.method = GiMethod::hybrid;
    const auto first = vplkit::plan_frame(scene, s, "view");
    CHECK(first.runs(vplkit::FrameStage::smc_vpls));
    CHECK(!first.runs(vplkit::FrameStage::vpl_paths));
    const auto second = vplkit::plan_frame(scene, s, "view", {first.vpl_key, true, true, first.tree_key});
    CHECK(!second.reuse_vpls);
    CHECK(!second.reuse_trees);
    CHECK(second.runs(vplkit::FrameStage::smc_vpls));
    CHECK(second.runs(vplkit::FrameStage::sst));
    CHECK(second.describe().find("rebuilt every frame") != std::string::npos);
}

TEST_CASE("smc: the VPLs of a closed sphere stand for its whole area") {
    const auto scene = vplkit::scene::load_gltf(kSphere);
    vplkit::Renderer renderer(vplkit::test::context(), scene);
    auto s = smc_settings(16, 8);
    s.smc.budget = 1024;
    s.smc.bounces = 1;
    const auto image = renderer.render(scene.camera(), s);
    REQUIRE(image.vpl_count == 1024);
    REQUIRE(scene.lights.size() == 1);
    const glm::vec3 light = scene.lights[0].position;
    double area = 0.0;
    for (const auto& v : image.vpls) {
        const glm::vec3 d = light - v.position;
        const double d2 = glm::dot(d, d);
        const double radiosity = 0.5 * scene.lights[0].intensity * glm::dot(v.normal, d) / std::sqrt(d2) / d2;
        REQUIRE(radiosity > 0.0);
        area += v.flux.x / radiosity;
    }
    double mesh = 0.0;
    for (size_t t = 0; t < scene.triangle_count(); ++t) {
        const glm::dvec3 a = scene.vertices[scene.indices[3 * t]].position;
        const glm::dvec3 b = scene.vertices[scene.indices[3 * t + 1]].position;
        const glm::dvec3 c = scene.vertices[scene.indices[3 * t + 2]].position;
        mesh += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    CAPTURE(area);
    CAPTURE(mesh);
    CHECK(area == doctest::Approx(mesh).epsilon(0.05));
}

TEST_CASE("smc: VPLs on a turning block move with it") {
    vplkit::scene::PosableScene posable(kAnimatedBox);
    const vplkit::scene::Scene& scene = posable.scene();
    vplkit::Renderer renderer(vplkit::test::context(), scene);
    const auto s = smc_settings(16, 8);
    const vplkit::scene::Camera camera = scene.camera();
    const float scale = glm::length(scene.bounds.extent());
    // On the tall block (0.6 x 1.2 x 0.6 about (-0.35, 0.6, -0.3), turning about y) and on a surface of the pose.
    auto block_vpls = [&](const vplkit::RenderedImage& image) {
        uint32_t n = 0;
        for (const auto& v : image.vpls) {
            const float dx = v.position.x + 0.35f, dz = v.position.z + 0.3f;
            const bool near_block = dx * dx + dz * dz < 0.43f * 0.43f && v.position.y > 0.01f && v.position.y < 1.21f;
            if (near_block && nearest_triangle(scene, v.position) < 1e-4 * scale) ++n;
        }
        return n;
    };
    const auto first = renderer.render(camera, s);
    const uint32_t before = block_vpls(first);
    REQUIRE(before >= 10);
    for (uint32_t frame = 1; frame <= 2; ++frame) {
        CAPTURE(frame);
        renderer.update_pose(posable.pose(double(frame) / 6.0));  // 15 degrees a frame
        const auto image = renderer.render(camera, s);
        REQUIRE(image.vpls.size() == s.smc.budget);
        uint32_t off_surface = 0;
        for (const auto& v : image.vpls) {
            if (!(nearest_triangle(scene, v.position) < 1e-4 * scale)) ++off_surface;
        }
        CHECK(off_surface == 0);
        CHECK(block_vpls(image) >= before * 4 / 5);
    }
}
