// Closest-hit and occlusion queries (shaders/bvh/trace_*.comp over vplkit/bvh.glsl) on lavapipe
// against the brute-force double-precision reference; tolerances in bvh_test_support.hpp.

#include "bvh_test_support.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

using vplkit::kBvhNoHit;
using vplkit::bvh_test::make_ray;
using vplkit::bvh_test::Triangles;
using vplkit::shaders::BvhHit;
using vplkit::shaders::BvhRay;

// Rays from random points in a box of half-size `spread` around `centre` towards random
// directions, with tmax random in (0, 6 * spread) so that occlusion has both answers (and a
// quarter of the rays unbounded: +infinity or the largest float).
std::vector<BvhRay> random_rays(uint32_t count, uint32_t seed, glm::vec3 centre, float spread) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_real_distribution<float> fraction(0.0f, 1.0f);
    std::vector<BvhRay> rays;
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 origin = centre + spread * glm::vec3(unit(rng), unit(rng), unit(rng));
        // Lengths other than 1: t is in units of the direction.
        const glm::vec3 direction = vplkit::bvh_test::random_direction(rng) * (0.5f + 2.0f * fraction(rng));
        const float tmax = (i % 8 == 0) ? INFINITY : (i % 8 == 4) ? 3.4e38f : 6.0f * spread * fraction(rng);
        rays.push_back(make_ray(origin, direction, (i % 8 == 1) ? 0.1f * spread : 0.0f, tmax));
    }
    return rays;
}

std::vector<BvhHit> trace_scene(const Triangles& triangles, const std::vector<BvhRay>& rays) {
    const auto bvh = vplkit::build_bvh(triangles);
    const auto gpu = vplkit::upload_bvh(vplkit::test::context(), bvh);
    return vplkit::bvh_test::trace_closest(gpu, rays);
}

}  // namespace

TEST_CASE("bvh trace: random rays against a random triangle soup match the reference") {
    const Triangles soup = vplkit::bvh_test::random_soup(1500, 11);
    const auto rays = random_rays(3000, 12, {0, 0, 0}, 1.5f);
    const auto result = vplkit::bvh_test::check_against_reference(soup, rays);
    CHECK(result.hits > 500);  // the rays do meet the soup (tmax cuts some short)
}

TEST_CASE("bvh trace: random rays against a closed mesh match the reference") {
    const Triangles sphere = vplkit::bvh_test::icosphere(4);  // 5120 triangles
    const auto rays = random_rays(3000, 13, {0, 0, 0}, 1.2f);
    const auto result = vplkit::bvh_test::check_against_reference(sphere, rays);
    CHECK(result.hits > 1000);
}

TEST_CASE("bvh trace: scenes at 1e-3 and 1e4 scale match the reference") {
    const Triangles soup = vplkit::bvh_test::random_soup(800, 14);
    struct Case {
        float scale;
        glm::vec3 offset;
    };
    for (const Case& c : {Case{1e-3f, {0, 0, 0}}, Case{1e4f, {0, 0, 0}}, Case{1e-3f, {0.01f, -0.02f, 0.005f}},
                          Case{1.0f, {1e4f, -1e4f, 3e3f}}}) {
        CAPTURE(c.scale);
        CAPTURE(c.offset.x);
        const Triangles scene = vplkit::bvh_test::transformed(soup, c.scale, c.offset);
        auto rays = random_rays(1500, 15, {0, 0, 0}, 1.5f);
        for (auto& ray : rays) {
            ray.origin = {ray.origin.x * c.scale + c.offset.x, ray.origin.y * c.scale + c.offset.y,
                          ray.origin.z * c.scale + c.offset.z};
            ray.direction = {ray.direction.x * c.scale, ray.direction.y * c.scale, ray.direction.z * c.scale};
        }
        vplkit::bvh_test::check_against_reference(scene, rays);
    }
}

TEST_CASE("bvh trace: a depth-capped tree answers like the reference") {
    const Triangles soup = vplkit::bvh_test::random_soup(2000, 16);
    vplkit::BvhBuildOptions options;
    options.max_depth = 9;  // 4 * 2^9 = 2048: nearly a perfect median tree
    const auto rays = random_rays(2000, 17, {0, 0, 0}, 1.5f);
    vplkit::bvh_test::check_against_reference(soup, rays, 0.01, options);
}

