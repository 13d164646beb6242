// Attributes the loader generates: flat normals where a primitive has no NORMAL, tangents where
// a normal-textured material has no TANGENT, and file tangents under a mirroring transform.
// Expected values are worked out by hand in the comments; tolerance 1e-5 (double arithmetic
// rounded to float once).

#include "gltf_builder.hpp"
#include "vplkit/scene.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <cmath>

using namespace vplkit::scene;
using namespace scene_test;

namespace {

constexpr float kTolerance = 1e-5f;

bool near(glm::vec3 a, glm::vec3 b) {
    return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(kTolerance)));
}
bool near(glm::vec4 a, glm::vec4 b) {
    return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec4(kTolerance)));
}

// A material with a normal texture (a 1x1 PNG written next to the file): what makes the loader
// generate tangents.
void add_normal_mapped_material(GltfBuilder& b) {
    const std::vector<uint8_t> flat_normal = png(1, 1, {128, 128, 255, 255});
    b.image_view(flat_normal);
    b.textures.push_back(R"({"source":0})");
    b.materials.push_back(R"({"name":"bumpy","normalTexture":{"index":0}})");
}

}  // namespace

TEST_CASE("flat normals are generated per face when a primitive has no NORMAL") {
    TempDir dir("flat_normals");
    GltfBuilder b;
    // Two triangles sharing the edge (0,0,0)-(1,0,0): [0,1,2] in z = 0 (face normal +z) and
    // [0,3,1] in y = 0 ((0,0,1) x (1,0,0) = +y).
    const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
    const int i = b.indices({0, 1, 2, 0, 3, 1});
    b.mesh("[" + primitive(p, -1, -1, -1, i) + "]");
    b.node(R"({"mesh":0})");
    // The same mesh mirrored in x: the faces must still point to +z and +y, which needs the
    // reversed winding.
    b.node(R"({"mesh":0,"scale":[-1,1,1],"translation":[5,0,0]})");
    b.roots = {0, 1};
    const Scene s = load_gltf(b.write(dir.path(), "flat"));
    REQUIRE(s.primitives.size() == 2);
    for (const PrimitiveInstance& prim : s.primitives) {
        CHECK(prim.normals == NormalSource::generated_flat);
        CHECK(prim.tangents == TangentSource::none);
        CHECK(prim.vertex_count == 6);  // vertices are not shared between flat faces
        REQUIRE(prim.triangle_count == 2);
        for (int k = 0; k < 3; ++k) {
            CHECK(near(s.vertices[s.indices[3 * prim.first_triangle + k]].normal, {0, 0, 1}));
            CHECK(near(s.vertices[s.indices[3 * prim.first_triangle + 3 + k]].normal, {0, 1, 0}));
        }
    }
    CHECK(s.primitives[1].mirrored);
    // The first face's corners in world space: (5,0,0), then (5,1,0) and (4,0,0) swapped.
    const uint32_t t = s.primitives[1].first_triangle;
    CHECK(near(s.vertices[s.indices[3 * t]].position, {5, 0, 0}));
    CHECK(near(s.vertices[s.indices[3 * t + 1]].position, {5, 1, 0}));
    CHECK(near(s.vertices[s.indices[3 * t + 2]].position, {4, 0, 0}));
}

