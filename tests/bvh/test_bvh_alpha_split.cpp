// Alpha-tested triangles in a subtree of their own (vplkit/bvh.hpp, build_bvh_split;
// build_scene_bvh): bvh.glsl traverses the opaque subtree with the alpha test compiled out, then
// the masked subtree with it. Closest hits and occlusion on lavapipe against the brute-force
// double-precision reference, on a soup of opaque and masked triangles.
//
// Expectation: masked triangles have a factor-only alpha (COLOR_0) of 1 at one corner k and 0 at
// the other two, cutoff 0.5, so the surface a ray may hit is exactly the half-size triangle at
// corner k (alpha = b_k >= 0.5 where b_k is k's barycentric weight); the reference gets that
// triangle in place of the full one. Fully cut-out triangles (alpha 0 everywhere) get a
// degenerate reference triangle, which no ray hits; masked-material triangles whose alpha
// passes everywhere get no record and stay whole (in the opaque subtree). A traversal that
// skipped the masked subtree misses certain hits on the half triangles; one that tested them
// without alpha hits their cut-out halves and the fully cut-out triangles; one that bounded the
// masked subtree wrongly misses nearer hits. Tolerances: bvh_test_support.hpp (relative 1e-5 in
// t; a ray within rounding of an edge, the alpha cut line included, may go either way).

#include "bvh_test_support.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_alpha.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/scene.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/vec3.hpp>

#include <cmath>
#include <random>
#include <vector>

namespace {

using vplkit::kBvhNoHit;
using vplkit::bvh_test::make_ray;
using vplkit::bvh_test::Triangles;
using vplkit::shaders::BvhHit;
using vplkit::shaders::BvhRay;

// What triangle i of the test scene is (i % 4).
enum Kind : uint32_t { opaque = 0, half_masked = 1, cut_out = 2, masked_but_solid = 3 };

Kind kind_of(uint32_t triangle) {
    return Kind(triangle % 4);
}
// The corner whose alpha is 1 in a half-masked triangle.
uint32_t solid_corner(uint32_t triangle) {
    return (triangle / 4) % 3;
}

// The soup as a scene: material 0 opaque, material 1 MASK (cutoff 0.5, no texture), alpha per
// corner in COLOR_0.
vplkit::scene::Scene masked_scene(const Triangles& soup) {
    vplkit::scene::Scene scene;
    vplkit::scene::Material solid;
    solid.name = "opaque";
    vplkit::scene::Material masked;
    masked.name = "masked";
    masked.alpha_mode = vplkit::scene::AlphaMode::mask;
    masked.alpha_cutoff = 0.5f;
    scene.materials = {solid, masked};
    const uint32_t count = uint32_t(soup.size() / 3);
    for (uint32_t t = 0; t < count; ++t) {
        const Kind kind = kind_of(t);
        for (uint32_t k = 0; k < 3; ++k) {
            vplkit::scene::Vertex v;
            v.position = soup[3 * t + k];
            v.normal = {0.0f, 0.0f, 1.0f};
            const float alpha = kind == half_masked ? (k == solid_corner(t) ? 1.0f : 0.0f)
                                : kind == cut_out   ? 0.0f
                                                    : 1.0f;
            v.color = {1.0f, 1.0f, 1.0f, alpha};
            scene.indices.push_back(uint32_t(scene.vertices.size()));
            scene.vertices.push_back(v);
        }
        scene.triangle_materials.push_back(kind == opaque ? 0u : 1u);
    }
    return scene;
}

// The surface a ray may hit, per triangle (indexed by id = scene triangle index).
std::vector<vplkit::reference::Triangle> visible_surface(const Triangles& soup) {
    auto out = vplkit::bvh_test::to_reference(soup);
    for (uint32_t t = 0; t < out.size(); ++t) {
        auto& tri = out[t];
        if (kind_of(t) == cut_out) {
            tri.v1 = tri.v0;
            tri.v2 = tri.v0;
        } else if (kind_of(t) == half_masked) {
            vplkit::reference::Double3* v[3] = {&tri.v0, &tri.v1, &tri.v2};
            const auto corner = *v[solid_corner(t)];
            for (uint32_t k = 0; k < 3; ++k) {
                for (int axis = 0; axis < 3; ++axis) (*v[k])[axis] = 0.5 * ((*v[k])[axis] + corner[axis]);
            }
        }
    }
    return out;
}

// A hit's barycentrics on a half-masked triangle, re-expressed on its half triangle: with k the
// solid corner, p = b_k v_k + sum_j b_j v_j and v_j = 2 v_j' - v_k give b_j' = 2 b_j (j != k).
void to_half_triangle(std::vector<BvhHit>& hits) {
    for (auto& hit : hits) {
        if (hit.id == kBvhNoHit || kind_of(hit.id) != half_masked) continue;
        const float b1 = hit.barycentrics.x, b2 = hit.barycentrics.y;
        switch (solid_corner(hit.id)) {
            case 0:
                hit.barycentrics = {2.0f * b1, 2.0f * b2};
                break;
            case 1:  // b1' = 1 - b0' - b2' with b0' = 2 b0 = 2 (1 - b1 - b2)
                hit.barycentrics = {2.0f * b1 - 1.0f, 2.0f * b2};
                break;
            default:
                hit.barycentrics = {2.0f * b1, 2.0f * b2 - 1.0f};
                break;
        }
    }
}

// As test_bvh_trace.cpp's: random origins and directions, tmax random or unbounded, so both
// occlusion answers occur.
std::vector<BvhRay> random_rays(uint32_t count, uint32_t seed, float spread) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_real_distribution<float> fraction(0.0f, 1.0f);
    std::vector<BvhRay> rays;
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 origin = spread * glm::vec3(unit(rng), unit(rng), unit(rng));
        const glm::vec3 direction = vplkit::bvh_test::random_direction(rng) * (0.5f + 2.0f * fraction(rng));
        const float tmax = (i % 4 == 0) ? INFINITY : 6.0f * spread * fraction(rng);
        rays.push_back(make_ray(origin, direction, 0.0f, tmax));
    }
    return rays;
}

