// direct_emissive.comp: its Monte Carlo estimate, averaged over seeds, against the direct-light
// integral over the emitter computed in double precision by dense quadrature (the square emitter
// split into 128 x 128 cells, midpoint rule: relative error ~1e-5 here, far below the Monte Carlo
// bound). Check: |mean - reference| <= 5 sigma / sqrt(seeds) + 1e-3 reference,
// sigma the spread of the per-seed estimates (DESIGN.md: stochastic estimators are checked
// against the exact value within k sigma / sqrt(n)).

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/gpu_lights.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/stages/selection_cdf.hpp"
#include "vplkit/shaders/direct_emissive.hpp"
#include "vplkit_test/context.hpp"
#include "direct_light_reference.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include <array>
#include <cmath>
#include <vector>

namespace {

using vplkit::reference::Vec3;
using Texel = std::array<float, 4>;

constexpr uint32_t kSize = 12;
const Vec3 kEmitted = {2.0, 1.5, 1.0};
const Vec3 kAlbedo = {0.6, 0.5, 0.4};
constexpr double kRoughness = 0.7;
const glm::vec3 kCamera{0.0f, 2.5f, 3.0f};

// A floor at y = 0 and a 1 x 1 emitter at y = 1.5 facing down (its winding's normal is -y),
// optionally a plate at y = 1 that hides the emitter from the floor's centre. `back_down`: the
// emitter's winding faces up instead and its material is double-sided, so its back lights the
// floor exactly as the one-sided front did.
vplkit::scene::Scene make_scene(bool with_plate, bool back_down = false) {
    vplkit::scene::Scene s;
    auto add_quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t material) {
        const uint32_t base = uint32_t(s.vertices.size());
        for (glm::vec3 p : {a, b, c, d}) {
            vplkit::scene::Vertex v;
            v.position = p;
            s.vertices.push_back(v);
        }
        for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) s.indices.push_back(base + i);
        s.triangle_materials.push_back(material);
        s.triangle_materials.push_back(material);
    };
    add_quad({-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, 0);  // floor, normal +y
    if (back_down) {
        add_quad({-0.5f, 1.5f, 0.5f}, {0.5f, 1.5f, 0.5f}, {0.5f, 1.5f, -0.5f}, {-0.5f, 1.5f, -0.5f}, 1);  // normal +y
    } else {
        add_quad({-0.5f, 1.5f, -0.5f}, {0.5f, 1.5f, -0.5f}, {0.5f, 1.5f, 0.5f}, {-0.5f, 1.5f, 0.5f}, 1);  // normal -y
    }
    if (with_plate) add_quad({-0.6f, 1, -0.6f}, {-0.6f, 1, 0.6f}, {0.6f, 1, 0.6f}, {0.6f, 1, -0.6f}, 0);
    s.materials.resize(2);
    s.materials[1].emissive_factor = {float(kEmitted[0]), float(kEmitted[1]), float(kEmitted[2])};
    s.materials[1].double_sided = back_down;
    s.emissive_triangles = {2, 3};
    return s;
}

struct Floor {
    std::vector<Texel> position, normal, geometric;
    std::vector<std::array<uint16_t, 4>> albedo;
};

// Floor points under and around the emitter; every 5th pixel is background.
Floor make_floor() {
    Floor f;
    for (uint32_t y = 0; y < kSize; ++y) {
        for (uint32_t x = 0; x < kSize; ++x) {
            const bool covered = (x + 3 * y) % 5 != 0;
            f.position.push_back(
                {-1.6f + 3.2f * (x + 0.5f) / kSize, 0.0f, -1.6f + 3.2f * (y + 0.5f) / kSize, covered ? 1.0f : 0.0f});
            f.normal.push_back({0, 1, 0, float(kRoughness)});
            f.geometric.push_back({0, 1, 0, 0});
            f.albedo.push_back({glm::packHalf1x16(float(kAlbedo[0])), glm::packHalf1x16(float(kAlbedo[1])),
                                glm::packHalf1x16(float(kAlbedo[2])), glm::packHalf1x16(1.0f)});
        }
    }
    return f;
}

