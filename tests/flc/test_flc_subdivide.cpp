// The divergent triangles' subdivision (flc_subdivide.comp, the FLC paper sec. 6): a triangle larger
// than S~_N becomes m^2 equal sub-triangles on the barycentric grid, each a regular candidate with
// its own draw of Alg. 1.
// - Tiling: the sub-triangles' centroids are exactly the grid's m^2 triangle centroids (in the
//   parent's barycentric coordinates x 3m: (3k+1, 3r+1) up, (3k+2, 3r+2) down; 1e-3 of a grid
//   step for float), each of area A / m^2 (1e-5 relative), the parent's normal and albedo.
// - Decimation: the kept sub-triangles over 16 seeds against m^2 x A_sub / S~_N, within 4 sigma of
//   the binomial (each sub-triangle is kept with probability A_sub / S~_N).
// - A triangle the host lists (1% margin) but the candidates pass found regular: its
//   sub-triangles are all discarded, it keeps its own level (no light counted twice).
// - Hard cases: a zero-area triangle, a long sliver larger than S~_N, a huge triangle, at scale 1,
//   1e-3 and 1e4: every field finite, no sub-triangle divergent, the sliver's inside its box.
// - A rigid transform of the mesh keeps every sub-triangle's level (the pattern depends on the
//   area alone, the numbers on the vertices' integers and the grid).

#include "flc_test_mesh.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/stages/flc.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace flc_test;
using vplkit::shaders::FlcCandidate;
using vplkit::stages::FlcPartition;

FlcPartition test_partition(float scale = 1.0f) {
    return {3, 0.25f * scale * scale, 1.0f * scale, 2.0f};  // S~_N = 0.25 / 1.75 = 1/7 (x scale^2)
}

struct Run {
    std::vector<FlcCandidate> candidates;  // the triangles', then the sub-triangles'
    std::vector<glm::vec4> albedo;         // per candidate
    vplkit::stages::FlcSubdivision subdivision;
};

std::vector<double> areas_of(const Mesh& mesh) {
    std::vector<double> out;
    for (uint32_t t = 0; t < mesh.triangle_count(); ++t) {
        const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]),
            c(mesh.positions[mesh.indices[3 * t + 2]]);
        out.push_back(0.5 * glm::length(glm::cross(b - a, c - a)));
    }
    return out;
}

Run run(const Mesh& mesh, const FlcPartition& partition, uint32_t seed) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t count = mesh.triangle_count();
    Run r;
    r.subdivision = vplkit::stages::flc_subdivision_for(areas_of(mesh), partition);
    const uint32_t total = count + r.subdivision.sub_count;
    std::vector<vplkit::scene::Vertex> vertices(mesh.positions.size());
    for (size_t i = 0; i < vertices.size(); ++i) vertices[i].position = mesh.positions[i];
    std::vector<glm::vec4> albedo;
    for (uint32_t t = 0; t < count; ++t) albedo.push_back({float(t), 0.5f, 0.25f, 0.0f});
    auto create = [&](VkDeviceSize bytes, const char* name) {
        return vplkit::Buffer::create(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, name);
    };
    auto vertex_buffer = create(vertices.size() * sizeof(vplkit::scene::Vertex), "vertices");
    auto index_buffer = create(mesh.indices.size() * sizeof(uint32_t), "indices");
    auto random_buffer = create(mesh.random.size() * sizeof(uint32_t), "vertex random");
    auto entries =
        create(std::max<size_t>(r.subdivision.entries.size(), 1) * sizeof(r.subdivision.entries[0]), "entries");
    auto candidates = create(total * sizeof(FlcCandidate), "candidates");
    auto triangle_albedo = create(count * sizeof(glm::vec4), "triangle albedo");
    auto candidate_albedo = create(total * sizeof(glm::vec4), "candidate albedo");
    vertex_buffer.upload(vertices);
    index_buffer.upload(mesh.indices);
    random_buffer.upload(mesh.random);
    if (!r.subdivision.entries.empty()) entries.upload(r.subdivision.entries);
    triangle_albedo.upload(albedo);
    vplkit::PassList passes("flc subdivide test");
    vplkit::stages::add_flc_candidates_pass(ctx, passes, {vertex_buffer, index_buffer, random_buffer, candidates},
                                            partition, count, seed);
    vplkit::stages::add_flc_subdivide_pass(
        ctx, passes,
        {vertex_buffer, index_buffer, random_buffer, entries, candidates, triangle_albedo, candidate_albedo}, partition,
        r.subdivision, count, seed);
    passes.run(ctx);
    r.candidates = candidates.download<FlcCandidate>(total);
    r.albedo = candidate_albedo.download<glm::vec4>(total);
    return r;
}

