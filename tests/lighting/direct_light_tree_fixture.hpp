#pragma once
// The fixture of the direct-light-tree tests (test_direct_light_tree.cpp, one-level;
// test_direct_light_tree2.cpp, two-level): scenes of emitters over a floor, the floor's G-buffer,
// the exact unshadowed direct light in double precision, a harness that renders the tree's light,
// and the unbiasedness check (the bound and why: test_direct_light_tree.cpp's header).

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/gi_counters_buffer.hpp"
#include "vplkit/gpu_light_tree.hpp"
#include "vplkit/gpu_two_level_light_tree.hpp"
#include "vplkit/gpu_lights.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/rtslc_scratch.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/stages/direct_light_tree.hpp"
#include "vplkit_test/context.hpp"
#include "direct_light_reference.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <vector>

namespace direct_tree_fixture {

using vplkit::reference::Vec3;
using Texel = std::array<float, 4>;

constexpr uint32_t kSize = 12;
inline const Vec3 kAlbedo = {0.6, 0.5, 0.4};
constexpr double kRoughness = 0.7;
inline const glm::vec3 kCamera{0.0f, 2.5f, 3.0f};

struct SceneBuilder {
    vplkit::scene::Scene s;
    SceneBuilder() {
        s.source = "direct light tree test";
        s.materials.resize(1);                                        // 0: the floor, not emissive
        add_quad({-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, 0);  // normal +y
    }
    void add_triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material) {
        const uint32_t base = uint32_t(s.vertices.size());
        for (glm::vec3 p : {a, b, c}) {
            vplkit::scene::Vertex v;
            v.position = p;
            s.vertices.push_back(v);
        }
        for (uint32_t i : {0u, 1u, 2u}) s.indices.push_back(base + i);
        if (!s.primitives.empty()) ++s.primitives.back().triangle_count;
        if (s.materials[material].emits()) s.emissive_triangles.push_back(uint32_t(s.triangle_materials.size()));
        s.triangle_materials.push_back(material);
    }
    void add_quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t material) {
        add_triangle(a, b, c, material);
        add_triangle(a, c, d, material);
    }
    // The triangles added from here to the next call are one primitive instance: one mesh light
    // of the two-level tree (two_level_lights). Without a call, all emitters are one mesh light.
    void begin_mesh_light() {
        vplkit::scene::PrimitiveInstance p;
        p.first_triangle = uint32_t(s.triangle_materials.size());
        s.primitives.push_back(p);
    }
    uint32_t add_emissive(glm::vec3 radiance, bool double_sided) {
        vplkit::scene::Material m;
        m.emissive_factor = radiance;
        m.double_sided = double_sided;
        s.materials.push_back(m);
        return uint32_t(s.materials.size() - 1);
    }
};

// A small triangle centred at c, facing down (-y) or up (+y), of size r.
inline void add_small_emitter(SceneBuilder& b, glm::vec3 c, float r, bool down, uint32_t material) {
    const glm::vec3 p0 = c + glm::vec3(-r, 0, -r), p1 = c + glm::vec3(r, 0, -r), p2 = c + glm::vec3(0, 0, r);
    if (down) {
        b.add_triangle(p0, p1, p2, material);  // (p1 - p0) x (p2 - p0) points down
    } else {
        b.add_triangle(p0, p2, p1, material);
    }
}

// A deterministic stream for placing emitters.
struct Lcg {
    uint32_t state;
    float next() {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / float(1u << 24);
    }
};

// `count` emitters over the floor with radiance spread over 1e-4..1e4 (log-uniform, varied
// colour), mostly facing down; every 7th faces up one-sided (lights nothing below), every 5th is
// double-sided facing up (lights the floor with its back).
inline SceneBuilder many_emitters(uint32_t count, uint32_t seed) {
    SceneBuilder b;
    Lcg rng{seed};
    for (uint32_t i = 0; i < count; ++i) {
        const float power = std::pow(10.0f, -4.0f + 8.0f * rng.next());
        const glm::vec3 colour{0.3f + rng.next(), 0.3f + rng.next(), 0.3f + rng.next()};
        const bool double_sided = i % 5 == 4;
        const uint32_t material = b.add_emissive(colour * power, double_sided);
        const glm::vec3 c{-1.8f + 3.6f * rng.next(), 0.4f + 1.6f * rng.next(), -1.8f + 3.6f * rng.next()};
        add_small_emitter(b, c, 0.05f + 0.2f * rng.next(), !(double_sided || i % 7 == 6), material);
    }
    return b;
}

