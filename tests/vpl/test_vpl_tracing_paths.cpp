// trace_vpls.comp's VPLs one by one (the energy checks are test_vpl_tracing.cpp's): every VPL
// finite and on a surface with a unit normal facing the arriving light (a CPU point-to-triangle
// distance in double, within 1e-5 of the scene's size: a hit point from barycentrics is off by a
// few ulps), the same seed giving the same VPLs bit for bit, and the VPLs packed by path then
// bounce, in the order of a CPU trace of the same random numbers.
#include "vplkit/scene.hpp"
#include "vplkit/shaders/types.hpp"
#include "brsm_reference.hpp"
#include "geometry_reference.hpp"
#include "vpl_tracing_setup.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

using namespace vplkit::vpl_tracing_test;

TEST_CASE("vpl tracing: every VPL is finite and on a surface with a unit normal facing the light") {
    Scene scene;
    add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(0.7f, 0.6f, 0.5f)));
    scene.lights.push_back(point_light({-0.4f, 0.2f, 0.1f}, {1.0f, 1.0f, 1.0f}, 2.0f));
    Tracer tracer(scene);
    const Traced t = tracer.run({3000, 5, 7});
    REQUIRE(t.vpls.size() >= 3000);
    const auto positions = vplkit::scene::triangle_positions(scene);
    const glm::dvec3 center = (glm::dvec3(kBoxLo) + glm::dvec3(kBoxHi)) * 0.5;
    int failures = 0;
    for (size_t i = 0; i < t.vpls.size() && failures < 5; ++i) {
        const auto& v = t.vpls[i];
        CAPTURE(i);
        bool ok = finite(v.position) && finite(v.normal) && finite(v.flux);
        const glm::dvec3 p = to_d(v.position), n = to_d(v.normal);
        ok = ok && std::abs(glm::length(n) - 1.0) < 1e-5;
        ok = ok && v.flux.x > 0 && v.flux.y > 0 && v.flux.z > 0;
        double nearest = 1e30;
        glm::dvec3 face{0.0};
        for (size_t k = 0; k < positions.size(); k += 3) {
            const glm::dvec3 a(positions[k]), b(positions[k + 1]), c(positions[k + 2]);
            const double d = vplkit::reference::point_triangle_distance(p, a, b, c);
            if (d < nearest) {
                nearest = d;
                face = glm::normalize(glm::cross(b - a, c - a));
            }
        }
        CAPTURE(nearest);
        ok = ok && nearest <= 1e-5;
        // The face normal, turned to the inside of the box (where all the light comes from).
        ok = ok && std::abs(std::abs(glm::dot(n, face)) - 1.0) < 1e-5 && glm::dot(n, center - p) > 0.0;
        if (!ok) ++failures;
        CHECK(ok);
    }
}

TEST_CASE("vpl tracing: the same seed gives the same VPLs and another seed other ones") {
    Scene scene;
    add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(0.5f)));
    scene.lights.push_back(point_light({0.1f, 0.2f, 0.0f}, {1.0f, 1.0f, 1.0f}, 1.0f));
    Tracer tracer(scene);
    // The members (not the padding, which nothing writes), in buffer order.
    auto in_order = [](const Traced& t) {
        std::vector<std::tuple<uint32_t, float, float, float, float, float, float, float, float, float>> v;
        for (size_t i = 0; i < t.vpls.size(); ++i) {
            const auto& x = t.vpls[i];
            v.emplace_back(t.bounces[i], x.position.x, x.position.y, x.position.z, x.normal.x, x.normal.y, x.normal.z,
                           x.flux.x, x.flux.y, x.flux.z);
        }
        return v;
    };
    auto sorted = [&](const Traced& t) {
        auto v = in_order(t);
        std::sort(v.begin(), v.end());
        return v;
    };
    const Traced first = tracer.run({2000, 3, 42});
    const Traced again = tracer.run({2000, 3, 42});
    // The same VPLs in the same order, bit for bit (the order is fixed by the seed: see the next case).
    CHECK(in_order(first) == in_order(again));
    const auto a = sorted(first);
    const auto c = sorted(tracer.run({2000, 3, 43}));
    REQUIRE(!a.empty());
    CHECK(a != c);
    // Not merely a reordering: the first-bounce positions differ.
    size_t same = 0;
    for (const auto& x : c) same += std::binary_search(a.begin(), a.end(), x) ? 1 : 0;
    CHECK(same < c.size() / 100);
}