glm::dvec3 d(const vplkit::shaders::vec3& v) {
    return {v.x, v.y, v.z};
}

}  // namespace

TEST_CASE("flc subdivide: a huge triangle becomes m^2 equal regular sub-triangles that tile it") {
    Mesh mesh;
    const glm::vec3 a(0.3f, -0.2f, 0.1f), b(5.3f, 0.4f, 0.1f), c(1.1f, 3.9f, 0.6f);
    add_triangle(mesh, a, b, c);
    const FlcPartition partition = test_partition();
    const Run r = run(mesh, partition, 3);
    REQUIRE(r.subdivision.entries.size() == 1);
    const double area = areas_of(mesh)[0];
    const double target = 0.99 * vplkit::stages::flc_divergence_area(partition);
    const uint32_t m = r.subdivision.entries[0].side;
    CHECK(double(m - 1) * double(m - 1) * target < area);  // the smallest side that works
    CHECK(double(m) * double(m) * target >= area);
    REQUIRE(r.subdivision.sub_count == m * m);
    CHECK(r.candidates[0].level == vplkit::stages::kFlcDivergent);
    // Barycentric coordinates (along b - a, c - a) x 3m of each sub-triangle's centroid.
    const glm::dvec3 e1 = glm::dvec3(b) - glm::dvec3(a), e2 = glm::dvec3(c) - glm::dvec3(a);
    const double g11 = glm::dot(e1, e1), g12 = glm::dot(e1, e2), g22 = glm::dot(e2, e2), det = g11 * g22 - g12 * g12;
    std::set<std::pair<long, long>> got, expected;
    for (uint32_t r_ = 0; r_ < m; ++r_) {
        for (uint32_t k = 0; k < m - r_; ++k) expected.insert({3 * k + 1, 3 * r_ + 1});
        for (uint32_t k = 0; k + 1 < m - r_; ++k) expected.insert({3 * k + 2, 3 * r_ + 2});
    }
    for (uint32_t s = 0; s < m * m; ++s) {
        CAPTURE(s);
        const FlcCandidate& sub = r.candidates[1 + s];
        CHECK(sub.level != vplkit::stages::kFlcDivergent);
        CHECK(double(sub.area) == doctest::Approx(area / (m * m)).epsilon(1e-5));
        CHECK(d(sub.normal) == d(r.candidates[0].normal));
        CHECK(r.albedo[1 + s] == glm::vec4(0.0f, 0.5f, 0.25f, 0.0f));
        const glm::dvec3 v = d(sub.position) - glm::dvec3(a);
        const double p1 = glm::dot(v, e1), p2 = glm::dot(v, e2);
        const double u = (g22 * p1 - g12 * p2) / det * 3.0 * m, w = (g11 * p2 - g12 * p1) / det * 3.0 * m;
        CHECK(std::abs(u - std::round(u)) < 3e-3);
        CHECK(std::abs(w - std::round(w)) < 3e-3);
        got.insert({std::lround(u), std::lround(w)});
    }
    CHECK(got == expected);  // every grid triangle once
    CHECK(r.albedo[0] == glm::vec4(0.0f, 0.5f, 0.25f, 0.0f));
}

