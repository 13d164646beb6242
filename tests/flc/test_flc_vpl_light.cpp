// flc_vpl_light.comp (the light at forward-light-cuts VPLs) against a CPU reference in double:
// flux / S_k = E(centroid) x rho on a grid of triangles in z = 0 facing +z, with an occluding
// square in z = 1.5 (in the BVH, not a candidate).
// Punctual lights: shadowed candidates must get exactly 0; lit ones E x rho within 1e-4 relative
// (a few float roundings of I cos / d^2). Candidates whose shadow ray crosses the occluder's plane
// within 1e-3 of its border are skipped (float and double may disagree about the hit there).
// Emitter: E is a mean of area samples, each the integrand L cos_x cos_y / d^2 x area at one
// point of the emitter (one emitter: pmf 1). The mean must lie between the integrand's minimum and
// maximum over the emitter (from a 64 x 64 quadrature; 5e-3 slack for the quadrature missing the
// extremes), a bound that holds for every sample count, and the mean over candidates must match
// the quadrature's within 2% (the emitter is small: the integrand varies by a few % across it).

#include "flc_test_mesh.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gpu_lights.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/flc.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

namespace {

using vplkit::shaders::FlcCandidate;
using vplkit::shaders::Vpl;
using namespace flc_test;

constexpr double kOccluderHeight = 1.5;
constexpr double kOccluderLow = 0.4, kOccluderHigh = 1.6;  // the square [low, high]^2

// The test partition: 3 levels, triangles of area 0.125 kept with probability 0.875.
vplkit::stages::FlcPartition partition() {
    return {3, 0.25f, 1.0f, 2.0f};
}

struct Emitter {
    glm::dvec3 v0, v1, v2;
    glm::dvec3 radiance;
};

struct Run {
    std::vector<FlcCandidate> candidates;
    std::vector<uint32_t> kept;
    std::vector<Vpl> vpls;
    std::vector<glm::vec4> albedo;
};

std::vector<glm::vec3> square(double h) {
    const float lo = float(kOccluderLow), hi = float(kOccluderHigh), z = float(h);
    return {{lo, lo, z}, {hi, lo, z}, {hi, hi, z}, {lo, lo, z}, {hi, hi, z}, {lo, hi, z}};
}

// scene_area: the light pass's partition.scene_area (0: S_k = S_0 mu^k; else the fitted S_k).
Run run(const Mesh& mesh, bool occluder, const std::vector<vplkit::scene::Light>& lights,
        const std::optional<Emitter>& emitter, uint32_t emitter_samples, float scene_area = 0.0f) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t count = mesh.triangle_count();
    std::vector<vplkit::scene::Vertex> vertices(mesh.positions.size());
    for (size_t i = 0; i < vertices.size(); ++i) vertices[i].position = mesh.positions[i];
    std::vector<glm::vec3> bvh_vertices;
    for (uint32_t index : mesh.indices) bvh_vertices.push_back(mesh.positions[index]);
    if (occluder) {
        const auto quad = square(kOccluderHeight);
        bvh_vertices.insert(bvh_vertices.end(), quad.begin(), quad.end());
    }
    Run r;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.1f, 1.0f);
    for (uint32_t t = 0; t < count; ++t) r.albedo.push_back({unit(rng), unit(rng), unit(rng), 0.0f});

    auto create = [&](VkDeviceSize bytes, const char* name) {
        return vplkit::Buffer::create(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, name);
    };
    auto vertex_buffer = create(vertices.size() * sizeof(vplkit::scene::Vertex), "flc vertices");
    auto index_buffer = create(mesh.indices.size() * sizeof(uint32_t), "flc indices");
    auto random_buffer = create(mesh.random.size() * sizeof(uint32_t), "flc vertex random");
    auto candidates = create(count * sizeof(FlcCandidate), "flc candidates");
    auto counts = create(vplkit::stages::flc_count_bytes(3), "flc counts");
    auto kept = create(count * sizeof(uint32_t), "flc kept");
    auto divergent = create(count * sizeof(uint32_t), "flc divergent");
    auto albedo = create(count * sizeof(glm::vec4), "flc albedo");
    auto vpls = create(count * sizeof(Vpl), "flc vpls");
    auto emitter_buffer = create(sizeof(vplkit::shaders::EmissiveTriangle), "flc emitters");
    vertex_buffer.upload(vertices);
    index_buffer.upload(mesh.indices);
    random_buffer.upload(mesh.random);
    albedo.upload(r.albedo);
    vplkit::shaders::EmissiveTriangle e{};
    if (emitter) {
        e.v0 = {float(emitter->v0.x), float(emitter->v0.y), float(emitter->v0.z)};
        e.v1 = {float(emitter->v1.x), float(emitter->v1.y), float(emitter->v1.z)};
        e.v2 = {float(emitter->v2.x), float(emitter->v2.y), float(emitter->v2.z)};
        e.area = float(0.5 * glm::length(glm::cross(emitter->v1 - emitter->v0, emitter->v2 - emitter->v0)));
        e.cdf = 1.0f;
        e.radiance = {float(emitter->radiance.x), float(emitter->radiance.y), float(emitter->radiance.z)};
    }
    emitter_buffer.upload(std::vector<vplkit::shaders::EmissiveTriangle>{e});
    const auto bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(bvh_vertices));
    const auto gpu_lights = vplkit::upload_lights(ctx, lights);

    vplkit::PassList passes("flc vpl light test");
    vplkit::stages::add_flc_candidates_pass(ctx, passes, {vertex_buffer, index_buffer, random_buffer, candidates},
                                            partition(), count, 7);
    vplkit::stages::add_flc_compact_passes(ctx, passes, {candidates, counts, kept, divergent}, 3, count);
    vplkit::stages::FlcPartition light_partition = partition();
    light_partition.scene_area = scene_area;
    vplkit::stages::add_flc_vpl_light_pass(
        ctx, passes, bvh, gpu_lights, vplkit::stages::EmitterBuffers{emitter_buffer, emitter ? 1u : 0u},
        {candidates, counts, kept, albedo, vpls}, light_partition, count, {emitter_samples, 3});
    passes.run(ctx);
    r.candidates = candidates.download<FlcCandidate>(count);
    const uint32_t kept_count = counts.download<uint32_t>(1)[0];
    r.kept = kept.download<uint32_t>(kept_count);
    r.vpls = vpls.download<Vpl>(count);
    r.vpls.resize(kept_count);
    return r;
}

