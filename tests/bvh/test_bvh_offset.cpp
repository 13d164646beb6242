// The self-intersection policy of vplkit/bvh.glsl (offset_ray_origin, bvh_hit_position,
// bvh_scene_scale) through the test shader shaders/surface_rays.comp: rays that start on the
// scene's own surfaces never hit the surface they leave, and an occluder just beyond the offset
// (twice the offset distance away) is never missed, at scales 1e-3, 1 and 1e4 and far from the
// world origin.

#include "bvh_test_support.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/bvh_test_shaders/segment_visibility.hpp"
#include "vplkit/bvh_test_shaders/surface_rays.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace {

namespace ts = vplkit::bvh_test_shaders;
using vplkit::kBvhNoHit;
using vplkit::bvh_test::Triangles;

// Both generated namespaces have their own vec3.
template <class V>
glm::dvec3 to_dvec(const V& v) {
    return {v.x, v.y, v.z};
}

// Runs one of the test shaders (its Pipeline) once per query; its results are in the binding
// `ResultBinding`, one Result each.
template <class Pipeline, auto ResultBinding, class Result, class Query>
std::vector<Result> run_queries(const vplkit::GpuBvh& bvh, const std::vector<Query>& queries, const std::string& name) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t count = uint32_t(queries.size());
    auto query_buffer = vplkit::Buffer::create(ctx, count * sizeof(Query), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                               vplkit::MemoryUse::device, name + " queries");
    auto result_buffer = vplkit::Buffer::create(ctx, count * sizeof(Result), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                vplkit::MemoryUse::device, name + " results");
    query_buffer.upload(queries);
    const auto& pipeline = ctx.pipeline<Pipeline>();
    vplkit::PassList passes(name + " test");
    passes.add(name,
               {vplkit::Use::read(bvh.nodes), vplkit::Use::read(bvh.triangles), vplkit::Use::read(bvh.alpha),
                vplkit::Use::read(query_buffer), vplkit::Use::write(result_buffer)},
               [&](VkCommandBuffer cmd) {
                   typename Pipeline::Bindings bindings;
                   vplkit::stages::bind_bvh(bindings, bvh);
                   bindings.queries = query_buffer.descriptor();
                   bindings.*ResultBinding = result_buffer.descriptor();
                   typename Pipeline::Push push{};
                   push.count = count;
                   pipeline.dispatch(cmd, bindings, push, count);
               });
    passes.run(ctx);
    return result_buffer.download<Result>(count);
}

std::vector<ts::SurfaceResult> run_surface_rays(const vplkit::GpuBvh& bvh,
                                                const std::vector<ts::SurfaceQuery>& queries) {
    return run_queries<ts::surface_rays::Pipeline, &ts::surface_rays::Bindings::results, ts::SurfaceResult>(
        bvh, queries, "surface rays");
}

std::vector<uint32_t> run_segments(const vplkit::GpuBvh& bvh, const std::vector<ts::SegmentQuery>& queries) {
    return run_queries<ts::segment_visibility::Pipeline, &ts::segment_visibility::Bindings::occluded, uint32_t>(
        bvh, queries, "segment visibility");
}

// Points to start from on a triangle: its corners, edge midpoints and random interior points.
std::vector<glm::vec2> surface_points(std::mt19937& rng) {
    std::vector<glm::vec2> points = {{0, 0}, {1, 0}, {0, 1}, {0.5f, 0}, {0, 0.5f}, {0.5f, 0.5f}};
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 4; ++i) {
        float a = unit(rng), b = unit(rng);
        if (a + b > 1.0f) {
            a = 1.0f - a;
            b = 1.0f - b;
        }
        points.push_back({a, b});
    }
    return points;
}

// A direction on the side of unit normal n, at cosine `cos_theta` to it.
glm::vec3 direction_at(glm::vec3 n, float cos_theta, std::mt19937& rng) {
    glm::vec3 t = glm::normalize(glm::cross(n, vplkit::bvh_test::random_direction(rng)));
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    return glm::normalize(cos_theta * n + sin_theta * t);
}

ts::SurfaceQuery make_query(uint32_t triangle, glm::vec2 b, float side, glm::vec3 direction) {
    ts::SurfaceQuery q{};
    q.barycentrics = {b.x, b.y};
    q.triangle = triangle;
    q.side = side;
    q.direction = {direction.x, direction.y, direction.z};
    q.tmax = 3.4e38f;
    return q;
}

glm::dvec3 geometric_normal(const vplkit::shaders::BvhTriangle& tri) {
    const glm::dvec3 v0 = to_dvec(tri.v0), v1 = to_dvec(tri.v1), v2 = to_dvec(tri.v2);
    return glm::normalize(glm::cross(v1 - v0, v2 - v0));
}