TEST_CASE("flc subdivide: the kept sub-triangles match their keep probability over 16 seeds") {
    Mesh mesh;
    add_triangle(mesh, glm::vec3(0.0f), glm::vec3(9.0f, 0.0f, 0.0f), glm::vec3(0.0f, 7.0f, 0.0f));
    const FlcPartition partition = test_partition();
    double kept = 0.0, expected = 0.0, variance = 0.0;
    for (uint32_t seed = 0; seed < 16; ++seed) {
        const Run r = run(mesh, partition, seed);
        const uint32_t n = r.subdivision.sub_count;
        const double p = double(r.candidates[1].area) / vplkit::stages::flc_divergence_area(partition);
        for (uint32_t s = 0; s < n; ++s) kept += r.candidates[1 + s].level >= 0 ? 1.0 : 0.0;
        expected += n * p;
        variance += n * p * (1.0 - p);
    }
    MESSAGE("kept " << kept << " sub-triangles, expected " << expected << " +- " << std::sqrt(variance));
    CHECK(std::abs(kept - expected) <= 4.0 * std::sqrt(variance));
}

TEST_CASE("flc subdivide: a listed triangle the candidates pass found regular keeps its level, no sub-triangle") {
    const FlcPartition partition = test_partition();
    const double below = 0.995 * vplkit::stages::flc_divergence_area(partition);  // inside the 1% margin
    Mesh mesh;
    const float side = float(std::sqrt(2.0 * below));
    add_triangle(mesh, glm::vec3(0.0f), glm::vec3(side, 0.0f, 0.0f), glm::vec3(0.0f, side, 0.0f));
    const Run r = run(mesh, partition, 1);
    REQUIRE(r.subdivision.entries.size() == 1);
    CHECK(r.candidates[0].level != vplkit::stages::kFlcDivergent);
    for (uint32_t s = 0; s < r.subdivision.sub_count; ++s) {
        CHECK(r.candidates[1 + s].level == vplkit::stages::kFlcDiscarded);
    }
}

TEST_CASE(
    "flc subdivide: zero-area, sliver and huge triangles at scale 1, 1e-3 and 1e4 give finite regular candidates") {
    for (float scale : {1.0f, 1e-3f, 1e4f}) {
        CAPTURE(scale);
        Mesh mesh;
        add_triangle(mesh, glm::vec3(1.0f) * scale, glm::vec3(1.0f) * scale, glm::vec3(2.0f, 1.0f, 1.0f) * scale);
        add_triangle(mesh, glm::vec3(0.0f), glm::vec3(40.0f, 0.0f, 0.0f) * scale,
                     glm::vec3(20.0f, 0.05f, 0.0f) * scale);
        add_triangle(mesh, glm::vec3(0.0f, 0.0f, 1.0f) * scale, glm::vec3(30.0f, 0.0f, 1.0f) * scale,
                     glm::vec3(0.0f, 30.0f, 1.0f) * scale);
        const Run r = run(mesh, test_partition(scale), 9);
        CHECK(r.subdivision.entries.size() == 2);  // the sliver (area 1 x scale^2 > 1/7) and the huge one
        CHECK(r.candidates[0].level == vplkit::stages::kFlcDiscarded);
        CHECK(r.candidates[1].level == vplkit::stages::kFlcDivergent);
        CHECK(r.candidates[2].level == vplkit::stages::kFlcDivergent);
        for (size_t i = 3; i < r.candidates.size(); ++i) {
            const FlcCandidate& c = r.candidates[i];
            REQUIRE(std::isfinite(c.position.x));
            REQUIRE(std::isfinite(c.position.y));
            REQUIRE(std::isfinite(c.position.z));
            REQUIRE(std::isfinite(c.area));
            REQUIRE(std::isfinite(c.normal.z));
            CHECK(c.level != vplkit::stages::kFlcDivergent);
            CHECK(c.area > 0.0f);
        }
        const uint32_t sliver_subs = r.subdivision.entries[0].side * r.subdivision.entries[0].side;
        for (uint32_t s = 0; s < sliver_subs; ++s) {
            const FlcCandidate& c = r.candidates[3 + s];
            CHECK(c.position.x >= 0.0f);
            CHECK(c.position.x <= 40.0f * scale);
            CHECK(c.position.y >= 0.0f);
            CHECK(c.position.y <= 0.05f * scale);
        }
    }
}

