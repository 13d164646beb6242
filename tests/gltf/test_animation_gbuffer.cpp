// An animated file posed at t renders as a static file with the pose of t written into its
// nodes: the G-buffer (coverage and world positions, 64 x 64) of skinned_quad animated from 0 to
// 90 degrees, at 0.5 s, against skinned_quad(45) with no animation. The rest pose must not match
// it, so the comparison can fail.

#include "animation_files.hpp"
#include "feature_files.hpp"
#include "gbuffer_readback.hpp"
#include "vplkit/scene.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace {

vplkit::scene::Scene load(const scene_test::GltfBuilder& b, std::optional<double> time) {
    scene_test::TempDir dir("animation_gbuffer");
    vplkit::scene::LoadOptions options;
    options.time = time;
    return vplkit::scene::load_gltf(b.write(dir.path(), "posed", true), options);
}

// The largest difference between two G-buffers' positions; coverage must agree in every pixel.
float position_difference(const gltf_features::GbufferReadback& a, const gltf_features::GbufferReadback& b) {
    float worst = 0.0f;
    for (size_t i = 0; i < a.position.size(); ++i) {
        if (a.position[i].w != b.position[i].w) return INFINITY;
        if (a.position[i].w == 1.0f) {
            worst = std::max(worst, glm::length(glm::vec3(a.position[i]) - glm::vec3(b.position[i])));
        }
    }
    return worst;
}

}  // namespace

TEST_CASE("gltf animation: a skin animated to t has the G-buffer of a static file posed as at t") {
    constexpr uint32_t kSize = 64;
    auto animated = gltf_features::skinned_quad(0.0f);
    const float q = std::sqrt(0.5f);
    gltf_features::add_animations(animated, {{"wave", {{0, "rotation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, q, 0, q}}}}});
    const auto baked =
        gltf_features::read_gbuffer(load(gltf_features::skinned_quad(45.0f), std::nullopt), kSize, kSize);
    const auto posed = gltf_features::read_gbuffer(load(animated, 0.5), kSize, kSize);
    int covered = 0;
    for (const glm::vec4& p : baked.position) covered += p.w == 1.0f;
    CHECK(covered > 200);
    CHECK(position_difference(posed, baked) <= 1e-5f);
    const auto rest = gltf_features::read_gbuffer(load(animated, std::nullopt), kSize, kSize);
    CHECK(position_difference(rest, baked) > 1e-2f);
}