glm::dvec3 to_d(const vplkit::shaders::vec3& v) {
    return {v.x, v.y, v.z};
}

// Whether the segment from c towards `to_light` (unit) crosses the occluder: -1 near its border.
int occluded(const glm::dvec3& c, const glm::dvec3& to_light) {
    if (to_light.z <= 0.0) return 0;
    const double s = (kOccluderHeight - c.z) / to_light.z;
    const glm::dvec3 p = c + s * to_light;
    const double inside = std::min({p.x - kOccluderLow, kOccluderHigh - p.x, p.y - kOccluderLow, kOccluderHigh - p.y});
    if (std::abs(inside) < 1e-3) return -1;
    return inside > 0.0 ? 1 : 0;
}

// S_k = 0.25 x 2^k, or fitted to scene_area: scene_area / floor(scene_area / S_k) (written here
// from flc_partition.glsl's description, in double).
double level_area(int k, double scene_area = 0.0) {
    const double nominal = 0.25 * std::pow(2.0, double(k));
    const double count = std::floor(scene_area / nominal);
    return count >= 1.0 ? scene_area / count : nominal;
}

// Checks flux / S_k against E x rho for punctual lights; returns {lit, shadowed} counts.
std::pair<int, int> check_punctual(const Run& r, const std::vector<vplkit::scene::Light>& lights,
                                   double scene_area = 0.0) {
    int lit = 0, shadowed = 0;
    for (size_t i = 0; i < r.kept.size(); ++i) {
        const uint32_t t = r.kept[i];
        const FlcCandidate& c = r.candidates[t];
        REQUIRE(c.level >= 0);
        CHECK(to_d(r.vpls[i].position) == to_d(c.position));
        CHECK(to_d(r.vpls[i].normal) == to_d(c.normal));
        const glm::dvec3 x = to_d(c.position);
        glm::dvec3 e(0.0);
        bool skip = false, any_shadow = false;
        for (const auto& l : lights) {
            const glm::dvec3 intensity = glm::dvec3(l.color) * double(l.intensity);
            glm::dvec3 wi, irradiance;
            if (l.type == vplkit::scene::LightType::directional) {
                wi = -glm::normalize(glm::dvec3(l.direction));
                irradiance = intensity;
            } else {
                const glm::dvec3 to = glm::dvec3(l.position) - x;
                wi = glm::normalize(to);
                irradiance = intensity / glm::dot(to, to);
            }
            const double cos_theta = wi.z;  // the grid faces +z
            if (cos_theta <= 0.0) continue;
            const int o = occluded(x, wi);
            if (o < 0) skip = true;
            if (o == 1) any_shadow = true;
            if (o == 0) e += irradiance * cos_theta;
        }
        if (skip) continue;
        const glm::dvec3 expected = e * glm::dvec3(r.albedo[t]);
        const glm::dvec3 got = to_d(r.vpls[i].flux) / level_area(c.level, scene_area);
        if (e == glm::dvec3(0.0)) {
            CHECK(to_d(r.vpls[i].flux) == glm::dvec3(0.0));  // shadowed: exactly nothing
            ++shadowed;
        } else {
            for (int ch = 0; ch < 3; ++ch) CHECK(std::abs(got[ch] - expected[ch]) <= 1e-4 * expected[ch] + 1e-9);
            any_shadow ? ++shadowed : ++lit;
        }
    }
    return {lit, shadowed};
}

}  // namespace

