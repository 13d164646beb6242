// The G-buffer's motion (gbuffer_views.hpp) on the animated box (scenes/animated_box: the tall block
// turns about Y): posed at t0, drawn, posed at t1, drawn; each pixel's motion against a CPU
// computation from the two poses (the triangle under the pixel's point in the t1 pose, the same
// barycentric point in the t0 pose, less the point), exactly 0 on everything that did not move,
// and 0 everywhere once the pose was drawn (the next frame's previous pose is this one); a still
// scene filters to the same bits with the motion bound as without it.

#include "vplkit/camera_view.hpp"
#include "vplkit/context.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_pose.hpp"
#include "vplkit/stages/gbuffer.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace {

constexpr uint32_t kSize = 64;
const std::string kScene = std::string(VPLKIT_SOURCE_DIR) + "/scenes/animated_box/animated_box.gltf";

struct Drawn {
    std::vector<glm::vec4> position, motion;
};

Drawn draw_gbuffer(vplkit::GpuScene& gpu, const vplkit::scene::Scene& scene) {
    auto& ctx = vplkit::test::context();
    auto images = vplkit::GbufferImages::create(ctx, kSize, kSize);
    vplkit::PassList passes("motion channel test");
    vplkit::stages::add_gbuffer_pass(ctx, passes, gpu, vplkit::camera_view(scene.camera(), kSize, kSize), images);
    passes.run(ctx);
    return {images.position.download<glm::vec4>(), images.motion.download<glm::vec4>()};
}

// The surface point under p (the G-buffer's position, pulled toward the eye along the camera ray):
// the camera ray through p meets `now`'s triangles; the nearest triangle along the ray that holds
// the hit, its barycentric point carried to `before`: before - now. nullopt if no triangle does.
std::optional<glm::dvec3> cpu_motion(const glm::dvec3& p, const glm::dvec3& eye,
                                     const std::vector<vplkit::scene::Vertex>& before,
                                     const std::vector<vplkit::scene::Vertex>& now,
                                     const std::vector<uint32_t>& indices) {
    const glm::dvec3 d = p - eye;
    double best = std::numeric_limits<double>::infinity();
    std::optional<glm::dvec3> out;
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const glm::dvec3 a(now[indices[t]].position), b(now[indices[t + 1]].position), c(now[indices[t + 2]].position);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        const double area2 = glm::dot(n, n);
        if (!(area2 > 0.0) || glm::dot(d, n) == 0.0) continue;
        const double along = glm::dot(a - eye, n) / glm::dot(d, n);  // 1: p itself
        const glm::dvec3 q = eye + along * d;
        const double u = glm::dot(glm::cross(c - b, q - b), n) / area2;
        const double v = glm::dot(glm::cross(a - c, q - c), n) / area2;
        const double w = 1.0 - u - v;
        constexpr double kSlack = 1e-4;
        const double gap = std::abs(along - 1.0) * glm::length(d);  // metres from p along the ray
        if (u < -kSlack || v < -kSlack || w < -kSlack || gap >= best) continue;
        best = gap;
        const glm::dvec3 pa(before[indices[t]].position), pb(before[indices[t + 1]].position),
            pc(before[indices[t + 2]].position);
        out = u * pa + v * pb + w * pc - (u * a + v * b + w * c);
    }
    return best < 1e-3 ? out : std::nullopt;
}

}  // namespace

TEST_CASE("motion channel: the animated box's motion from t0 to t1 against the two poses on the CPU") {
    auto& ctx = vplkit::test::context();
    vplkit::scene::LoadOptions options;
    options.time = 0.3;
    vplkit::scene::PosableScene posable(kScene, options);
    vplkit::scene::Scene& scene = posable.scene();
    auto gpu = vplkit::GpuScene::create(ctx, scene);
    const Drawn still = draw_gbuffer(gpu, scene);
    for (const glm::vec4& m : still.motion) CHECK(m == glm::vec4(0.0f));  // never posed: no motion

    const std::vector<vplkit::scene::Vertex> before = scene.vertices;
    REQUIRE(posable.pose(0.55).vertices);  // the block turns 22.5 degrees
    gpu.update_vertices(scene);
    REQUIRE(gpu.has_motion());
    const Drawn moved = draw_gbuffer(gpu, scene);

    const glm::dvec3 eye(scene.camera().position);
    size_t moving = 0, resting = 0;
    double worst = 0.0, largest = 0.0;
    for (uint32_t i = 0; i < kSize * kSize; ++i) {
        CAPTURE(i);
        const glm::vec4& p = moved.position[i];
        const glm::vec4& m = moved.motion[i];
        if (p.w <= 0.5f) {
            CHECK(m == glm::vec4(0.0f));
            continue;
        }
        CHECK(m.w == 0.0f);
        const std::optional<glm::dvec3> expected =
            cpu_motion(glm::dvec3(p), eye, before, scene.vertices, scene.indices);
        REQUIRE(expected.has_value());
        if (*expected == glm::dvec3(0.0)) {
            // Walls and the short block: the same vertices in both poses, motion exactly 0.
            ++resting;
            CHECK(glm::vec3(m) == glm::vec3(0.0f));
            continue;
        }
        ++moving;
        largest = std::max(largest, glm::length(*expected));
        worst = std::max(worst, glm::length(glm::dvec3(glm::vec3(m)) - *expected));
    }
    MESSAGE(moving << " pixels moved (largest " << largest << " m), " << resting << " did not; largest error " << worst
                   << " m");
    CHECK(moving > 100);  // the tall block is seen
    CHECK(resting > 1000);
    CHECK(largest > 0.05);  // several pixels (the box is 2 m across 64 pixels)
    // Float interpolation of the corners' differences: rounding of about 1e-7 m (measured 8.6e-8).
    CHECK(worst < 1e-6);

    // Drawn: this pose is the previous one now, so a frame without a new pose has no motion.
    gpu.settle_motion();
    const Drawn again = draw_gbuffer(gpu, scene);
    for (const glm::vec4& m : again.motion) CHECK(m == glm::vec4(0.0f));
}