TEST_CASE("flc subdivide: a rigid transform of the mesh keeps every sub-triangle's level") {
    Mesh mesh;
    add_triangle(mesh, glm::vec3(0.0f), glm::vec3(6.0f, 0.0f, 0.0f), glm::vec3(1.0f, 5.0f, 0.0f));
    add_triangle(mesh, glm::vec3(0.0f, 0.0f, 2.0f), glm::vec3(0.0f, 4.0f, 2.0f), glm::vec3(3.0f, 0.0f, 2.0f));
    const glm::mat4 moved = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, -7.0f, 2.5f)), 0.7f,
                                        glm::normalize(glm::vec3(1.0f, 2.0f, 3.0f)));
    const FlcPartition partition = test_partition();
    const Run before = run(mesh, partition, 4);
    const Run after = run(transformed(mesh, moved), partition, 4);
    REQUIRE(before.subdivision.sub_count == after.subdivision.sub_count);
    REQUIRE(before.subdivision.sub_count > 50);
    int kept = 0;
    for (size_t i = 2; i < before.candidates.size(); ++i) {
        CAPTURE(i);
        CHECK(before.candidates[i].level == after.candidates[i].level);
        kept += before.candidates[i].level >= 0;
    }
    CHECK(kept > 10);
}

TEST_CASE("flc subdivide: a subdivision beyond the candidate limit is refused") {
    const std::vector<double> areas = {1.0, 1e12};
    // In the stage's own terms (its partition's fields), never a command-line flag.
    CHECK_THROWS_WITH_AS(vplkit::stages::flc_subdivision_for(areas, test_partition()),
                         doctest::Contains("the partition needs a larger s0 (fewer VPLs per point)"), vplkit::Error);
    try {
        vplkit::stages::flc_subdivision_for(areas, test_partition());
    } catch (const vplkit::Error& e) {
        CHECK(std::string(e.what()).find("--") == std::string::npos);
    }
}

TEST_CASE("flc subdivide: past 65,535 workgroups of 64 candidates the limit is the device's binding range") {
    // The flc passes fold their dispatches (vplkit/dispatch.glsl), so the subdivision itself takes
    // up to kFlcMaxCandidates (2^31); a device takes as many as its FlcCandidate buffer's binding
    // holds. 3000^2 sub-triangles and two triangles: 9,000,002 candidates, 140,626 workgroups.
    const FlcPartition partition = test_partition();
    const double target = 0.99 * vplkit::stages::flc_divergence_area(partition);
    const std::vector<double> areas = {0.5 * target, 2999.5 * 2999.5 * target};
    const vplkit::stages::FlcSubdivision subdivision = vplkit::stages::flc_subdivision_for(areas, partition);
    REQUIRE(subdivision.entries.size() == 1);
    CHECK(subdivision.entries[0].side == 3000u);
    CHECK(subdivision.sub_count == 3000u * 3000u);

    vplkit::Context& ctx = vplkit::test::context();
    const uint64_t device_max = vplkit::stages::flc_max_candidates(ctx);
    CHECK(device_max > 65535ull * 64ull);  // lavapipe: 2^27 bytes / 32 = 4,194,304
    CHECK(device_max == std::min<uint64_t>(vplkit::stages::kFlcMaxCandidates,
                                           ctx.limits().max_storage_buffer_range / sizeof(FlcCandidate)));
    if (device_max < 2 + 3000ull * 3000ull) {
        CHECK_THROWS_WITH_AS(vplkit::stages::flc_subdivision_for(areas, partition, device_max),
                             doctest::Contains("the partition needs a larger s0 (fewer VPLs per point)"),
                             vplkit::Error);
    }
}