// The offset origin's distance from the plane of the triangle it left, in double.
double plane_distance(const vplkit::shaders::BvhTriangle& tri, const glm::dvec3& p) {
    return glm::dot(p - to_dvec(tri.v0), geometric_normal(tri));
}

struct Scale {
    float scale;
    glm::vec3 offset;
};
const Scale kScales[] = {{1e-3f, {0, 0, 0}}, {1.0f, {0, 0, 0}}, {1e4f, {0, 0, 0}}, {1.0f, {1e4f, -3e3f, 2e3f}}};

// Checks that the GPU's offset is the stated policy: 2^-16 * max(scene scale, |p|_max) along the
// normal, to within float rounding of the origin's coordinates.
void check_offset(const vplkit::Bvh& bvh, const ts::SurfaceQuery& q, const ts::SurfaceResult& r, size_t& failures) {
    const auto& tri = bvh.triangles[q.triangle];
    const glm::dvec3 p = (1.0 - q.barycentrics.x - q.barycentrics.y) * to_dvec(tri.v0) +
                         double(q.barycentrics.x) * to_dvec(tri.v1) + double(q.barycentrics.y) * to_dvec(tri.v2);
    const double p_max = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    const double h = double(vplkit::kBvhOriginOffset) * std::max(double(bvh.scene_scale), p_max);
    const double distance = q.side * plane_distance(tri, to_dvec(r.origin));
    // Each coordinate of the offset origin is rounded to float: up to 3 half-ulps of max(|p|)
    // = 2^-24 * 3 * p_max <= 0.02 h (and the scale was read back exactly: compare it too).
    if (r.scale != bvh.scene_scale || std::fabs(distance - h) > 0.05 * h) {
        ++failures;
        if (failures <= 3) {
            MESSAGE("offset " << distance << " expected " << h << " (scale " << r.scale << " / " << bvh.scene_scale
                              << ")");
        }
    }
}

}  // namespace

TEST_CASE("bvh offset: rays leaving a convex mesh from its surface hit nothing") {
    // Every point of a convex mesh lies on the inner side of each face's plane, so a ray that
    // starts on a face and leaves to its outer side meets nothing, at any angle: any hit is a
    // self-intersection (or one with a neighbour face).
    std::mt19937 rng(41);
    for (const Scale& s : kScales) {
        CAPTURE(s.scale);
        CAPTURE(s.offset.x);
        const Triangles sphere = vplkit::bvh_test::transformed(vplkit::bvh_test::icosphere(2), s.scale, s.offset);
        const auto bvh = vplkit::build_bvh(sphere);
        const auto gpu = vplkit::upload_bvh(vplkit::test::context(), bvh);
        std::vector<ts::SurfaceQuery> queries;
        for (uint32_t t = 0; t < bvh.triangles.size(); ++t) {
            const auto& tri = bvh.triangles[t];
            const glm::vec3 n = glm::vec3(geometric_normal(tri));
            // Outward: the normal points away from the sphere's centre (the mesh winds that way).
            const float side = glm::dot(glm::dvec3(n), to_dvec(tri.v0) - glm::dvec3(s.offset)) > 0.0 ? 1.0f : -1.0f;
            REQUIRE(side == 1.0f);
            for (const glm::vec2& b : surface_points(rng)) {
                for (float cos_theta : {1.0f, 0.5f, 0.05f, 1e-3f}) {
                    queries.push_back(make_query(t, b, side, direction_at(side * n, cos_theta, rng)));
                }
            }
        }
        const auto results = run_surface_rays(gpu, queries);
        size_t hits = 0, offset_failures = 0;
        for (size_t i = 0; i < queries.size(); ++i) {
            hits += results[i].hit.id != kBvhNoHit ? 1 : 0;
            check_offset(bvh, queries[i], results[i], offset_failures);
        }
        MESSAGE(queries.size() << " rays leaving the surface: " << hits << " hits");
        CHECK(hits == 0);
        CHECK(offset_failures == 0);
    }
}

