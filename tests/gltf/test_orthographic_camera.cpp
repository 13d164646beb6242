// Orthographic cameras (glTF 2.0 5.13): loaded beside perspective ones in node order, and
// rendered with a parallel projection, so the G-buffer position at a pixel is the point the CPU
// projection says lies under that pixel's centre.
//
// Expectation: feature_files' two_cameras, camera 1 at (0.5, 0.5, 1) looking down -Z with
// ymag 0.625. For a 32 x 32 image (aspect 1, so the half width is ymag too) pixel (i, j)'s centre
// sees x = 0.5 + ((i + 0.5) / 16 - 1) 0.625, y = 0.5 - ((j + 0.5) / 16 - 1) 0.625 on the quad z = 0
// when (x, y) is in [0, 1]^2. Tolerance 1e-5: rasterization interpolates the position at the
// pixel centre in float (positions of order 1). Pixels within 0.05 of the quad's edge are skipped.
// Along the view (z) the G-buffer holds the point moved toward the viewer by the larger of 2^-16
// of its coordinates' magnitude (here 2^-16 at most: corners of order 1) and 2 depth ulps
// (gbuffer_shade.frag, so that shadow rays start in front of every surface): z in [-1e-5,
// 1e-5 + 2^-15].

#include "feature_files.hpp"
#include "gbuffer_readback.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace {

vplkit::scene::Scene load(uint32_t camera) {
    scene_test::TempDir dir("ortho");
    vplkit::scene::LoadOptions options;
    options.camera = camera;
    return vplkit::scene::load_gltf(gltf_features::two_cameras().write(dir.path(), "cameras", true), options);
}

}  // namespace

TEST_CASE("gltf: a file's orthographic camera is loaded beside its perspective one, in node order") {
    const auto scene = load(1);
    CHECK(vplkit::scene::warning_lines(scene.warnings).empty());
    REQUIRE(scene.cameras.size() == 2);
    CHECK(scene.cameras[0].projection == vplkit::scene::Projection::perspective);
    CHECK(scene.cameras[1].projection == vplkit::scene::Projection::orthographic);
    CHECK(scene.camera().name == "top");
    CHECK(scene.camera().ymag == 0.625f);
    CHECK(scene.camera().znear == 0.1f);
    CHECK(scene.camera().zfar == 10.0f);
    try {
        load(2);
        FAIL("camera 2 loaded");
    } catch (const std::exception& e) {
        CHECK(std::string(e.what()).find("camera 2 was asked for, but the file has 2 (0..1)") != std::string::npos);
    }
}

TEST_CASE("gltf: an orthographic camera's G-buffer holds the point under each pixel by the parallel projection") {
    const auto scene = load(1);
    constexpr uint32_t kSize = 32;
    const auto g = gltf_features::read_gbuffer(scene, kSize, kSize);
    uint32_t inside = 0, outside = 0;
    double worst = 0.0, worst_z_low = 0.0, worst_z_high = 0.0;
    for (uint32_t j = 0; j < kSize; ++j) {
        for (uint32_t i = 0; i < kSize; ++i) {
            const double x = 0.5 + ((i + 0.5) / (kSize / 2.0) - 1.0) * 0.625;
            const double y = 0.5 - ((j + 0.5) / (kSize / 2.0) - 1.0) * 0.625;
            const double edge = std::min({x, y, 1.0 - x, 1.0 - y});
            const glm::vec4& p = g.position[j * kSize + i];
            if (edge > 0.05) {
                ++inside;
                CHECK(p.w == 1.0f);
                worst = std::max({worst, std::abs(p.x - x), std::abs(p.y - y)});
                worst_z_low = std::max(worst_z_low, -double(p.z));
                worst_z_high = std::max(worst_z_high, double(p.z));
            } else if (edge < -0.05) {
                ++outside;
                CHECK(p.w == 0.0f);
            }
        }
    }
    CHECK(inside > 400);
    CHECK(outside > 100);
    CHECK(worst <= 1e-5);
    CHECK(worst_z_low <= 1e-5);
    CHECK(worst_z_high <= 1e-5 + std::ldexp(1.0, -15));
}

TEST_CASE("gltf: an orthographic camera's eye lies far back along the view, so the view direction is parallel") {
    const auto scene = load(1);
    const auto view = vplkit::camera_view(scene.camera(), 64, 32);
    // The direction from the quad's corners to the eye is +Z within 1e-4 rad (camera_view.hpp).
    for (const glm::dvec3 corner : {glm::dvec3(0, 0, 0), glm::dvec3(1, 1, 0)}) {
        const glm::dvec3 to_eye = glm::dvec3(view.position) - corner;
        CHECK(std::atan2(std::hypot(to_eye.x, to_eye.y), to_eye.z) <= 1e-4);
    }
}