struct Floor {
    std::vector<Texel> position, normal, geometric;
    std::vector<std::array<uint16_t, 4>> albedo;
};

// Floor points; every 5th pixel is background.
// The punctual lights of the unbiasedness tests: a point light, a spot lighting the floor, a spot
// whose cone misses every pixel (it lights the ceiling only), and a directional light (not the
// tree's).
inline std::vector<vplkit::scene::Light> hard_case_punctual_lights() {
    vplkit::scene::Light point;
    point.position = {0.6f, 1.3f, -0.4f};
    point.color = {1.0f, 0.8f, 0.6f};
    point.intensity = 2.0f;
    vplkit::scene::Light spot = point;
    spot.type = vplkit::scene::LightType::spot;
    spot.position = {-0.8f, 1.6f, 0.7f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.inner_cone_angle = 0.3f;
    spot.outer_cone_angle = 0.6f;
    spot.intensity = 5.0f;
    vplkit::scene::Light away = spot;
    away.direction = {0.0f, 1.0f, 0.0f};
    vplkit::scene::Light sun;
    sun.type = vplkit::scene::LightType::directional;
    sun.direction = {0.0f, -1.0f, 0.0f};
    return {point, spot, away, sun};
}

inline Floor make_floor() {
    Floor f;
    for (uint32_t y = 0; y < kSize; ++y) {
        for (uint32_t x = 0; x < kSize; ++x) {
            const bool covered = (x + 3 * y) % 5 != 0;
            f.position.push_back(
                {-1.7f + 3.4f * (x + 0.5f) / kSize, 0.0f, -1.7f + 3.4f * (y + 0.5f) / kSize, covered ? 1.0f : 0.0f});
            f.normal.push_back({0, 1, 0, float(kRoughness)});
            f.geometric.push_back({0, 1, 0, 0});
            f.albedo.push_back({glm::packHalf1x16(float(kAlbedo[0])), glm::packHalf1x16(float(kAlbedo[1])),
                                glm::packHalf1x16(float(kAlbedo[2])), glm::packHalf1x16(1.0f)});
        }
    }
    return f;
}

inline Vec3 to_vec3(glm::vec3 v) {
    return {v.x, v.y, v.z};
}

// The exact direct light at floor point x from every emissive triangle and every point and spot
// light (directional lights are not the tree's), unshadowed.
inline Vec3 reference(const vplkit::scene::Scene& scene, const Vec3& x, const Vec3& albedo) {
    Vec3 wo = {kCamera.x - x[0], kCamera.y - x[1], kCamera.z - x[2]};
    const double wl = std::sqrt(wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2]);
    for (double& c : wo) c /= wl;
    const Vec3 n = {0, 1, 0};
    Vec3 sum = {0, 0, 0};
    auto add_from = [&](const Vec3& y, const Vec3& n_y, bool double_sided, const Vec3& radiance, double area) {
        Vec3 d = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
        const double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        const double dl = std::sqrt(d2);
        for (double& c : d) c /= dl;
        const double cos_x = d[1];
        double cos_y = -(n_y[0] * d[0] + n_y[1] * d[1] + n_y[2] * d[2]);
        if (double_sided) cos_y = std::abs(cos_y);
        if (cos_x <= 0 || cos_y <= 0) return;
        const Vec3 f = vplkit::reference::gltf_brdf(n, wo, d, albedo, kRoughness, 0.0);
        for (int c = 0; c < 3; ++c) sum[c] += f[c] * radiance[c] * cos_x * cos_y / d2 * area;
    };
    constexpr int m = 48;  // sub-triangles per edge
    for (uint32_t t : scene.emissive_triangles) {
        const auto& mat = scene.materials[scene.triangle_materials[t]];
        const Vec3 radiance = to_vec3(mat.emission());
        glm::dvec3 a = scene.vertices[scene.indices[3 * t]].position;
        glm::dvec3 b = scene.vertices[scene.indices[3 * t + 1]].position;
        glm::dvec3 c = scene.vertices[scene.indices[3 * t + 2]].position;
        const glm::dvec3 cross = glm::cross(b - a, c - a);
        const double area = 0.5 * glm::length(cross);
        if (!(area > 0)) continue;
        const glm::dvec3 n_y = cross / (2 * area);
        const double sub_area = area / (m * m);
        // The m^2 sub-triangles of the regular subdivision: m(m+1)/2 upright, m(m-1)/2 inverted.
        for (int i = 0; i < m; ++i) {
            for (int j = 0; i + j < m; ++j) {
                const glm::dvec3 up = a + (b - a) * ((i + 1.0 / 3.0) / m) + (c - a) * ((j + 1.0 / 3.0) / m);
                add_from({up.x, up.y, up.z}, {n_y.x, n_y.y, n_y.z}, mat.double_sided, radiance, sub_area);
                if (i + j + 1 < m) {
                    const glm::dvec3 down = a + (b - a) * ((i + 2.0 / 3.0) / m) + (c - a) * ((j + 2.0 / 3.0) / m);
                    add_from({down.x, down.y, down.z}, {n_y.x, n_y.y, n_y.z}, mat.double_sided, radiance, sub_area);
                }
            }
        }
    }
    for (const auto& light : scene.lights) {
        if (light.type == vplkit::scene::LightType::directional) continue;
        vplkit::reference::LightDesc desc;
        desc.kind = light.type == vplkit::scene::LightType::spot ? vplkit::reference::LightKind::spot
                                                                 : vplkit::reference::LightKind::point;
        desc.position = to_vec3(light.position);
        desc.direction = to_vec3(light.direction);
        desc.intensity = to_vec3(light.color * light.intensity);
        desc.range = light.range;
        desc.inner_cone = light.inner_cone_angle;
        desc.outer_cone = light.outer_cone_angle;
        const auto incidence = vplkit::reference::sample_light(desc, x);
        const double cos_x = incidence.wi[1];
        if (cos_x <= 0) continue;
        const Vec3 f = vplkit::reference::gltf_brdf(n, wo, incidence.wi, albedo, kRoughness, 0.0);
        for (int c = 0; c < 3; ++c) sum[c] += f[c] * incidence.irradiance[c] * cos_x;
    }
    return sum;
}

