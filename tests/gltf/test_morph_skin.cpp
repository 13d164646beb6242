// The still frame's pose: morph targets at the file's default weights (node over mesh, sparse
// target accessors) and skins posed by their joints' node transforms times the inverse bind
// matrices (glTF 2.0 3.7.2.2, 3.7.3).
//
// Expectations: feature_files' morph_quad and skinned_quad, worked out by hand in their comments
// and below. Tolerance 1e-6: float arithmetic on values of order 1.

#include "feature_files.hpp"
#include "vplkit/scene.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <string>

namespace {

vplkit::scene::Scene load(const scene_test::GltfBuilder& b, const std::string& name) {
    scene_test::TempDir dir(name);
    return vplkit::scene::load_gltf(b.write(dir.path(), name, true));
}

void check_vertices(const vplkit::scene::Scene& scene, const std::vector<glm::vec3>& positions,
                    const std::vector<glm::vec3>& normals) {
    REQUIRE(scene.vertices.size() == positions.size());
    for (size_t v = 0; v < positions.size(); ++v) {
        CAPTURE(v);
        CHECK(glm::length(scene.vertices[v].position - positions[v]) <= 1e-6f);
        CHECK(glm::length(scene.vertices[v].normal - glm::normalize(normals[v])) <= 1e-6f);
    }
}

std::string load_error(const scene_test::GltfBuilder& b) {
    try {
        load(b, "bad");
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("gltf: a morph target at weight 0.5 moves the vertices half-way (sparse target, normals too)") {
    // Mesh weights (0.5, 0): target 0 lifts vertices 1 and 2 by half of 2, turns normals by half of (1, 0, -1).
    const auto scene = load(gltf_features::morph_quad(), "morph");
    CHECK(vplkit::scene::warning_lines(scene.warnings).empty());
    const glm::vec3 n(0.5f, 0.0f, 0.5f);
    check_vertices(scene, {{0, 0, 0}, {1, 0, 1}, {1, 1, 1}, {0, 1, 0}}, {n, n, n, n});
}

TEST_CASE("gltf: a node's morph weights take precedence over its mesh's") {
    // Node weights (0.25, 1): z + 0.5 on vertices 1 and 2, x + 1 everywhere.
    const auto scene = load(gltf_features::morph_quad({0.25f, 1.0f}), "morph_node");
    const glm::vec3 n(0.25f, 0.0f, 0.75f);
    check_vertices(scene, {{1, 0, 0}, {2, 0, 0.5f}, {2, 1, 0.5f}, {1, 1, 0}}, {n, n, n, n});
    // Weights that do not match the targets: one clear error.
    const std::string error = load_error(gltf_features::morph_quad({0.5f}));
    CHECK(error.find("has 2 morph targets, but 1 weights are given") != std::string::npos);
}

TEST_CASE("gltf: a morph target's TANGENT displacements turn the tangents (handedness kept)") {
    scene_test::GltfBuilder b;
    const int p = b.vec3s({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const int n = b.vec3s({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const int t = b.vec4s({{1, 0, 0, -1}, {1, 0, 0, -1}, {1, 0, 0, -1}, {1, 0, 0, -1}});
    const int dt = b.vec3s({{-1, 1, 0}, {-1, 1, 0}, {-1, 1, 0}, {-1, 1, 0}});
    const int i = b.indices({0, 1, 2, 0, 2, 3});
    b.meshes.push_back("{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(p) + ",\"NORMAL\":" +
                       std::to_string(n) + ",\"TANGENT\":" + std::to_string(t) + "},\"indices\":" + std::to_string(i) +
                       ",\"targets\":[{\"TANGENT\":" + std::to_string(dt) + "}]}],\"weights\":[0.5]}");
    b.roots.push_back(b.node("{\"mesh\":0}"));
    const auto scene = load(b, "morph_tangents");
    // (1, 0, 0) + 0.5 (-1, 1, 0) = (0.5, 0.5, 0), normalized; w stays -1.
    const float h = std::sqrt(0.5f);
    for (const auto& v : scene.vertices) CHECK(glm::length(v.tangent - glm::vec4(h, h, 0, -1)) <= 1e-6f);
}

TEST_CASE("gltf: a skinned quad is posed by its rotated joint, blended where a vertex has two joints") {
    // Arm rotated 90 degrees about +Y at (0.5, 0, 0): vertex 1 (1, 0, 0) -> (0.5, 0, -0.5), normal
    // (1, 0, 0); vertex 2 half hip, half arm: (0.5 (1, 1, 0) + 0.5 (0.5, 1, -0.5)), normal by the
    // blend's inverse transpose: (1, 0, 1) / sqrt 2. The mesh node's translation (5, 5, 5) is ignored.
    for (bool short_joints : {false, true}) {
        CAPTURE(short_joints);
        const auto scene = load(gltf_features::skinned_quad(90.0f, short_joints), "skinned");
        CHECK(vplkit::scene::warning_lines(scene.warnings).empty());
        const glm::vec3 z(0, 0, 1);
        check_vertices(scene, {{0, 0, 0}, {0.5f, 0, -0.5f}, {0.75f, 1, -0.25f}, {0, 1, 0}},
                       {z, {1, 0, 0}, {1, 0, 1}, z});
    }
}

namespace {

// Every triangle counter-clockwise on the side its vertex normals point to (the file's front).
void check_front_faces(const vplkit::scene::Scene& scene) {
    for (size_t t = 0; t < scene.triangle_count(); ++t) {
        const auto& a = scene.vertices[scene.indices[3 * t]];
        const auto& b = scene.vertices[scene.indices[3 * t + 1]];
        const auto& c = scene.vertices[scene.indices[3 * t + 2]];
        const glm::vec3 face = glm::cross(b.position - a.position, c.position - a.position);
        CHECK(glm::dot(face, a.normal + b.normal + c.normal) > 0.0f);
    }
}

}  // namespace

TEST_CASE("gltf: a mirroring skin keeps the file's front faces counter-clockwise") {
    const auto plain = load(gltf_features::skinned_quad(90.0f), "skinned");
    check_front_faces(plain);
    const auto mirrored = load(gltf_features::skinned_quad(90.0f, false, true), "mirrored");
    REQUIRE(mirrored.vertices.size() == plain.vertices.size());
    for (size_t v = 0; v < plain.vertices.size(); ++v) {
        const glm::vec3 flip(-1, 1, 1);
        CHECK(glm::length(mirrored.vertices[v].position - flip * plain.vertices[v].position) <= 1e-6f);
        CHECK(glm::length(mirrored.vertices[v].normal - flip * plain.vertices[v].normal) <= 1e-6f);
    }
    check_front_faces(mirrored);
}

TEST_CASE("gltf: a skin whose joints are in their bind pose draws the mesh as it is stored") {
    const auto scene = load(gltf_features::skinned_quad(0.0f), "bind_pose");
    const glm::vec3 z(0, 0, 1);
    check_vertices(scene, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {z, z, z, z});
}