TEST_CASE("bvh trace: the empty scene misses every ray") {
    std::mt19937 rng(18);
    std::vector<BvhRay> rays;
    for (int i = 0; i < 256; ++i) {
        // Some through the world origin, where the empty root box sits.
        const glm::vec3 d = vplkit::bvh_test::random_direction(rng);
        rays.push_back(make_ray(i % 2 ? -d : glm::vec3(0.0f), d, 0.0f, i % 4 < 2 ? 3.4e38f : INFINITY));
    }
    const glm::vec3 p(1, 1, 1);
    for (const Triangles& scene : {Triangles{}, Triangles{p, p, p, {0, 0, 0}, {1, 1, 1}, {2, 2, 2}}}) {
        const auto bvh = vplkit::build_bvh(scene);
        const auto gpu = vplkit::upload_bvh(vplkit::test::context(), bvh);
        CHECK(gpu.triangles.size() >= sizeof(vplkit::shaders::BvhTriangle));
        const auto hits = vplkit::bvh_test::trace_closest(gpu, rays);
        const auto occlusion = vplkit::bvh_test::trace_occlusion(gpu, rays);
        for (size_t i = 0; i < rays.size(); ++i) {
            CHECK(hits[i].id == kBvhNoHit);
            CHECK(hits[i].triangle == kBvhNoHit);
            // +infinity comes back as the largest float (kBvhMaxT in bvh.glsl).
            CHECK(hits[i].t == (std::isinf(rays[i].tmax) ? std::numeric_limits<float>::max() : rays[i].tmax));
            CHECK(occlusion[i] == 0);
        }
    }
}

TEST_CASE("bvh trace: one triangle - hits inside with exact barycentrics and misses outside") {
    const Triangles one = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
    std::mt19937 rng(19);
    std::uniform_real_distribution<float> unit(-1.0f, 5.0f);
    std::vector<BvhRay> rays;
    for (int i = 0; i < 1000; ++i) {
        const glm::vec3 target(unit(rng), unit(rng), 0.0f);
        // From above and below (both windings must hit: no culling).
        const glm::vec3 origin = target + glm::vec3(0.3f * unit(rng), 0.3f * unit(rng), i % 2 ? 2.0f : -2.0f);
        rays.push_back(make_ray(origin, target - origin, 0.0f, 10.0f));
    }
    vplkit::bvh_test::check_against_reference(one, rays);

    // Rays straight down (direction (0, 0, -1): two zero components) at exact points.
    std::vector<BvhRay> down;
    for (float x : {0.5f, 1.0f, 2.0f, 3.0f}) {
        down.push_back(make_ray({x, 0.5f, 3.0f}, {0, 0, -1}, 0.0f, 10.0f));
    }
    const auto hits = trace_scene(one, down);
    for (size_t i = 0; i < down.size(); ++i) {
        CHECK(hits[i].id == 0);
        CHECK(hits[i].t == 3.0f);
        CHECK(hits[i].barycentrics.x == doctest::Approx(down[i].origin.x / 4.0f).epsilon(1e-6));
        CHECK(hits[i].barycentrics.y == doctest::Approx(0.125f).epsilon(1e-6));
    }
}

TEST_CASE("bvh trace: axis-aligned rays inside a box hit its walls at the exact distance") {
    const Triangles box = vplkit::bvh_test::grid_box(8);
    const auto bvh = vplkit::build_bvh(box);
    const auto gpu = vplkit::upload_bvh(vplkit::test::context(), bvh);
    std::vector<BvhRay> rays;
    std::vector<float> expected;
    // Origins on a grid of exact floats, including points on the grid lines of the walls'
    // triangulation, so rays also pass exactly through edges and vertices. -0.0 components too.
    for (int i = -3; i <= 3; ++i) {
        for (int j = -3; j <= 3; ++j) {
            for (int k = -3; k <= 3; k += 2) {
                const glm::vec3 o(0.25f * float(i), 0.25f * float(j), 0.25f * float(k));
                for (int axis = 0; axis < 3; ++axis) {
                    for (float sign : {-1.0f, 1.0f}) {
                        glm::vec3 d(0.0f);
                        d[(axis + 1) % 3] = -0.0f;
                        d[axis] = sign;
                        rays.push_back(make_ray(o, d, 0.0f, 100.0f));
                        expected.push_back(1.0f - sign * o[axis]);
                    }
                }
            }
        }
    }
    const auto hits = vplkit::bvh_test::trace_closest(gpu, rays);
    const auto occlusion = vplkit::bvh_test::trace_occlusion(gpu, rays);
    size_t misses = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        misses += hits[i].id == kBvhNoHit ? 1 : 0;
        CHECK(hits[i].t == expected[i]);  // exact: every quantity is a small dyadic number
        CHECK(occlusion[i] == 1);
    }
    CHECK(misses == 0);
}

