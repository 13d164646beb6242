// Watertightness of the traversal (vplkit/bvh.glsl: Woop, Benthin and Wald 2013, float edge
// functions with zero counted as inside): a ray through the inside of a closed mesh must hit it,
// also when it passes exactly through a shared vertex or edge, or within rounding of one. Zero
// misses are allowed; no reference tolerance applies here.

#include "bvh_test_support.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <random>
#include <set>
#include <tuple>
#include <vector>

namespace {

using vplkit::kBvhNoHit;
using vplkit::bvh_test::make_ray;
using vplkit::bvh_test::Triangles;
using vplkit::shaders::BvhRay;

// Every vertex and every edge midpoint of the mesh, once each.
std::vector<glm::vec3> vertices_and_edge_midpoints(const Triangles& mesh) {
    std::set<std::tuple<float, float, float>> seen;
    std::vector<glm::vec3> points;
    auto add = [&](glm::vec3 p) {
        if (seen.insert({p.x, p.y, p.z}).second) {
            points.push_back(p);
        }
    };
    for (size_t t = 0; t < mesh.size(); t += 3) {
        for (int k = 0; k < 3; ++k) {
            add(mesh[t + k]);
            add(0.5f * (mesh[t + k] + mesh[t + (k + 1) % 3]));
        }
    }
    return points;
}

struct Count {
    size_t rays = 0;
    size_t misses = 0;
    size_t occlusion_misses = 0;
    size_t wrong_t = 0;
};

// Traces `rays` (each should first meet the mesh at t_expected[i], within `t_tolerance`).
Count trace_all(const Triangles& mesh, const std::vector<BvhRay>& rays, const std::vector<float>& t_expected,
                double t_tolerance) {
    const auto bvh = vplkit::build_bvh(mesh);
    const auto gpu = vplkit::upload_bvh(vplkit::test::context(), bvh);
    const auto hits = vplkit::bvh_test::trace_closest(gpu, rays);
    const auto occlusion = vplkit::bvh_test::trace_occlusion(gpu, rays);
    Count count;
    count.rays = rays.size();
    for (size_t i = 0; i < rays.size(); ++i) {
        count.misses += hits[i].id == kBvhNoHit ? 1 : 0;
        count.occlusion_misses += occlusion[i] == 0 ? 1 : 0;
        if (hits[i].id != kBvhNoHit && std::fabs(double(hits[i].t) - t_expected[i]) > t_tolerance * t_expected[i]) {
            ++count.wrong_t;
            if (count.wrong_t <= 3) {
                MESSAGE("ray " << i << ": t " << hits[i].t << " expected " << t_expected[i]);
            }
        }
    }
    MESSAGE(count.rays << " rays: " << count.misses << " closest-hit misses, " << count.occlusion_misses
                       << " occlusion misses");
    return count;
}

}  // namespace

TEST_CASE("bvh watertight: rays through the vertices and edges of a grid box from inside and outside all hit") {
    // Every coordinate here is a small dyadic number, so directions are exact: each ray passes
    // exactly through its target vertex or edge point, where edge functions are exactly 0.
    const Triangles box = vplkit::bvh_test::grid_box(8);
    const auto targets = vertices_and_edge_midpoints(box);
    const std::vector<glm::vec3> inside = {
        {0, 0, 0}, {0.25f, -0.5f, 0.125f}, {-0.75f, 0.625f, 0.5f}, {0.5f, 0.5f, 0.5f}};
    std::vector<BvhRay> rays;
    std::vector<float> t_expected;
    for (const glm::vec3& target : targets) {
        for (const glm::vec3& c : inside) {
            // From inside, out through the target: first hit at t = 1.
            rays.push_back(make_ray(c, target - c, 0.0f, 4.0f));
            t_expected.push_back(1.0f);
            // From outside, in through the target towards c: first hit at t = 0.5.
            const glm::vec3 outside = 2.0f * target - c;
            rays.push_back(make_ray(outside, 2.0f * (c - target), 0.0f, 4.0f));
            t_expected.push_back(0.5f);
        }
    }
    const Count count = trace_all(box, rays, t_expected, 1e-6);
    CHECK(count.rays > 4000);
    CHECK(count.misses == 0);
    CHECK(count.occlusion_misses == 0);
    CHECK(count.wrong_t == 0);
}

TEST_CASE("bvh watertight: rays aimed at the vertices and edge midpoints of a sphere mesh all hit") {
    // Float vertices on the unit sphere: an aimed ray passes within rounding of its target, on
    // either side, the case where non-watertight tests leak.
    const Triangles sphere = vplkit::bvh_test::icosphere(3);  // 1280 triangles
    const auto targets = vertices_and_edge_midpoints(sphere);
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> radius(0.0f, 0.5f);
    std::vector<glm::vec3> inside = {{0, 0, 0}};
    for (int i = 0; i < 3; ++i) {
        inside.push_back(radius(rng) * vplkit::bvh_test::random_direction(rng));
    }
    std::vector<BvhRay> rays;
    std::vector<float> t_expected;
    for (const glm::vec3& target : targets) {
        for (const glm::vec3& c : inside) {
            rays.push_back(make_ray(c, target - c, 0.0f, 4.0f));
            t_expected.push_back(1.0f);
            const glm::vec3 outside = 2.0f * target - c;
            rays.push_back(make_ray(outside, c - outside, 0.0f, 4.0f));
            t_expected.push_back(0.5f);
        }
    }
    // The rounding of target - c moves the hit by a few ulps along the ray.
    const Count count = trace_all(sphere, rays, t_expected, 1e-5);
    CHECK(count.rays > 10000);
    CHECK(count.misses == 0);
    CHECK(count.occlusion_misses == 0);
    CHECK(count.wrong_t == 0);
}

TEST_CASE("bvh watertight: a closed mesh far from the origin and at small scale stays closed") {
    for (auto [scale, offset] : {std::pair{1e-3f, glm::vec3(0.0f)}, std::pair{1.0f, glm::vec3(1e4f, -2e3f, 5e3f)},
                                 std::pair{1e4f, glm::vec3(0.0f)}}) {
        CAPTURE(scale);
        const Triangles sphere = vplkit::bvh_test::transformed(vplkit::bvh_test::icosphere(2), scale, offset);
        const auto targets = vertices_and_edge_midpoints(sphere);
        const glm::vec3 centre = offset;
        std::vector<BvhRay> rays;
        std::vector<float> t_expected;
        for (const glm::vec3& target : targets) {
            rays.push_back(make_ray(centre, target - centre, 0.0f, 4.0f));
            t_expected.push_back(1.0f);
        }
        // Far from the origin the direction target - centre carries the rounding of 1e4-sized
        // coordinates: ulp(1e4) / 1 = 1e-3 relative to the unit radius.
        const Count count = trace_all(sphere, rays, t_expected, scale == 1.0f ? 3e-3 : 1e-5);
        CHECK(count.misses == 0);
        CHECK(count.occlusion_misses == 0);
        CHECK(count.wrong_t == 0);
    }
}