// The scene's tree, built once, and frames rendered through it.
class Harness {
public:
    // two_level: run() samples the two-level tree (GpuTwoLevelLightTree) instead of the one-level one.
    Harness(const vplkit::scene::Scene& scene, const Floor& floor, bool two_level = false)
        : ctx_(vplkit::test::context()),
          gbuffer_(vplkit::GbufferImages::create(ctx_, kSize, kSize)),
          bvh_(vplkit::upload_bvh(ctx_, vplkit::build_bvh(vplkit::scene::triangle_positions(scene)))),
          emitters_(vplkit::upload_emitters(ctx_, scene)),
          tree_(vplkit::GpuLightTree::create(ctx_, scene, emitters_)),
          counters_(vplkit::create_gi_counters(ctx_)) {
        gbuffer_.position.upload(floor.position);
        gbuffer_.normal.upload(floor.normal);
        gbuffer_.geometric_normal.upload(floor.geometric);
        gbuffer_.albedo.upload(floor.albedo);
        vplkit::PassList build("light tree over lights");
        tree_.add_build_passes(ctx_, build);
        build.run(ctx_);
        if (two_level) two_level_.emplace(vplkit::GpuTwoLevelLightTree::create(ctx_, scene, emitters_));
    }

    // interleave > 1: the interleaved passes, the tree's light alone (frame = seed rotates the shares).
    std::vector<Texel> run(uint32_t seed, uint32_t samples, bool visibility, float initial = 0.0f, uint32_t block = 4,
                           uint32_t interleave = 1) {
        auto radiance = vplkit::Image::create(ctx_, kSize, kSize, VK_FORMAT_R32G32B32A32_SFLOAT,
                                              VK_IMAGE_USAGE_STORAGE_BIT, "radiance");
        radiance.upload(std::vector<Texel>(kSize * kSize, Texel{initial, initial, initial, 1.0f}));
        vplkit::stages::RtslcOptions options;
        options.samples_per_pixel = samples;
        options.block_size = block;
        options.seed = seed;
        options.frame = seed;
        options.visibility = visibility;
        options.interleave = interleave;
        auto scratch = vplkit::RtslcScratch::create(ctx_, kSize, kSize, options);
        vplkit::PassList passes("direct light tree test");
        const vplkit::stages::DirectLightTree tree = two_level_ ? vplkit::stages::DirectLightTree(two_level_->buffers())
                                                                : vplkit::stages::DirectLightTree(tree_.buffers());
        if (interleave > 1) {
            vplkit::stages::add_direct_light_tree_interleaved_passes(ctx_, passes, gbuffer_, bvh_, tree, kCamera,
                                                                     radiance, counters_, options, scratch);
        } else {
            vplkit::stages::add_direct_light_tree_passes(ctx_, passes, gbuffer_, bvh_, tree, kCamera, radiance,
                                                         counters_, options, scratch);
        }
        passes.run(ctx_);
        counts = vplkit::read_gi_counters(counters_);
        return radiance.download<Texel>();
    }