TEST_CASE("motion channel: the renderer draws the previous frame's pose, and none once it was drawn") {
    auto& ctx = vplkit::test::context();
    vplkit::scene::PosableScene posable(kScene);
    vplkit::Renderer renderer(ctx, posable.scene());
    vplkit::RenderSettings settings;
    settings.width = settings.height = kSize;
    settings.method = vplkit::GiMethod::none;  // the G-buffer is what is looked at
    settings.read_back_aovs = true;
    const vplkit::scene::Camera camera = posable.scene().camera();
    const vplkit::RenderedImage first = renderer.render(camera, settings);
    auto moving_pixels = [](const vplkit::RenderedImage& image) {
        size_t n = 0;
        for (size_t i = 0; i < image.motion.size(); i += 3) {
            n += image.motion[i] != 0.0f || image.motion[i + 1] != 0.0f || image.motion[i + 2] != 0.0f ? 1 : 0;
        }
        return n;
    };
    REQUIRE(first.motion.size() == 3 * kSize * kSize);
    CHECK(moving_pixels(first) == 0);
    renderer.update_pose(posable.pose(0.25));
    settings.frame = 1;
    CHECK(moving_pixels(renderer.render(camera, settings)) > 100);
    settings.frame = 2;
    CHECK(moving_pixels(renderer.render(camera, settings)) == 0);  // nothing moved since
    // Two poses before a frame: the motion is from the pose drawn last (t = 0.25), not the one between.
    renderer.update_pose(posable.pose(0.4));
    renderer.update_pose(posable.pose(0.5));
    settings.frame = 3;
    const vplkit::RenderedImage two_steps = renderer.render(camera, settings);
    vplkit::scene::LoadOptions at;
    at.time = 0.25;
    vplkit::scene::PosableScene reference(kScene, at);
    vplkit::Renderer direct(ctx, reference.scene());
    direct.update_pose(reference.pose(0.5));
    settings.frame = 1;
    const vplkit::RenderedImage one_step = direct.render(camera, settings);
    REQUIRE(one_step.motion.size() == two_steps.motion.size());
    double worst = 0.0;
    for (size_t i = 0; i < one_step.motion.size(); ++i) {
        worst = std::max(worst, double(std::abs(one_step.motion[i] - two_steps.motion[i])));
    }
    CHECK(moving_pixels(one_step) > 100);
    CHECK(worst < 1e-5);
}

TEST_CASE("motion channel: a still scene's filtered frames are bit-identical with the motion bound or not") {
    // The motion of a scene never posed is exactly 0, and position + 0 is the position: the
    // filter's arithmetic is the camera-only one's to the bit (what keeps still scenes' images).
    auto& ctx = vplkit::test::context();
    const vplkit::scene::Scene scene =
        vplkit::scene::load_gltf(std::string(VPLKIT_SOURCE_DIR) + "/scenes/cornell_point/cornell_point.gltf");
    vplkit::RenderSettings settings;
    settings.width = settings.height = kSize;
    settings.method = vplkit::GiMethod::hybrid;
    settings.vpl_source = vplkit::VplSource::ir;
    settings.vpl_paths = 256;
    settings.samples_per_pixel = 4;
    settings.denoise = vplkit::DenoiseMode::svgf;
    std::vector<float> images[2];
    for (int camera_only = 0; camera_only < 2; ++camera_only) {
        vplkit::Renderer renderer(ctx, scene);
        settings.denoise_motion = camera_only ? vplkit::DenoiseMotion::camera_only : vplkit::DenoiseMotion::follow;
        for (uint32_t f = 0; f < 3; ++f) {
            settings.frame = f;
            images[camera_only] = renderer.render(scene.camera(), settings).radiance;
        }
    }
    REQUIRE(images[0].size() == 3 * kSize * kSize);
    CHECK(images[0] == images[1]);
}
