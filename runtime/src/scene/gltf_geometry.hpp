#pragma once
// Flattening one node's instance of one glTF primitive into the scene's world-space triangles:
// transform, winding, degenerate-triangle removal, flat normals where the file has none,
// tangents where a normal texture needs them.

#include "scene/gltf_accessors.hpp"
#include "vplkit/scene.hpp"

#include <glm/mat4x4.hpp>

#include <span>
#include <string>
#include <vector>

namespace vplkit::scene::detail {

// One morph target's displacements (glTF 2.0 3.7.2.2); an empty array: the target has none.
struct MorphTarget {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec3> tangents;  // xyz only: the handedness w is not morphed
};

// JOINTS_n / WEIGHTS_n: four joint indices (into the skin's joints) and their weights per vertex.
struct JointSet {
    std::vector<glm::uvec4> joints;
    std::vector<glm::vec4> weights;
};

// One glTF primitive decoded in its mesh's object space; every value finite, every index in range.
struct PrimitiveData {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;    // empty: the file has none
    std::vector<glm::vec4> tangents;   // empty: the file has none
    std::vector<glm::vec2> uvs;        // empty: the file has none
    std::vector<glm::vec2> uvs1;       // TEXCOORD_1; empty: the file has none
    std::vector<glm::vec4> colors;     // COLOR_0 as RGBA in [0, 1]; empty: the file has none
    std::vector<uint32_t> indices;     // 3 per triangle
    uint32_t material = 0;             // index into Scene::materials
    std::vector<MorphTarget> targets;  // each array as long as positions, or empty
    std::vector<JointSet> joint_sets;  // JOINTS_0/WEIGHTS_0, JOINTS_1/WEIGHTS_1, ...
};

// Appends `data` transformed by `world` (node to world) to `scene`: vertices, triangles, their
// materials and one PrimitiveInstance (`info` gives node, mesh, primitive; the rest is filled in).
// `wants_tangents`: the material has a normal texture. Counts dropped degenerate triangles,
// repaired normals and undefined tangents in scene.warnings. `where` names the instance for the
// error a non-finite transformed position raises.
void append_instance(const GltfSource& source, Scene& scene, const PrimitiveData& data, const glm::dmat4& world,
                     bool wants_tangents, PrimitiveInstance info, const std::string& where);

// Tangents for `vertices` (world space, unit normals) from the UVs of `triangles` (indices into
// `vertices`, 3 per triangle): each triangle's tangent and bitangent from its UV gradients
// (Lengyel's derivation: the edges e1, e2 satisfy e1 = du1 T + dv1 B, e2 = du2 T + dv2 B),
// averaged per vertex weighted by triangle area, Gram-Schmidt against the normal; w = -1 where
// the averaged bitangent points against cross(normal, tangent). Returns the number of vertices
// whose tangent is undefined (no triangle with non-degenerate UVs): those get an arbitrary unit
// vector orthogonal to the normal and w = +1.
uint32_t generate_tangents(std::span<Vertex> vertices, std::span<const uint32_t> triangles);

}  // namespace vplkit::scene::detail