TEST_CASE("bvh trace: an axis-parallel ray lying in a box face still finds what the box holds") {
    // A floor at y = 0 (x, z in [0, 8]) and walls standing on it or hanging from it, so that BVH
    // boxes have faces exactly at y = 0; rays travel along +-x and +-z exactly in y = 0 (their
    // y component is 0 and their origin lies in the boxes' face planes). Each ray meets a wall
    // through the wall's bottom or top edge: watertight traversal must report the wall (the
    // floor lies in the ray's plane and cannot be hit).
    Triangles scene;
    auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
        scene.insert(scene.end(), {a, b, c, a, c, d});
    };
    for (int i = 0; i < 8; ++i) {
        for (int j = 0; j < 8; ++j) {
            const float x = float(i), z = float(j);
            quad({x, 0, z}, {x, 0, z + 1}, {x + 1, 0, z + 1}, {x + 1, 0, z});
        }
    }
    quad({10, 0, 0}, {10, 2, 0}, {10, 2, 8}, {10, 0, 8});    // wall at x = 10, standing on y = 0
    quad({-2, -2, 0}, {-2, 0, 0}, {-2, 0, 8}, {-2, -2, 8});  // wall at x = -2, hanging below y = 0
    quad({0, 0, 10}, {0, 2, 10}, {8, 2, 10}, {8, 0, 10});    // wall at z = 10, standing
    quad({0, -2, -2}, {0, 0, -2}, {8, 0, -2}, {8, -2, -2});  // wall at z = -2, hanging
    const auto bvh = vplkit::build_bvh(scene);
    const auto gpu = vplkit::upload_bvh(vplkit::test::context(), bvh);

    std::vector<BvhRay> rays;
    std::vector<float> expected_t;
    for (int i = 0; i < 16; ++i) {
        const float u = 0.5f * float(i) + 0.25f;  // 0.25 .. 7.75, off the floor's grid lines
        const float v = 0.5f * float(i % 8);      // on grid lines too
        rays.push_back(make_ray({v, 0, u}, {1, 0, 0}, 0.0f, 100.0f));
        expected_t.push_back(10.0f - v);
        rays.push_back(make_ray({v, 0, u}, {-1, -0.0f, 0}, 0.0f, 100.0f));
        expected_t.push_back(v + 2.0f);
        rays.push_back(make_ray({u, 0, v}, {0, 0, 1}, 0.0f, 100.0f));
        expected_t.push_back(10.0f - v);
        rays.push_back(make_ray({u, -0.0f, v}, {0, 0, -1}, 0.0f, 100.0f));
        expected_t.push_back(v + 2.0f);
    }
    const auto hits = vplkit::bvh_test::trace_closest(gpu, rays);
    const auto occlusion = vplkit::bvh_test::trace_occlusion(gpu, rays);
    for (size_t i = 0; i < rays.size(); ++i) {
        CAPTURE(i);
        CHECK(hits[i].id != kBvhNoHit);
        CHECK(hits[i].id >= 128);  // a wall, not the floor
        CHECK(hits[i].t == expected_t[i]);
        CHECK(occlusion[i] == 1);
    }
}

TEST_CASE("bvh trace: rays in the plane of a triangle give a finite answer on the triangle or a miss") {
    const Triangles one = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
    std::mt19937 rng(20);
    std::vector<BvhRay> rays;
    std::uniform_real_distribution<float> unit(-2.0f, 6.0f);
    for (int i = 0; i < 500; ++i) {
        const glm::vec3 origin(unit(rng), unit(rng), 0.0f);
        glm::vec3 d = vplkit::bvh_test::random_direction(rng);
        d.z = 0.0f;
        rays.push_back(make_ray(origin, d, 0.0f, 100.0f));
    }
    // Along the triangle's edges, and through its vertices, in its plane.
    rays.push_back(make_ray({-1, 0, 0}, {1, 0, 0}, 0.0f, 100.0f));
    rays.push_back(make_ray({0, -1, 0}, {0, 1, 0}, 0.0f, 100.0f));
    rays.push_back(make_ray({5, -1, 0}, {-1, 1, 0}, 0.0f, 100.0f));
    const auto bvh = vplkit::build_bvh(one);
    const auto gpu = vplkit::upload_bvh(vplkit::test::context(), bvh);
    const auto hits = vplkit::bvh_test::trace_closest(gpu, rays);
    const auto occlusion = vplkit::bvh_test::trace_occlusion(gpu, rays);
    size_t hit_count = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const BvhHit& h = hits[i];
        CHECK(std::isfinite(h.t));
        CHECK(occlusion[i] == (h.id != kBvhNoHit ? 1u : 0u));
        if (h.id == kBvhNoHit) {
            continue;
        }
        ++hit_count;
        // A hit must be a point of the triangle (within float rounding of its 4-unit size).
        const glm::vec3 o(rays[i].origin.x, rays[i].origin.y, rays[i].origin.z);
        const glm::vec3 d(rays[i].direction.x, rays[i].direction.y, rays[i].direction.z);
        const glm::vec3 p = o + h.t * d;
        CHECK(std::isfinite(h.barycentrics.x));
        CHECK(std::isfinite(h.barycentrics.y));
        CHECK(p.x >= -1e-4f);
        CHECK(p.y >= -1e-4f);
        CHECK(p.x + p.y <= 4.0f + 1e-4f);
    }
    MESSAGE(hit_count << " of " << rays.size() << " in-plane rays reported a hit");
}