// The direct light from the emitter square at floor point x: midpoint rule on n x n equal cells.
Vec3 reference(const Vec3& x, const Vec3& albedo) {
    constexpr int n = 128;
    const double cell = 1.0 / n;
    Vec3 wo = {kCamera.x - x[0], kCamera.y - x[1], kCamera.z - x[2]};
    const double wl = std::sqrt(wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2]);
    for (double& c : wo) c /= wl;
    Vec3 sum = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const Vec3 y = {-0.5 + (i + 0.5) * cell, 1.5, -0.5 + (j + 0.5) * cell};
            Vec3 d = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
            const double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            const double dl = std::sqrt(d2);
            for (double& c : d) c /= dl;
            const double cos_x = d[1], cos_y = d[1];  // floor normal +y, emitter normal -y
            if (cos_x <= 0) continue;
            const Vec3 f = vplkit::reference::gltf_brdf({0, 1, 0}, wo, d, albedo, kRoughness, 0.0);
            for (int c = 0; c < 3; ++c) sum[c] += f[c] * kEmitted[c] * cos_x * cos_y / d2 * cell * cell;
        }
    }
    return sum;
}

std::vector<Texel> run(const vplkit::scene::Scene& scene, const Floor& floor, uint32_t seed, uint32_t samples,
                       float initial) {
    vplkit::Context& ctx = vplkit::test::context();
    auto gbuffer = vplkit::GbufferImages::create(ctx, kSize, kSize);
    gbuffer.position.upload(floor.position);
    gbuffer.normal.upload(floor.normal);
    gbuffer.geometric_normal.upload(floor.geometric);
    gbuffer.albedo.upload(floor.albedo);
    const auto bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(vplkit::scene::triangle_positions(scene)));
    const auto emitters = vplkit::upload_emitters(ctx, scene);
    auto radiance =
        vplkit::Image::create(ctx, kSize, kSize, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "radiance");
    radiance.upload(std::vector<Texel>(kSize * kSize, Texel{initial, initial, initial, 1.0f}));
    vplkit::PassList passes("direct emissive test");
    vplkit::stages::add_direct_emissive_pass(ctx, passes, gbuffer, bvh, emitters, {kCamera, samples, seed}, radiance);
    passes.run(ctx);
    return radiance.download<Texel>();
}

// The mean over `seeds` seeds of the estimate against the quadrature, per covered pixel and channel.
// Returns the images.
std::vector<std::vector<Texel>> check_against_reference(const vplkit::scene::Scene& scene, const Floor& floor) {
    constexpr int seeds = 12;
    std::vector<std::vector<Texel>> images;
    for (int s = 0; s < seeds; ++s) images.push_back(run(scene, floor, 1000 + s, 16, 0.0f));
    const Vec3 albedo = {glm::unpackHalf1x16(floor.albedo[0][0]), glm::unpackHalf1x16(floor.albedo[0][1]),
                         glm::unpackHalf1x16(floor.albedo[0][2])};
    int checked = 0;
    for (uint32_t i = 0; i < kSize * kSize; ++i) {
        CAPTURE(i);
        if (floor.position[i][3] == 0.0f) {
            for (const auto& img : images) CHECK(img[i][0] == 0.0f);  // background untouched
            continue;
        }
        const Vec3 expected = reference({floor.position[i][0], 0.0, floor.position[i][2]}, albedo);
        for (int c = 0; c < 3; ++c) {
            double mean = 0.0, square = 0.0;
            for (const auto& img : images) {
                mean += img[i][c];
                square += double(img[i][c]) * img[i][c];
            }
            mean /= seeds;
            const double sigma = std::sqrt(std::max(square / seeds - mean * mean, 0.0) * seeds / (seeds - 1));
            CHECK(std::abs(mean - expected[c]) <= 5.0 * sigma / std::sqrt(double(seeds)) + 1e-3 * expected[c]);
            CHECK(expected[c] > 0.0);
        }
        ++checked;
    }
    CHECK(checked > 100);
    return images;
}

}  // namespace

TEST_CASE("direct emissive: the mean over seeds matches the emitter integral within 5 sigma") {
    const auto scene = make_scene(false);
    const auto floor = make_floor();
    const auto images = check_against_reference(scene, floor);
    // The same seed gives the same image; another seed another one.
    CHECK(run(scene, floor, 1000, 16, 0.0f) == images[0]);
    CHECK(images[1] != images[0]);
}

TEST_CASE("direct emissive: a double-sided emitter lights with its back as with its front") {
    // glTF doubleSided: light paths (trace_vpls.comp) leave both faces; direct light must see
    // both too, or the floor under an upward-wound double-sided emitter stays dark.
    check_against_reference(make_scene(false, true), make_floor());
}