// Traces `rays` through `bvh` and compares with the reference of the visible surface.
vplkit::bvh_test::Agreement check(const vplkit::Bvh& bvh, const Triangles& soup, const std::vector<BvhRay>& rays) {
    const auto gpu = vplkit::upload_bvh(vplkit::test::context(), bvh);
    REQUIRE(gpu.alpha_tests);
    auto hits = vplkit::bvh_test::trace_closest(gpu, rays);
    const auto occlusion = vplkit::bvh_test::trace_occlusion(gpu, rays);
    to_half_triangle(hits);
    const auto surface = visible_surface(soup);
    const auto result = vplkit::bvh_test::compare_with_reference(surface, rays, hits, occlusion);
    MESSAGE(result.rays << " rays, " << result.hits << " reference hits, " << result.ties << " ties, "
                        << result.near_edge << " + " << result.occlusion_near << " excused near an edge or bound");
    CHECK(result.failures == 0);
    CHECK(double(result.near_edge) <= 0.01 * double(result.rays));
    CHECK(double(result.occlusion_near) <= 0.01 * double(result.rays));
    // The rays meet every kind of triangle: count the nearest hits per kind.
    uint32_t per_kind[4] = {};
    for (const auto& hit : hits) {
        if (hit.id != kBvhNoHit) ++per_kind[kind_of(hit.id)];
    }
    CHECK(per_kind[opaque] > 300);
    CHECK(per_kind[half_masked] > 100);
    CHECK(per_kind[cut_out] == 0);
    CHECK(per_kind[masked_but_solid] > 300);
    return result;
}

}  // namespace

TEST_CASE("bvh alpha split: closest hits and occlusion through the opaque and masked subtrees match the reference") {
    const Triangles soup = vplkit::bvh_test::random_soup(2000, 31);
    const auto scene = masked_scene(soup);
    vplkit::AlphaTestStats stats;
    const vplkit::Bvh bvh = vplkit::build_scene_bvh(scene, &stats);
    CHECK(stats.tested_triangles == 1000);  // half-masked and cut-out ones
    // The split layout: node 1 and masked_root under node 0, word 0 of the records names the
    // masked root, and the opaque subtree's triangles (masked_but_solid ones included) have none.
    REQUIRE(bvh.masked_root != 0);
    CHECK(bvh.nodes[0].index == bvh.masked_root);
    CHECK(bvh.alpha.at(0) == bvh.masked_root);
    CHECK(bvh.opaque_triangles == 1000);
    for (uint32_t i = 0; i < bvh.triangles.size(); ++i) {
        const bool tested = kind_of(bvh.triangles[i].id) == half_masked || kind_of(bvh.triangles[i].id) == cut_out;
        CHECK((i >= bvh.opaque_triangles) == tested);
        CHECK((bvh.triangles[i].alpha != 0) == tested);
    }
    check(bvh, soup, random_rays(6000, 32, 1.5f));
}

TEST_CASE("bvh alpha split: a tree that is not split is traversed whole, alpha tests everywhere") {
    const Triangles soup = vplkit::bvh_test::random_soup(2000, 33);
    const auto scene = masked_scene(soup);
    const auto rays = random_rays(4000, 34, 1.5f);
    SUBCASE("build_bvh: one tree") {
        vplkit::Bvh bvh = vplkit::build_bvh(vplkit::scene::triangle_positions(scene));
        vplkit::add_alpha_tests(bvh, scene);
        CHECK(bvh.masked_root == 0);
        CHECK(bvh.alpha.at(0) == 0);
        check(bvh, soup, rays);
    }
    SUBCASE("a split whose opaque subtree holds tested triangles is not used") {
        // Flags for the opaque triangles only: the tested ones land in the "opaque" subtree.
        std::vector<uint8_t> flags(soup.size() / 3, 0);
        for (uint32_t t = 0; t < flags.size(); ++t) flags[t] = kind_of(t) == opaque ? 1 : 0;
        vplkit::Bvh bvh = vplkit::build_bvh_split(vplkit::scene::triangle_positions(scene), flags);
        REQUIRE(bvh.masked_root != 0);
        vplkit::add_alpha_tests(bvh, scene);
        CHECK(bvh.alpha.at(0) == 0);
        check(bvh, soup, rays);
    }
}