TEST_CASE("bvh trace: invalid rays miss and tmax = +infinity is unbounded") {
    const Triangles one = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<BvhRay> rays = {
        make_ray({0, 0, 1}, {0, 0, 0}, 0.0f, 10.0f),        // no direction
        make_ray({0, 0, 1}, {0, 0, -1e-25f}, 0.0f, 10.0f),  // below kBvhMinDirection
        make_ray({0, 0, 1}, {0, 0, -1}, 2.0f, 2.0f),        // tmin >= tmax
        make_ray({0, 0, 1}, {0, 0, -1}, 3.0f, 2.0f),       make_ray({nan, 0, 1}, {0, 0, -1}, 0.0f, 10.0f),
        make_ray({0, 0, 1}, {0, nan, -1}, 0.0f, 10.0f),    make_ray({0, 0, 1}, {0, 0, -1}, 0.0f, -inf),
        make_ray({0, 0, 1}, {0, 0, -1}, -inf, 10.0f),      make_ray({0, 0, 1}, {0, 0, -1}, 0.0f, nan),
        make_ray({0, 0, 1}, {0, 0, -1}, nan, 10.0f),
    };
    rays.push_back(make_ray({0, 0, 1}, {0, 0, -1}, 0.0f, inf));    // +inf: unbounded, valid
    rays.push_back(make_ray({0, 0, 1}, {0, 0, -1}, 0.0f, 10.0f));  // a valid one, for contrast
    const auto bvh = vplkit::build_bvh(one);
    const auto gpu = vplkit::upload_bvh(vplkit::test::context(), bvh);
    const auto hits = vplkit::bvh_test::trace_closest(gpu, rays);
    const auto occlusion = vplkit::bvh_test::trace_occlusion(gpu, rays);
    for (size_t i = 0; i + 2 < rays.size(); ++i) {
        CAPTURE(i);
        CHECK(hits[i].id == kBvhNoHit);
        CHECK(occlusion[i] == 0);
    }
    const size_t unbounded = rays.size() - 2;
    CHECK(hits[unbounded].id == 0);
    CHECK(hits[unbounded].t == 1.0f);
    CHECK(occlusion[unbounded] == 1);
    CHECK(hits.back().id == 0);
    CHECK(hits.back().t == 1.0f);
    CHECK(occlusion.back() == 1);
}

TEST_CASE("bvh trace: degenerate triangles mixed into a scene are never hit") {
    Triangles scene = vplkit::bvh_test::random_soup(300, 21);
    // Degenerate triangles right where the rays go: they must change nothing.
    std::mt19937 rng(22);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (int i = 0; i < 100; ++i) {
        const glm::vec3 p(unit(rng), unit(rng), unit(rng)), q(unit(rng), unit(rng), unit(rng));
        if (i % 2) {
            scene.insert(scene.end(), {p, p, q});  // two coincident vertices
        } else {
            // Three points on a line parallel to the x axis: exactly collinear in float.
            scene.insert(scene.end(), {p, {q.x, p.y, p.z}, {0.5f * (p.x + q.x), p.y, p.z}});
        }
    }
    CHECK(vplkit::build_bvh(scene).degenerate_triangles == 100);
    const auto rays = random_rays(1500, 23, {0, 0, 0}, 1.5f);
    vplkit::bvh_test::check_against_reference(scene, rays);
}