    const vplkit::GpuLightTree& tree() const { return tree_; }
    const vplkit::GpuTwoLevelLightTree& two_level() const { return *two_level_; }
    vplkit::stages::GiCounts counts;

private:
    vplkit::Context& ctx_;
    vplkit::GbufferImages gbuffer_;
    vplkit::GpuBvh bvh_;
    vplkit::GpuEmitters emitters_;
    vplkit::GpuLightTree tree_;
    std::optional<vplkit::GpuTwoLevelLightTree> two_level_;
    vplkit::Buffer counters_;
};

// The mean over `seeds` seeds against the reference (visibility off), per covered pixel and
// channel; returns the largest |mean - exact| / (sigma / sqrt(seeds)).
inline double check_unbiased(const vplkit::scene::Scene& scene, Harness& harness, const Floor& floor, int seeds,
                             uint32_t samples, bool expect_light = true) {
    std::vector<std::vector<Texel>> images;
    for (int s = 0; s < seeds; ++s) {
        images.push_back(harness.run(7000 + uint32_t(s), samples, false));
        REQUIRE(harness.counts.cut_short == 0);
        CHECK(harness.counts.dropped_samples == 0);
    }
    const Vec3 albedo = {glm::unpackHalf1x16(floor.albedo[0][0]), glm::unpackHalf1x16(floor.albedo[0][1]),
                         glm::unpackHalf1x16(floor.albedo[0][2])};
    double worst_z = 0.0;
    int lit = 0;
    for (uint32_t i = 0; i < kSize * kSize; ++i) {
        CAPTURE(i);
        if (floor.position[i][3] == 0.0f) {
            for (const auto& img : images) CHECK(img[i][0] == 0.0f);  // background untouched
            continue;
        }
        const Vec3 expected = reference(scene, {floor.position[i][0], 0.0, floor.position[i][2]}, albedo);
        for (int c = 0; c < 3; ++c) {
            CAPTURE(c);
            double mean = 0.0, square = 0.0;
            for (const auto& img : images) {
                REQUIRE(std::isfinite(img[i][c]));
                mean += img[i][c];
                square += double(img[i][c]) * img[i][c];
            }
            mean /= seeds;
            const double sigma = std::sqrt(std::max(square / seeds - mean * mean, 0.0) * seeds / (seeds - 1));
            const double bound = 5.0 * sigma / std::sqrt(double(seeds)) + 2e-3 * expected[c];
            CHECK(std::abs(mean - expected[c]) <= bound);
            if (sigma > 0.0) worst_z = std::max(worst_z, std::abs(mean - expected[c]) / (sigma / std::sqrt(seeds)));
            lit += expected[c] > 0.0 ? 1 : 0;
        }
    }
    CHECK((lit > 0) == expect_light);
    return worst_z;
}

}  // namespace direct_tree_fixture