TEST_CASE("bvh offset: rays into a closed mesh from its surface hit the far side, never their own face") {
    std::mt19937 rng(42);
    for (const Scale& s : kScales) {
        CAPTURE(s.scale);
        CAPTURE(s.offset.x);
        const Triangles sphere = vplkit::bvh_test::transformed(vplkit::bvh_test::icosphere(2), s.scale, s.offset);
        const auto bvh = vplkit::build_bvh(sphere);
        const auto gpu = vplkit::upload_bvh(vplkit::test::context(), bvh);
        const auto reference_triangles = vplkit::bvh_test::to_reference(sphere);
        std::vector<ts::SurfaceQuery> queries;
        for (uint32_t t = 0; t < bvh.triangles.size(); t += 2) {
            const glm::vec3 inward = -glm::vec3(geometric_normal(bvh.triangles[t]));
            for (const glm::vec2& b : surface_points(rng)) {
                for (float cos_theta : {1.0f, 0.3f, 0.02f}) {
                    queries.push_back(make_query(t, b, -1.0f, direction_at(inward, cos_theta, rng)));
                }
            }
        }
        const auto results = run_surface_rays(gpu, queries);
        size_t misses = 0, self_hits = 0, wrong = 0, offset_failures = 0;
        for (size_t i = 0; i < queries.size(); ++i) {
            const auto& hit = results[i].hit;
            check_offset(bvh, queries[i], results[i], offset_failures);
            if (hit.id == kBvhNoHit) {
                ++misses;
                continue;
            }
            if (hit.triangle == queries[i].triangle) {
                ++self_hits;
                continue;
            }
            // The far side, where the reference (from the same float origin) says.
            vplkit::reference::Ray ray;
            ray.origin = {results[i].origin.x, results[i].origin.y, results[i].origin.z};
            ray.direction = {queries[i].direction.x, queries[i].direction.y, queries[i].direction.z};
            ray.tmin = 0.0;
            ray.tmax = 1e30;
            const auto ref = vplkit::reference::closest_hit(reference_triangles, ray);
            // t is in world units here (unit directions): the rounding is relative to the
            // scene's coordinates, up to |offset| + scale.
            const double reach = std::fabs(s.offset.x) + std::fabs(s.offset.y) + std::fabs(s.offset.z) + 2.0 * s.scale;
            if (!ref.hit || std::fabs(double(hit.t) - ref.t) > vplkit::bvh_test::kRelativeTolerance * reach) {
                ++wrong;
            }
        }
        MESSAGE(queries.size() << " rays into the mesh: " << misses << " misses, " << self_hits << " self hits");
        CHECK(misses == 0);
        CHECK(self_hits == 0);
        CHECK(wrong == 0);
        CHECK(offset_failures == 0);
    }
}

TEST_CASE("bvh offset: an occluder twice the offset away is never missed") {
    std::mt19937 rng(43);
    for (const Scale& s : kScales) {
        CAPTURE(s.scale);
        CAPTURE(s.offset.x);
        // A floor of 8 x 8 quads over [-1, 1]^2 at y = 0, and a larger ceiling at y = gap,
        // gap = 2 * (2^-16 * scene scale): twice the largest offset any floor point gets.
        Triangles floor_tris;
        for (int i = 0; i < 8; ++i) {
            for (int j = 0; j < 8; ++j) {
                const float x = -1.0f + 0.25f * float(i), z = -1.0f + 0.25f * float(j);
                const glm::vec3 a(x, 0, z), b(x, 0, z + 0.25f), c(x + 0.25f, 0, z + 0.25f), d(x + 0.25f, 0, z);
                floor_tris.insert(floor_tris.end(), {a, b, c, a, c, d});
            }
        }
        Triangles scene = vplkit::bvh_test::transformed(floor_tris, s.scale, s.offset);
        // The scene scale: the largest coordinate of the (padded) root box. The ceiling spans
        // x, z in [-8, 8] * scale, so it sets the box; its height is solved for below. (Far from
        // the world origin the gap is 0.3 units over a 1-unit floor: a ray at cosine 0.1
        // travels 3 units sideways before it reaches the ceiling, which must still be there.)
        const float extent = 8.0f * s.scale;
        const float far =
            std::max({std::fabs(s.offset.x) + extent, std::fabs(s.offset.y) + extent, std::fabs(s.offset.z) + extent});
        const float scene_scale = far * (1.0f + vplkit::kBvhBoxPadding);
        const float gap = 2.0f * vplkit::kBvhOriginOffset * scene_scale;
        const float y = s.offset.y + gap;
        const glm::vec3 ceiling[4] = {{s.offset.x - extent, y, s.offset.z - extent},
                                      {s.offset.x + extent, y, s.offset.z - extent},
                                      {s.offset.x + extent, y, s.offset.z + extent},
                                      {s.offset.x - extent, y, s.offset.z + extent}};
        // Wound to face down, towards the floor (the winding does not matter to the test).
        scene.insert(scene.end(), {ceiling[0], ceiling[1], ceiling[2], ceiling[0], ceiling[2], ceiling[3]});
        const auto bvh = vplkit::build_bvh(scene);
        const auto gpu = vplkit::upload_bvh(vplkit::test::context(), bvh);
        CHECK(bvh.scene_scale >= 0.99f * scene_scale);
        CHECK(bvh.scene_scale <= 1.01f * scene_scale);
        const uint32_t floor_count = uint32_t(floor_tris.size() / 3);
        std::vector<ts::SurfaceQuery> queries;
        for (uint32_t t = 0; t < bvh.triangles.size(); ++t) {
            if (bvh.triangles[t].id >= floor_count) {
                continue;  // start on the floor only
            }
            const glm::vec3 n = glm::vec3(geometric_normal(bvh.triangles[t]));
            const float side = n.y > 0.0f ? 1.0f : -1.0f;
            for (const glm::vec2& b : surface_points(rng)) {
                for (float cos_theta : {1.0f, 0.5f, 0.1f}) {
                    queries.push_back(make_query(t, b, side, direction_at(glm::vec3(0, 1, 0), cos_theta, rng)));
                }
            }
        }
        const auto results = run_surface_rays(gpu, queries);
        size_t missed = 0, floor_hits = 0, offset_failures = 0;
        for (size_t i = 0; i < queries.size(); ++i) {
            const auto& hit = results[i].hit;
            check_offset(bvh, queries[i], results[i], offset_failures);
            if (hit.id == kBvhNoHit) {
                ++missed;
            } else if (hit.id < floor_count) {
                ++floor_hits;
            }
        }
        MESSAGE(queries.size() << " rays towards a ceiling " << gap << " above the floor: " << missed << " missed it, "
                               << floor_hits << " hit the floor");
        CHECK(missed == 0);
        CHECK(floor_hits == 0);
        CHECK(offset_failures == 0);
    }
}