namespace {

// Where path `path` of trace_vpls.comp, from the only emitter, a point light at `light` inside the
// box [lo, hi], first meets the box: the shader's random numbers (PCG32 stream `path` under
// `seed`: the emitter's number, then u.x, u.y of sample_uniform_sphere), the ray in double.
struct BoxHit {
    glm::dvec3 position{0.0};
    glm::dvec3 normal{0.0};      // the face's, facing the light (the inside)
    double edge_distance = 0.0;  // to the nearest edge of the face
};
BoxHit first_box_hit(vplkit::reference::Pcg32& rng, glm::dvec3 light, glm::dvec3 lo, glm::dvec3 hi) {
    rng.next_float();  // which emitter: there is one
    const double ux = rng.next_float(), uy = rng.next_float();
    const double z = 1.0 - 2.0 * ux, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * kPi * uy;
    const glm::dvec3 d(r * std::cos(phi), r * std::sin(phi), z);
    int axis = -1;
    double t = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) continue;
        const double ta = ((d[a] > 0.0 ? hi[a] : lo[a]) - light[a]) / d[a];
        if (ta < t) t = ta, axis = a;
    }
    BoxHit h;
    h.position = light + t * d;
    h.normal[axis] = d[axis] > 0.0 ? -1.0 : 1.0;
    h.edge_distance = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (a == axis) continue;
        h.edge_distance = std::min({h.edge_distance, h.position[a] - lo[a], hi[a] - h.position[a]});
    }
    return h;
}

}  // namespace

// Before the VPLs were packed by path (trace_vpls.comp appended each at atomicAdd(count, 1)),
// this failed: the invocations of a SIMD batch appended their first hits together, then their
// second ones, and the batches landed in the order the driver's threads ran them.
TEST_CASE("vpl tracing: the VPLs come out by path then bounce, in the order of a CPU trace of the same paths") {
    const float rho = 0.7f;
    Scene scene;
    add_box(scene, kBoxLo, kBoxHi, add_material(scene, glm::vec3(rho)));
    const glm::vec3 light{0.3f, 0.1f, -0.2f};
    const float intensity = 3.0f;
    scene.lights.push_back(point_light(light, {1.0f, 1.0f, 1.0f}, intensity));
    Tracer tracer(scene);
    // 1000 paths: four blocks of the packing (256 paths each), the last one partial.
    const VplTracingOptions options{1000, 3, 77};
    const Traced t = tracer.run(options);

    // The CPU trace. In the closed box every path hits a wall first (a VPL, rho > 0); Russian
    // roulette then goes on while its number is below q = rho (grey: beta * rho / q keeps beta), up
    // to max_bounces hits. Between two roulette numbers the path draws its bounce direction (two).
    std::vector<uint32_t> bounces;
    std::vector<BoxHit> first_hits;
    for (uint32_t path = 0; path < options.paths; ++path) {
        vplkit::reference::Pcg32 rng(options.seed, path);
        first_hits.push_back(first_box_hit(rng, light, kBoxLo, kBoxHi));
        uint32_t hits = 1;
        while (hits < options.max_bounces && rng.next_float() < double(rho)) {
            rng.next_float();
            rng.next_float();
            ++hits;
        }
        for (uint32_t k = 1; k <= hits; ++k) bounces.push_back(k);
    }
    // Element by element, in order: the bounces say where each path's VPLs begin.
    REQUIRE(t.bounces == bounces);
    const double phi_per_path = 4.0 * kPi * intensity / options.paths;
    size_t path = 0, checked_normals = 0;
    for (size_t i = 0; i < t.vpls.size(); ++i) {
        CAPTURE(i);
        const auto& v = t.vpls[i];
        // Flux Phi / N rho at every bounce (roulette's beta * rho / q keeps beta in a grey box):
        // a few float products, so 1e-5 relative is a few ulps.
        const double flux = phi_per_path * double(rho);
        CHECK(v.flux.x == doctest::Approx(flux).epsilon(1e-5));
        CHECK(v.flux.z == doctest::Approx(flux).epsilon(1e-5));
        if (t.bounces[i] != 1) continue;
        const BoxHit& h = first_hits[path++];
        CAPTURE(path);
        // The float ray and BVH against the double ray: 1e-5 of the box's size (2) is generous.
        CHECK(glm::distance(to_d(v.position), h.position) <= 2e-5);
        // At an edge the shader may take either face: its normal is checked away from them.
        if (h.edge_distance > 1e-4) {
            CHECK(glm::dot(to_d(v.normal), h.normal) > 1.0 - 1e-5);
            ++checked_normals;
        }
    }
    CHECK(path == options.paths);
    CHECK(checked_normals > options.paths * 9 / 10);
}