TEST_CASE("flc vpl light: a point light with an occluder, flux = E x rho x S_k, shadowed VPLs get 0") {
    const Mesh mesh = grid(8, 0.5f);  // [0, 4]^2, 128 triangles of area 0.125
    vplkit::scene::Light point;
    point.type = vplkit::scene::LightType::point;
    point.position = {1.0f, 1.0f, 3.0f};
    point.color = {1.0f, 0.8f, 0.6f};
    point.intensity = 10.0f;
    const std::vector<vplkit::scene::Light> lights = {point};
    const Run r = run(mesh, true, lights, std::nullopt, 1);
    CHECK(r.kept.size() > 90);  // 0.875 x 128 = 112 expected
    const auto [lit, shadowed] = check_punctual(r, lights);
    MESSAGE("point light: " << r.kept.size() << " VPLs kept of 128, " << lit << " lit, " << shadowed << " shadowed");
    CHECK(lit > 20);
    CHECK(shadowed > 20);  // the shadow covers [-0.2, 2.2]^2: about a third of the grid
}

TEST_CASE("flc vpl light: a directional light with an occluder matches E x rho") {
    const Mesh mesh = grid(8, 0.5f);
    vplkit::scene::Light sun;
    sun.type = vplkit::scene::LightType::directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f));
    sun.color = {1.0f, 0.9f, 0.8f};
    sun.intensity = 3.0f;
    const std::vector<vplkit::scene::Light> lights = {sun};
    const Run r = run(mesh, true, lights, std::nullopt, 1);
    const auto [lit, shadowed] = check_punctual(r, lights);
    MESSAGE("directional light: " << lit << " lit, " << shadowed << " shadowed");
    CHECK(lit > 40);
    CHECK(shadowed > 5);
}

TEST_CASE("flc vpl light: with the level areas fitted to a scene area, flux = E x rho x the fitted S_k") {
    // 17.3 / S_k = 69.2, 34.6, 17.3: S_k becomes 17.3 / 69, / 34, / 17, each 0.3% to 1.8% above
    // S_0 mu^k (the stratified decimation draws with these; the light must carry the same).
    const Mesh mesh = grid(8, 0.5f);
    vplkit::scene::Light sun;
    sun.type = vplkit::scene::LightType::directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f));
    sun.color = {1.0f, 0.9f, 0.8f};
    sun.intensity = 3.0f;
    const std::vector<vplkit::scene::Light> lights = {sun};
    const Run r = run(mesh, true, lights, std::nullopt, 1, 17.3f);
    const int lit = check_punctual(r, lights, 17.3).first;
    MESSAGE("directional light, fitted level areas: " << lit << " lit");
    CHECK(lit > 40);
}