namespace {

ts::SegmentQuery segment(uint32_t p_triangle, glm::vec2 p_b, float p_side, uint32_t q_triangle, glm::vec2 q_b,
                         float q_side) {
    ts::SegmentQuery s{};
    s.p_triangle = p_triangle;
    s.p_barycentrics = {p_b.x, p_b.y};
    s.p_side = p_side;
    s.q_triangle = q_triangle;
    s.q_barycentrics = {q_b.x, q_b.y};
    s.q_side = q_side;
    return s;
}

glm::dvec3 surface_point(const vplkit::shaders::BvhTriangle& tri, glm::vec2 b) {
    return (1.0 - b.x - b.y) * to_dvec(tri.v0) + double(b.x) * to_dvec(tri.v1) + double(b.y) * to_dvec(tri.v2);
}

}  // namespace

TEST_CASE("bvh offset: segments between points on a convex mesh are never blocked by their own ends") {
    // A segment between two points of a convex mesh runs inside it: nothing can block it but the
    // surfaces at its two ends. Pairs on the same face, on neighbouring faces (consecutive in
    // leaf order, mostly adjacent) and far apart, from corners, edges and interiors.
    std::mt19937 rng(44);
    for (const Scale& s : kScales) {
        CAPTURE(s.scale);
        CAPTURE(s.offset.x);
        const Triangles sphere = vplkit::bvh_test::transformed(vplkit::bvh_test::icosphere(2), s.scale, s.offset);
        const auto bvh = vplkit::build_bvh(sphere);
        const auto gpu = vplkit::upload_bvh(vplkit::test::context(), bvh);
        const uint32_t n = uint32_t(bvh.triangles.size());
        std::uniform_int_distribution<uint32_t> any(0, n - 1);
        std::vector<ts::SegmentQuery> queries;
        for (uint32_t t = 0; t < n; ++t) {
            const auto points = surface_points(rng);
            for (size_t k = 0; k < points.size(); ++k) {
                const glm::vec2 other = points[(k + 1) % points.size()];
                // Inward (-1): the side of each face the segment runs on.
                queries.push_back(segment(t, points[k], -1.0f, t, other, -1.0f));
                queries.push_back(segment(t, points[k], -1.0f, (t + 1) % n, other, -1.0f));
                queries.push_back(segment(t, points[k], -1.0f, any(rng), other, -1.0f));
            }
        }
        const auto occluded = run_segments(gpu, queries);
        size_t blocked = 0;
        for (uint32_t o : occluded) {
            blocked += o;
        }
        MESSAGE(queries.size() << " segments inside a convex mesh: " << blocked << " blocked");
        CHECK(blocked == 0);
    }
}

