// The VPL tracing tests' harness (vpl_tracing_setup.hpp).
#include "vpl_tracing_setup.hpp"

#include "vplkit/bvh.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <cmath>

namespace vplkit::vpl_tracing_test {

uint32_t add_material(Scene& scene, glm::vec3 rho, float metallic) {
    vplkit::scene::Material m;
    m.base_color_factor = glm::vec4(rho, 1.0f);
    m.metallic_factor = metallic;
    scene.materials.push_back(m);
    return uint32_t(scene.materials.size() - 1);
}

void add_triangle(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material) {
    for (glm::vec3 p : {a, b, c}) {
        vplkit::scene::Vertex v;
        v.position = p;
        v.normal = glm::normalize(glm::cross(b - a, c - a));
        scene.indices.push_back(uint32_t(scene.vertices.size()));
        scene.vertices.push_back(v);
    }
    scene.triangle_materials.push_back(material);
    if (scene.materials[material].emits())
        scene.emissive_triangles.push_back(uint32_t(scene.triangle_materials.size() - 1));
}

void add_quad(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t material) {
    add_triangle(scene, a, b, c, material);
    add_triangle(scene, a, c, d, material);
}

void add_box(Scene& scene, glm::vec3 lo, glm::vec3 hi, uint32_t material) {
    const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                            {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    add_quad(scene, c[0], c[1], c[2], c[3], material);
    add_quad(scene, c[4], c[5], c[6], c[7], material);
    add_quad(scene, c[0], c[1], c[5], c[4], material);
    add_quad(scene, c[3], c[2], c[6], c[7], material);
    add_quad(scene, c[0], c[3], c[7], c[4], material);
    add_quad(scene, c[1], c[2], c[6], c[5], material);
}

vplkit::scene::Light point_light(glm::vec3 position, glm::vec3 color, float intensity) {
    vplkit::scene::Light l;
    l.type = vplkit::scene::LightType::point;
    l.position = position;
    l.color = color;
    l.intensity = intensity;
    return l;
}

Tracer::Tracer(const Scene& scene)
    : bvh_(vplkit::upload_bvh(vplkit::test::context(), vplkit::build_bvh(vplkit::scene::triangle_positions(scene)))),
      sources_(vplkit::upload_vpl_sources(vplkit::test::context(), scene)) {}

Traced Tracer::run(const VplTracingOptions& options) {
    vplkit::Context& ctx = vplkit::test::context();
    auto output = vplkit::VplTracingOutput::create(ctx, options);
    vplkit::PassList passes("vpl tracing test");
    vplkit::stages::add_trace_vpls_passes(ctx, passes, bvh_, sources_, options, output);
    passes.run(ctx);
    const auto counts = vplkit::download_vpl_counts(output);
    // Short paths stay far below lavapipe's loop limit: none may be reported cut.
    REQUIRE(counts.cut_short == 0);
    const uint32_t count = vplkit::download_vpl_count(output);
    REQUIRE(count == counts.vpls);
    REQUIRE(count <= output.capacity);
    Traced t;
    if (count > 0) {
        t.vpls = output.vpls.download<vplkit::shaders::Vpl>(count);
        t.bounces = output.bounces.download<uint32_t>(count);
    }
    return t;
}

std::vector<Rgb> flux_per_bounce(const Traced& t, uint32_t max_bounces) {
    std::vector<Rgb> sums(max_bounces + 1, Rgb{0, 0, 0});
    for (size_t i = 0; i < t.vpls.size(); ++i) {
        REQUIRE(t.bounces[i] >= 1);
        REQUIRE(t.bounces[i] <= max_bounces);
        sums[t.bounces[i]][0] += t.vpls[i].flux.x;
        sums[t.bounces[i]][1] += t.vpls[i].flux.y;
        sums[t.bounces[i]][2] += t.vpls[i].flux.z;
    }
    return sums;
}

void check_mean_flux(Tracer& tracer, VplTracingOptions options, uint32_t seeds, const std::vector<Rgb>& expected) {
    std::vector<std::vector<Rgb>> runs;
    for (uint32_t s = 0; s < seeds; ++s) {
        options.seed = 1000 + 17 * s;
        runs.push_back(flux_per_bounce(tracer.run(options), options.max_bounces));
    }
    for (uint32_t k = 1; k <= options.max_bounces; ++k) {
        for (int c = 0; c < 3; ++c) {
            double mean = 0.0;
            for (const auto& r : runs) mean += r[k][c];
            mean /= seeds;
            double var = 0.0;
            for (const auto& r : runs) var += (r[k][c] - mean) * (r[k][c] - mean);
            const double sigma = std::sqrt(var / (seeds - 1));
            const double bound = 4.0 * sigma / std::sqrt(double(seeds)) + 2e-4 * expected[k][c];
            CAPTURE(k);
            CAPTURE(c);
            CAPTURE(mean);
            CAPTURE(expected[k][c]);
            CAPTURE(sigma);
            CHECK(std::abs(mean - expected[k][c]) <= bound);
        }
    }
}

bool finite(const vplkit::shaders::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::dvec3 to_d(const vplkit::shaders::vec3& v) {
    return {v.x, v.y, v.z};
}

}  // namespace vplkit::vpl_tracing_test
