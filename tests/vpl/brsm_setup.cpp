// The BRSM tests' harness (brsm_setup.hpp).
#include "brsm_setup.hpp"

#include <doctest/doctest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <array>
#include <cmath>
#include <string>

namespace vplkit::brsm_test {

namespace {

constexpr std::array<glm::vec2, 4> kUv = {glm::vec2(0, 0), glm::vec2(0, 1), glm::vec2(1, 1), glm::vec2(1, 0)};

uint32_t add_material(Scene& s, glm::vec3 albedo, float metallic = 0.0f) {
    vplkit::scene::Material m;
    m.name = "material " + std::to_string(s.materials.size());
    m.base_color_factor = glm::vec4(albedo, 1.0f);
    m.metallic_factor = metallic;
    s.materials.push_back(m);
    return uint32_t(s.materials.size() - 1);
}

void finish(Scene& s) {
    s.bounds.min = glm::vec3(INFINITY);
    s.bounds.max = glm::vec3(-INFINITY);
    for (const auto& v : s.vertices) {
        s.bounds.min = glm::min(s.bounds.min, v.position);
        s.bounds.max = glm::max(s.bounds.max, v.position);
    }
}

glm::dvec3 total_flux(const std::vector<vplkit::shaders::Vpl>& vpls, size_t first, size_t count) {
    glm::dvec3 sum(0.0);
    for (size_t i = first; i < first + count; ++i) sum += glm::dvec3(vpls[i].flux.x, vpls[i].flux.y, vpls[i].flux.z);
    return sum;
}

}  // namespace

// The box [-1, 1] x [0, 2] x [-1, 1] without its front (z = 1) face, every face turned inwards,
// coordinates times `scale`; the left wall reddish, the right one greenish, a grey metal-free rest
// (the ceiling half metallic, so (1 - metallic) enters the contribution).
Scene open_box(float scale) {
    Scene s;
    s.source = "brsm test open box";
    const uint32_t grey = add_material(s, {0.7f, 0.7f, 0.7f});
    const uint32_t red = add_material(s, {0.8f, 0.2f, 0.15f});
    const uint32_t green = add_material(s, {0.2f, 0.7f, 0.25f});
    const uint32_t ceiling = add_material(s, {0.6f, 0.6f, 0.6f}, 0.5f);
    auto P = [scale](float x, float y, float z) { return glm::vec3(x, y, z) * scale; };
    raster_test::add_quad(s, {P(-1, 0, -1), P(-1, 0, 1), P(1, 0, 1), P(1, 0, -1)}, kUv, grey);     // floor, up
    raster_test::add_quad(s, {P(-1, 2, -1), P(1, 2, -1), P(1, 2, 1), P(-1, 2, 1)}, kUv, ceiling);  // down
    raster_test::add_quad(s, {P(-1, 0, -1), P(1, 0, -1), P(1, 2, -1), P(-1, 2, -1)}, kUv, grey);   // back, +z
    raster_test::add_quad(s, {P(-1, 0, -1), P(-1, 2, -1), P(-1, 2, 1), P(-1, 0, 1)}, kUv, red);    // left, +x
    raster_test::add_quad(s, {P(1, 0, -1), P(1, 0, 1), P(1, 2, 1), P(1, 2, -1)}, kUv, green);      // right, -x
    finish(s);
    return s;
}

Light point_light(glm::vec3 position, float intensity) {
    Light l;
    l.type = LightType::point;
    l.name = "point";
    l.position = position;
    l.intensity = intensity;
    l.color = {1.0f, 0.9f, 0.8f};
    return l;
}

Light spot_light(glm::vec3 position, glm::vec3 direction, float intensity) {
    Light l;
    l.type = LightType::spot;
    l.name = "spot";
    l.position = position;
    l.direction = glm::normalize(direction);
    l.intensity = intensity;
    l.color = {0.7f, 0.8f, 1.0f};
    l.inner_cone_angle = 0.3f;
    l.outer_cone_angle = 0.6f;
    return l;
}

Light sun(glm::vec3 direction, float intensity) {
    Light l;
    l.type = LightType::directional;
    l.name = "sun";
    l.direction = glm::normalize(direction);
    l.intensity = intensity;
    return l;
}

vplkit::scene::Camera camera(glm::vec3 eye, glm::vec3 target, glm::vec3 up, float scale) {
    auto c = vplkit::scene::look_at(eye * scale, target * scale, up, 0.9f);
    c.znear = 0.01f * scale;
    c.zfar = 100.0f * scale;
    return c;
}

vplkit::scene::Camera box_camera(float scale) {
    return camera({0.3f, 1.1f, 3.2f}, {0.0f, 0.9f, 0.0f}, {0.0f, 1.0f, 0.0f}, scale);
}

Scene box_with(std::vector<Light> lights, float scale) {
    Scene s = open_box(scale);
    for (Light& l : lights) {
        l.position *= scale;
        s.lights.push_back(l);
    }
    return s;
}

std::vector<float> level0(const vplkit::Buffer& mips, uint32_t size) {
    return mips.download<float>(size_t(size) * size);
}

// mean over seeds of the total flux of each light's VPLs against `expected`, per channel.
void check_mean_flux(Setup& setup, BrsmOptions options, uint32_t seeds, const std::vector<glm::dvec3>& expected) {
    std::vector<std::vector<glm::dvec3>> totals(expected.size());
    for (uint32_t seed = 0; seed < seeds; ++seed) {
        options.seed = seed;
        const BrsmOutput out = setup.run(options);
        const auto vpls = setup.vpls(out);
        const auto counts = vplkit::download_brsm_light_vpl_counts(out);
        size_t first = 0;
        for (size_t l = 0; l < expected.size(); ++l) {
            totals[l].push_back(total_flux(vpls, first, counts[l]));
            first += counts[l];
        }
        REQUIRE(first == vpls.size());
    }
    for (size_t l = 0; l < expected.size(); ++l) {
        for (int c = 0; c < 3; ++c) {
            double mean = 0, var = 0;
            for (const auto& t : totals[l]) mean += t[c];
            mean /= seeds;
            for (const auto& t : totals[l]) var += (t[c] - mean) * (t[c] - mean);
            const double sigma = std::sqrt(var / (seeds - 1));
            const double bound = 4.0 * sigma / std::sqrt(double(seeds)) + 1e-4 * expected[l][c];
            CAPTURE(l);
            CAPTURE(c);
            CAPTURE(mean);
            CAPTURE(expected[l][c]);
            CAPTURE(sigma);
            CHECK(std::abs(mean - expected[l][c]) <= bound);
        }
    }
}

BrsmOptions small_options(uint32_t vpls) {
    BrsmOptions o;
    o.vpl_count = vpls;
    return o;
}

}  // namespace vplkit::brsm_test