TEST_CASE("bvh offset: segments and point-light rays through a plate are blocked exactly where they cross it") {
    std::mt19937 rng(45);
    for (const Scale& s : kScales) {
        CAPTURE(s.scale);
        CAPTURE(s.offset.x);
        // The unit sphere mesh, and inside it a square plate z = 0, |x|, |y| < 0.5.
        Triangles scene = vplkit::bvh_test::transformed(vplkit::bvh_test::icosphere(2), s.scale, s.offset);
        const uint32_t sphere_triangles = uint32_t(scene.size() / 3);
        const Triangles plate = {{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0},
                                 {-0.5f, -0.5f, 0}, {0.5f, 0.5f, 0},  {-0.5f, 0.5f, 0}};
        const Triangles placed = vplkit::bvh_test::transformed(plate, s.scale, s.offset);
        scene.insert(scene.end(), placed.begin(), placed.end());
        const auto bvh = vplkit::build_bvh(scene);
        const auto gpu = vplkit::upload_bvh(vplkit::test::context(), bvh);

        std::vector<uint32_t> on_sphere;
        for (uint32_t t = 0; t < bvh.triangles.size(); ++t) {
            if (bvh.triangles[t].id < sphere_triangles) {
                on_sphere.push_back(t);
            }
        }
        std::uniform_int_distribution<size_t> pick(0, on_sphere.size() - 1);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        auto random_b = [&] {
            float a = unit(rng), b = unit(rng);
            return a + b > 1.0f ? glm::vec2(1.0f - a, 1.0f - b) : glm::vec2(a, b);
        };
        // The light: a free point inside the sphere, above the plate.
        const glm::vec3 light = glm::vec3(0.1f, -0.2f, 0.6f) * s.scale + s.offset;
        std::vector<ts::SegmentQuery> queries;
        std::vector<int> expected;  // 1 blocked, 0 free, -1 within rounding of the plate's rim: either
        // The expected answer uses the offset endpoints (the policy, in double), so the GPU's
        // only freedom is float rounding of positions: a few ulps of the largest coordinate
        // (1e-3 at 1e4 from the origin), in the unscaled frame divided by the scale.
        const double far = std::max({std::fabs(s.offset.x), std::fabs(s.offset.y), std::fabs(s.offset.z)}) + s.scale;
        const double rim_tolerance = std::max(1e-4, 8.0 * std::exp2(-24.0) * far / s.scale);
        auto offset_point = [&](const glm::dvec3& x, const glm::dvec3& n) {
            const double x_max = std::max({std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)});
            return x + n * (double(vplkit::kBvhOriginOffset) * std::max(double(bvh.scene_scale), x_max));
        };
        for (int i = 0; i < 4000; ++i) {
            const uint32_t tp = on_sphere[pick(rng)];
            const glm::vec2 bp = random_b();
            const glm::dvec3 p =
                offset_point(surface_point(bvh.triangles[tp], bp), -geometric_normal(bvh.triangles[tp]));
            ts::SegmentQuery query;
            glm::dvec3 q;
            if (i % 2 == 0) {
                const uint32_t tq = on_sphere[pick(rng)];
                const glm::vec2 bq = random_b();
                query = segment(tp, bp, -1.0f, tq, bq, -1.0f);
                q = offset_point(surface_point(bvh.triangles[tq], bq), -geometric_normal(bvh.triangles[tq]));
            } else {
                query = segment(tp, bp, -1.0f, vplkit::kBvhNoHit, {0, 0}, 0.0f);
                query.q_point = {light.x, light.y, light.z};
                q = glm::dvec3(light);
            }
            // Where the segment crosses the plate's plane, in the unscaled frame.
            const glm::dvec3 a = (p - glm::dvec3(s.offset)) / double(s.scale);
            const glm::dvec3 b = (q - glm::dvec3(s.offset)) / double(s.scale);
            int e = 0;
            if ((a.z > 0.0) != (b.z > 0.0)) {
                const glm::dvec3 x = a + (a.z / (a.z - b.z)) * (b - a);
                const double rim = 0.5 - std::max(std::fabs(x.x), std::fabs(x.y));
                e = std::fabs(rim) < rim_tolerance ? -1 : (rim > 0.0 ? 1 : 0);
            }
            queries.push_back(query);
            expected.push_back(e);
        }
        const auto occluded = run_segments(gpu, queries);
        size_t wrong = 0, blocked = 0;
        for (size_t i = 0; i < queries.size(); ++i) {
            blocked += occluded[i];
            if (expected[i] >= 0 && int(occluded[i]) != expected[i]) {
                ++wrong;
            }
        }
        MESSAGE(queries.size() << " segments: " << blocked << " blocked by the plate, " << wrong << " wrong");
        CHECK(wrong == 0);
        CHECK(blocked > 400);
    }
}