TEST_CASE("direct emissive: every emitter with power can be drawn, with the probability it is weighed by") {
    // A bright emitter's power next to one 1e-9 as bright: in float, the dim one's CDF interval
    // rounded to zero width (never drawn: its light lost) while a separately stored pmf weighed
    // it. The CDF is now on the random numbers' 2^-24 grid, every emitter with power at least
    // one step, and the shader's pmf is the CDF's step.
    vplkit::Context& ctx = vplkit::test::context();
    auto scene = make_scene(false);
    scene.materials.push_back(scene.materials[1]);
    scene.materials[1].emissive_factor *= 1e9f;
    scene.triangle_materials[3] = 2;  // the emitter's second triangle is the dim one
    const auto emitters = vplkit::upload_emitters(ctx, scene);
    REQUIRE(emitters.count == 2);
    const auto triangles = emitters.triangles.download<vplkit::shaders::EmissiveTriangle>(2);
    const float step = 1.0f / float(vplkit::stages::kSelectionSteps);
    CHECK(triangles[0].cdf > 0.0f);
    CHECK(triangles[1].cdf - triangles[0].cdf >= step);
    CHECK(triangles[1].cdf == 1.0f);
}

TEST_CASE("selection cdf: on the 2^-24 grid, a step for every positive weight, none for zero weights") {
    const std::vector<double> weights = {0.0, 1.0, 1e-12, 0.0, 3.0, 1e-30, 2.5, 0.0};
    const auto cdf = vplkit::stages::selection_cdf(weights);
    REQUIRE(cdf.size() == weights.size());
    const double steps = vplkit::stages::kSelectionSteps;
    double sum = 0.0;
    for (double w : weights) sum += w;
    double previous = 0.0;
    for (size_t i = 0; i < cdf.size(); ++i) {
        CAPTURE(i);
        const double k = double(cdf[i]) * steps;
        CHECK(k == std::floor(k));  // a multiple of 2^-24
        const double width = double(cdf[i]) - previous;
        if (weights[i] > 0.0) {
            CHECK(width >= 1.0 / steps);
            CHECK(std::abs(width - weights[i] / sum) <= 2.0 / steps);  // one forced step plus rounding
        } else {
            CHECK(width == 0.0);
        }
        previous = cdf[i];
    }
    CHECK(cdf[6] == 1.0f);  // the last positive weight ends at 1; the trailing zero stays there
    CHECK(cdf[7] == 1.0f);
    CHECK_THROWS_AS(vplkit::stages::selection_cdf({0.0, 0.0}), vplkit::Error);
    CHECK_THROWS_AS(vplkit::stages::selection_cdf({1.0, -1.0}), vplkit::Error);
    CHECK_THROWS_AS(vplkit::stages::selection_cdf({1.0, std::nan("")}), vplkit::Error);
}

TEST_CASE("direct emissive: light adds to what is there and an occluder blocks it") {
    const auto floor = make_floor();
    const auto open = run(make_scene(false), floor, 7, 8, 0.25f);
    const auto covered = run(make_scene(true), floor, 7, 8, 0.25f);
    // The floor's centre pixel (under the plate): the plate hides the whole emitter from it.
    const uint32_t centre = (kSize / 2) * kSize + kSize / 2;
    REQUIRE(floor.position[centre][3] == 1.0f);
    CHECK(open[centre][0] > 0.25f);
    CHECK(covered[centre][0] == 0.25f);
}

TEST_CASE("direct emissive: a scene without emitters adds nothing and zero samples are refused") {
    vplkit::Context& ctx = vplkit::test::context();
    auto scene = make_scene(false);
    scene.emissive_triangles.clear();
    const auto emitters = vplkit::upload_emitters(ctx, scene);
    CHECK(emitters.count == 0);
    auto gbuffer = vplkit::GbufferImages::create(ctx, 4, 4);
    const auto bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(vplkit::scene::triangle_positions(scene)));
    auto radiance =
        vplkit::Image::create(ctx, 4, 4, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "radiance");
    // The pass records (whether it runs is the planner's decision) and leaves the radiance as it was.
    const std::vector<std::array<float, 4>> before(16, {0.25f, 0.5f, 0.75f, 1.0f});
    radiance.upload(before);
    vplkit::PassList passes;
    vplkit::stages::add_direct_emissive_pass(ctx, passes, gbuffer, bvh, emitters, {kCamera, 4, 0}, radiance);
    CHECK(passes.size() == 1);
    passes.run(ctx);
    CHECK(radiance.download<std::array<float, 4>>() == before);
    CHECK_THROWS_WITH_AS(
        vplkit::stages::add_direct_emissive_pass(ctx, passes, gbuffer, bvh, emitters, {kCamera, 0, 0}, radiance),
        doctest::Contains("at least 1"), vplkit::Error);
}
