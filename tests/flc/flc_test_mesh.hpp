#pragma once
// Small triangle meshes for the flc tests and the candidate pass run on them.

#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/flc.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace flc_test {

struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;  // 3 per triangle
    std::vector<uint32_t> random;   // one per position (scene::vertex_random_value of mesh 0)
    uint32_t triangle_count() const { return uint32_t(indices.size() / 3); }
};

// n x n squares of side `cell` in z = 0, facing +z, two triangles each (shared vertices).
Mesh grid(uint32_t n, float cell);
// Appends one triangle with its own three vertices.
void add_triangle(Mesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c);
// The mesh with every position moved by `transform` (random integers kept).
Mesh transformed(const Mesh& mesh, const glm::mat4& transform);

// Runs flc_candidates.comp on `mesh`.
std::vector<vplkit::shaders::FlcCandidate> run_candidates(const Mesh& mesh,
                                                          const vplkit::stages::FlcPartition& partition, uint32_t seed);

// The uniform number flc_candidates.comp draws for triangle t, in double.
double triangle_u(const Mesh& mesh, uint32_t t, uint32_t seed);

}  // namespace flc_test
