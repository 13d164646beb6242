// Scene::vertex_random (forward light cuts' per-vertex random integers, the FLC paper sec. 3): one per
// vertex, the same whatever transform the node applies (so a triangle's random number follows
// it when the mesh moves), different between two nodes instancing one mesh, and distinct within a
// mesh (a 32-bit hash of distinct inputs: a collision among a few vertices would be a bug).

#include "gltf_builder.hpp"
#include "vplkit/scene.hpp"

#include <doctest/doctest.h>

#include <set>

using namespace vplkit::scene;
using namespace scene_test;

namespace {

// The unit quad (with or without normals) instanced by node 0 with `transform` (a JSON fragment)
// and by node 1 untransformed.
fs::path write_quads(const fs::path& dir, const std::string& name, const std::string& transform, bool normals) {
    GltfBuilder b;
    b.mesh("[" + unit_quad(b, normals) + "]", "quad");
    b.node(R"({"mesh":0)" + transform + "}");
    b.node(R"({"mesh":0})");
    b.roots = {0, 1};
    return b.write(dir, name, true);
}

}  // namespace

TEST_CASE("vertex random: one per vertex, unchanged by the node's transform, distinct per instance") {
    TempDir dir("vertex_random");
    for (bool normals : {true, false}) {
        CAPTURE(normals);
        const std::string suffix = normals ? "" : "_flat";
        const Scene still = load_gltf(write_quads(dir.path(), "still" + suffix, "", normals));
        const Scene moved = load_gltf(write_quads(
            dir.path(), "moved" + suffix,
            R"(,"translation":[5,-3,2],"rotation":[0.2,0.4,0.1,0.8888194417315589],"scale":[3,0.5,2])", normals));
        const Scene mirrored = load_gltf(write_quads(dir.path(), "mirrored" + suffix, R"(,"scale":[-1,1,1])", normals));
        REQUIRE(still.vertex_random.size() == still.vertices.size());
        CHECK(moved.vertex_random == still.vertex_random);
        // Without normals a mirroring node's triangles list their own corners in swapped order.
        if (normals) CHECK(mirrored.vertex_random == still.vertex_random);
        CHECK(moved.vertices[0].position != still.vertices[0].position);

        // Per triangle, the xor of its corners (what the flc shader reads) is unchanged too, however
        // the mirroring node reordered the corners.
        for (size_t t = 0; t < still.triangle_count(); ++t) {
            auto triangle_bits = [t](const Scene& s) {
                return s.vertex_random[s.indices[3 * t]] ^ s.vertex_random[s.indices[3 * t + 1]] ^
                       s.vertex_random[s.indices[3 * t + 2]];
            };
            CHECK(triangle_bits(mirrored) == triangle_bits(still));
        }

        // Node 0's and node 1's copies of the quad: different numbers.
        const PrimitiveInstance& first = still.primitives.at(0);
        const PrimitiveInstance& second = still.primitives.at(1);
        REQUIRE(first.vertex_count == second.vertex_count);
        std::set<uint32_t> distinct(still.vertex_random.begin(), still.vertex_random.end());
        // Without normals each triangle has its own corners, which repeat the file's vertex (and number).
        CHECK(distinct.size() == (normals ? still.vertices.size() : 8u));
        CHECK(still.vertex_random[first.first_vertex] != still.vertex_random[second.first_vertex]);
    }
}
