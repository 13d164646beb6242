// FLC reads an `addressed` scene (FlcCandidateBuffers::addressed, raster_scene.glsl's
// kSceneAddressed) at its device addresses, as the raster stages do: what a scene of more than
// 1.86M vertices (72 bytes each, past maxStorageBufferRange) but fewer triangles than FLC's
// candidate limit takes. Tested without such a scene by forcing the path on the in-repo Cornell
// box: vertices and indices at unaligned offsets among decoys give the bindings' candidates and
// sub-triangles (the only FLC passes that read the scene, so the rest of the frame follows) byte
// for byte; a scene past the range that is not addressed is refused, naming the buffer and limit.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/stages/flc.hpp"
#include "vplkit_test/context.hpp"
#include "vplkit_test/placed_buffer.hpp"
#include "vplkit_test/range_refusal.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using vplkit::shaders::FlcCandidate;

using vplkit::test::placed;

template <class T>
vplkit::BufferView whole(std::vector<vplkit::Buffer>& keep, const std::vector<T>& records, const char* name) {
    return placed(keep, records, T{}, 0, 0, name);
}

vplkit::scene::Scene cornell() {
    return vplkit::scene::load_gltf(std::filesystem::path(VPLKIT_SOURCE_DIR) /
                                    "scenes/cornell_point/cornell_point.gltf");
}

std::vector<double> triangle_areas(const vplkit::scene::Scene& scene) {
    std::vector<double> out;
    for (size_t t = 0; 3 * t + 2 < scene.indices.size(); ++t) {
        const glm::dvec3 a(scene.vertices[scene.indices[3 * t]].position);
        const glm::dvec3 b(scene.vertices[scene.indices[3 * t + 1]].position);
        const glm::dvec3 c(scene.vertices[scene.indices[3 * t + 2]].position);
        out.push_back(0.5 * glm::length(glm::cross(b - a, c - a)));
    }
    return out;
}

struct Candidates {
    std::vector<FlcCandidate> candidates;  // the triangles', then the sub-triangles'
    std::vector<glm::vec4> albedo;         // per candidate
};

// The candidates and subdivide passes over `vertices` and `indices` (the scene's, wherever placed).
Candidates run(const vplkit::scene::Scene& scene, vplkit::BufferView vertices, vplkit::BufferView indices,
               bool addressed, const vplkit::stages::FlcPartition& partition,
               const vplkit::stages::FlcSubdivision& subdivision) {
    vplkit::Context& ctx = vplkit::test::context();
    const auto count = uint32_t(scene.indices.size() / 3);
    const uint32_t total = count + subdivision.sub_count;
    std::vector<vplkit::Buffer> keep;
    std::vector<glm::vec4> albedo;
    for (uint32_t t = 0; t < count; ++t) albedo.push_back({float(t), 0.5f, 0.25f, 0.0f});
    const vplkit::BufferView random = whole(keep, scene.vertex_random, "vertex random");
    const vplkit::BufferView entries = whole(keep, subdivision.entries, "entries");
    const vplkit::BufferView triangle_albedo = whole(keep, albedo, "triangle albedo");
    const vplkit::BufferView candidates =
        whole(keep, std::vector<FlcCandidate>(total), "candidates");  // zeros, all overwritten
    const vplkit::BufferView candidate_albedo = whole(keep, std::vector<glm::vec4>(total), "candidate albedo");
    vplkit::PassList passes("flc scene address");
    vplkit::stages::add_flc_candidates_pass(ctx, passes, {vertices, indices, random, candidates, addressed}, partition,
                                            count, 5);
    vplkit::stages::add_flc_subdivide_pass(
        ctx, passes, {vertices, indices, random, entries, candidates, triangle_albedo, candidate_albedo, addressed},
        partition, subdivision, count, 5);
    passes.run(ctx);
    return {keep[3].download<FlcCandidate>(total), keep[4].download<glm::vec4>(total)};
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

}  // namespace

TEST_CASE("flc scene address: candidates and sub-triangles read at addresses match the bindings'") {
    const vplkit::scene::Scene scene = cornell();
    REQUIRE(scene.vertex_random.size() == scene.vertices.size());
    // S~_N a small fraction of the box's face, so the walls' triangles are subdivided.
    const glm::vec3 extent = scene.bounds.extent();
    const float face = extent.x * extent.y;
    const vplkit::stages::FlcPartition partition{3, 0.02f * face, 0.1f * glm::length(extent), 2.0f};
    const vplkit::stages::FlcSubdivision subdivision =
        vplkit::stages::flc_subdivision_for(triangle_areas(scene), partition);
    REQUIRE_FALSE(subdivision.entries.empty());  // the subdivide pass reads the scene too

    std::vector<vplkit::Buffer> keep;
    const vplkit::BufferView bound_vertices = whole(keep, scene.vertices, "scene vertices");
    const vplkit::BufferView bound_indices = whole(keep, scene.indices, "scene indices");
    // A decoy vertex far outside the box, a decoy index its first vertex: reading either moves a
    // candidate. Odd decoy counts: offsets no storage binding could start at (37 x 72 bytes).
    vplkit::scene::Vertex decoy{};
    decoy.position = {1e3f, -1e3f, 1e3f};
    const vplkit::BufferView vertices = placed(keep, scene.vertices, decoy, 37, 5, "placed vertices");
    const vplkit::BufferView indices = placed(keep, scene.indices, 0u, 7, 4, "placed indices");

    const Candidates expected = run(scene, bound_vertices, bound_indices, false, partition, subdivision);
    const Candidates got = run(scene, vertices, indices, true, partition, subdivision);
    size_t kept = 0;
    for (const FlcCandidate& c : expected.candidates) kept += c.level >= 0;
    CHECK(kept > 0);  // the comparison means something
    CHECK(same_bytes(expected.candidates, got.candidates));
    CHECK(same_bytes(expected.albedo, got.albedo));
}

TEST_CASE("flc scene address: a scene past a binding's range must be addressed") {
    // A view the size of the range plus one vertex (the buffer behind it is small: the check
    // comes before anything is recorded).
    vplkit::Context& ctx = vplkit::test::context();
    const vplkit::scene::Scene scene = cornell();
    std::vector<vplkit::Buffer> keep;
    vplkit::BufferView vertices = whole(keep, scene.vertices, "scene vertices");
    vertices.size = ctx.info().max_storage_buffer_range + sizeof(vplkit::scene::Vertex);
    const vplkit::BufferView indices = whole(keep, scene.indices, "scene indices");
    const vplkit::BufferView random = whole(keep, scene.vertex_random, "vertex random");
    const vplkit::BufferView candidates = whole(keep, std::vector<FlcCandidate>(1), "candidates");
    const vplkit::stages::FlcPartition partition{3, 0.25f, 1.0f, 2.0f};
    vplkit::PassList passes("flc scene address refusal");
    vplkit::test::check_refused_past_range(ctx, {"flc candidates", "scene vertices"}, [&] {
        vplkit::stages::add_flc_candidates_pass(ctx, passes, {vertices, indices, random, candidates}, partition,
                                                uint32_t(scene.indices.size() / 3), 0);
    });
}