TEST_CASE("flc vpl light: an emissive triangle's irradiance by area samples lies within the integrand's range") {
    const Mesh mesh = grid(8, 0.5f);
    // A small emitter facing down (clockwise seen from above: its front is -z).
    const Emitter emitter{{2.0, 2.0, 2.5}, {2.0, 2.1, 2.5}, {2.1, 2.0, 2.5}, {40.0, 30.0, 20.0}};
    const Run r = run(mesh, false, {}, emitter, 8);
    CHECK(r.kept.size() > 90);
    const glm::dvec3 n_y = glm::normalize(glm::cross(emitter.v1 - emitter.v0, emitter.v2 - emitter.v0));
    REQUIRE(n_y.z < 0.0);
    const double area = 0.5 * glm::length(glm::cross(emitter.v1 - emitter.v0, emitter.v2 - emitter.v0));
    double sum_got = 0.0, sum_expected = 0.0;
    for (size_t i = 0; i < r.kept.size(); ++i) {
        const uint32_t t = r.kept[i];
        const FlcCandidate& c = r.candidates[t];
        const glm::dvec3 x = to_d(c.position);
        // The integrand G = cos_x cos_y / d^2 x area over a 64 x 64 grid of the emitter.
        const int m = 64;
        double lo = 1e300, hi = 0.0, mean = 0.0;
        int samples = 0;
        for (int a = 0; a < m; ++a) {
            for (int b = 0; a + b < m; ++b) {
                const double u = (a + 1.0 / 3.0) / m, v = (b + 1.0 / 3.0) / m;
                const glm::dvec3 y = emitter.v0 + u * (emitter.v1 - emitter.v0) + v * (emitter.v2 - emitter.v0);
                const glm::dvec3 to = y - x;
                const double d2 = glm::dot(to, to);
                const glm::dvec3 wi = to / std::sqrt(d2);
                const double g = std::max(wi.z, 0.0) * std::max(-glm::dot(n_y, wi), 0.0) / d2 * area;
                lo = std::min(lo, g);
                hi = std::max(hi, g);
                mean += g;
                ++samples;
            }
        }
        mean /= samples;
        const glm::dvec3 got = to_d(r.vpls[i].flux) / level_area(c.level) / glm::dvec3(r.albedo[t]);
        for (int ch = 0; ch < 3; ++ch) {
            const double g_got = got[ch] / emitter.radiance[ch];
            CHECK(g_got >= lo * (1.0 - 5e-3));
            CHECK(g_got <= hi * (1.0 + 5e-3));
        }
        sum_got += got[0] / emitter.radiance[0];
        sum_expected += mean;
    }
    MESSAGE("emitter: mean of 8 samples over the quadrature's, summed over " << r.kept.size()
                                                                             << " VPLs: " << sum_got / sum_expected);
    CHECK(sum_got == doctest::Approx(sum_expected).epsilon(0.02));
}

TEST_CASE("flc vpl light: bad input is refused by name") {
    vplkit::Context& ctx = vplkit::test::context();
    auto create = [&](VkDeviceSize bytes) {
        return vplkit::Buffer::create(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device,
                                      "flc bad input");
    };
    auto small = create(16);
    auto big = create(4096);
    const auto bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(square(1.0)));
    const auto lights = vplkit::upload_lights(ctx, {});
    vplkit::PassList passes("flc bad input");
    const vplkit::stages::EmitterBuffers emitters{small, 0};
    CHECK_THROWS_WITH_AS(vplkit::stages::add_flc_vpl_light_pass(ctx, passes, bvh, lights, emitters,
                                                                {big, big, big, big, big}, partition(), 4, {0, 0}),
                         doctest::Contains("emitter samples"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::stages::add_flc_vpl_light_pass(ctx, passes, bvh, lights, emitters,
                                                                {big, big, big, small, big}, partition(), 4, {4, 0}),
                         doctest::Contains("'triangle albedo'"), vplkit::Error);
    // vertex_random with fewer entries than vertices (a hand-built scene that left it empty).
    CHECK_THROWS_WITH_AS(
        vplkit::stages::add_flc_candidates_pass(ctx, passes, {big, big, small, big}, partition(), 4, 0),
        doctest::Contains("vertex_random holds 4 entries for 56 vertices"), vplkit::Error);
}