TEST_CASE("generated tangents follow +u with the glTF bitangent sign") {
    TempDir dir("tangents_quad");
    GltfBuilder b;
    add_normal_mapped_material(b);
    // unit_quad: UV (x, 1 - y), so dP/du = +x and v grows toward -y. The bitangent
    // w * cross(n, t) = w * (+y) must point where v decreases (+y): w = +1.
    b.mesh("[" + unit_quad(b, true, true, 0) + "]");
    // Mirrored UVs (1 - x, 1 - y): dP/du = -x, cross(+z, -x) = -y, so w = -1.
    const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const int n = b.vec3s({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const int uv = b.vec2s({{1, 1}, {0, 1}, {0, 0}, {1, 0}});
    const int i = b.indices({0, 1, 2, 0, 2, 3});
    b.mesh("[" + primitive(p, n, uv, -1, i, 0) + "]");
    b.node(R"({"mesh":0})");
    b.node(R"({"mesh":1,"translation":[2,0,0]})");
    b.roots = {0, 1};
    const Scene s = load_gltf(b.write(dir.path(), "quads"));
    REQUIRE(s.primitives.size() == 2);
    CHECK(s.primitives[0].tangents == TangentSource::generated);
    CHECK(s.primitives[1].tangents == TangentSource::generated);
    CHECK(s.warnings.untangented_vertices == 0);
    for (uint32_t v = 0; v < 4; ++v) {
        CHECK(near(s.vertices[s.primitives[0].first_vertex + v].tangent, {1, 0, 0, 1}));
        CHECK(near(s.vertices[s.primitives[1].first_vertex + v].tangent, {-1, 0, 0, -1}));
    }
}

TEST_CASE("generated tangents average over triangles by area") {
    TempDir dir("tangents_fan");
    GltfBuilder b;
    add_normal_mapped_material(b);
    // Two triangles in z = 0 sharing only vertex 0:
    //   A = [0,1,2], (0,0,0) (1,0,0) (0,1,0), UV (0,1) (1,1) (0,0): dP/du = +x, area 1/2.
    //   B = [0,3,4], (0,0,0) (-2,0,0) (0,-2,0), UV (0,1) (0,0) (-1,1): dP/du = +y (solving
    //   e1 = (-2,0,0) = 0 T - 1 B', e2 = (0,-2,0) = -1 T + 0 B' gives T = (0,2,0), B' = (2,0,0)),
    //   area 2.
    // Vertex 0: normalize(1/2 (1,0,0) + 2 (0,1,0)) = (1, 4, 0) / sqrt(17). Its averaged dP/dv is
    // 1/2 (0,-1,0) + 2 (1,0,0); cross(+z, t) = (-4, 1, 0) / sqrt(17) points against it: w = +1.
    // The other vertices carry their one triangle's tangent: +x for 1 and 2, +y for 3 and 4.
    const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-2, 0, 0}, {0, -2, 0}});
    const int n = b.vec3s({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const int uv = b.vec2s({{0, 1}, {1, 1}, {0, 0}, {0, 0}, {-1, 1}});
    const int i = b.indices({0, 1, 2, 0, 3, 4});
    b.mesh("[" + primitive(p, n, uv, -1, i, 0) + "]");
    b.node(R"({"mesh":0})");
    b.roots = {0};
    const Scene s = load_gltf(b.write(dir.path(), "fan"));
    REQUIRE(s.vertices.size() == 5);
    const float r17 = 1.0f / std::sqrt(17.0f);
    CHECK(near(s.vertices[0].tangent, {r17, 4 * r17, 0, 1}));
    CHECK(near(s.vertices[1].tangent, {1, 0, 0, 1}));
    CHECK(near(s.vertices[2].tangent, {1, 0, 0, 1}));
    CHECK(near(s.vertices[3].tangent, {0, 1, 0, 1}));
    CHECK(near(s.vertices[4].tangent, {0, 1, 0, 1}));
}

TEST_CASE("generated tangents are made orthogonal to a tilted normal") {
    TempDir dir("tangents_tilted");
    GltfBuilder b;
    add_normal_mapped_material(b);
    // The unit quad (dP/du = +x) with file normals (1,0,1)/sqrt2: Gram-Schmidt gives
    // x - n (n . x) = (1/2, 0, -1/2), normalized (1,0,-1)/sqrt2.
    const float h = float(std::sqrt(0.5));
    const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const int n = b.vec3s({{h, 0, h}, {h, 0, h}, {h, 0, h}, {h, 0, h}});
    const int uv = b.vec2s({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    const int i = b.indices({0, 1, 2, 0, 2, 3});
    b.mesh("[" + primitive(p, n, uv, -1, i, 0) + "]");
    b.node(R"({"mesh":0})");
    b.roots = {0};
    const Scene s = load_gltf(b.write(dir.path(), "tilted"));
    for (const Vertex& v : s.vertices) CHECK(near(v.tangent, {h, 0, -h, 1}));
}

TEST_CASE("tangents without UVs are counted and still orthogonal to the normal") {
    TempDir dir("tangents_no_uv");
    GltfBuilder b;
    add_normal_mapped_material(b);
    b.mesh("[" + unit_quad(b, true, false, 0) + "]");
    b.node(R"({"mesh":0})");
    b.roots = {0};
    const Scene s = load_gltf(b.write(dir.path(), "no_uv"));
    CHECK(s.warnings.untangented_vertices == 4);
    for (const Vertex& v : s.vertices) {
        CHECK(std::abs(glm::dot(glm::vec3(v.tangent), v.normal)) < kTolerance);
        CHECK(std::abs(glm::length(glm::vec3(v.tangent)) - 1.0f) < kTolerance);
        CHECK(v.tangent.w == 1.0f);
    }
}

TEST_CASE("file tangents are transformed and a mirror flips their handedness") {
    TempDir dir("tangents_file");
    GltfBuilder b;
    const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const int n = b.vec3s({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const int t = b.vec4s({{1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, 1}});
    const int i = b.indices({0, 1, 2, 0, 2, 3});
    b.mesh("[" + primitive(p, n, -1, t, i) + "]");
    b.node(R"({"mesh":0,"scale":[3,1,1]})");   // stretched: tangent stays +x, w stays +1
    b.node(R"({"mesh":0,"scale":[-1,1,1]})");  // mirrored: tangent -x, and w = -1 so that the
                                               // bitangent w * cross(+z, -x) = +y is unchanged
    b.roots = {0, 1};
    const Scene s = load_gltf(b.write(dir.path(), "file_tangents"));
    REQUIRE(s.primitives.size() == 2);
    CHECK(s.primitives[0].tangents == TangentSource::file);
    for (uint32_t v = 0; v < 4; ++v) {
        CHECK(near(s.vertices[s.primitives[0].first_vertex + v].tangent, {1, 0, 0, 1}));
        CHECK(near(s.vertices[s.primitives[1].first_vertex + v].tangent, {-1, 0, 0, -1}));
    }
}
