#pragma once
// The pose of a primitive in the still frame: morph targets at the node's (else the mesh's)
// weights, then skinning by the joints' node transforms times their inverse bind matrices (glTF
// 2.0 3.7.2.2 and 3.7.3). Weights and transforms are the file's, or their animated values at the
// load's time (gltf_animation writes those into the nodes first).

#include "scene/gltf_geometry.hpp"

#include <glm/mat4x4.hpp>

#include <span>
#include <string>
#include <vector>

namespace vplkit::scene::detail {

// `data` with every target added at its weight: positions and normals (renormalized later,
// by append_instance) and tangents' xyz. weights.size() == data.targets.size().
PrimitiveData morphed(const PrimitiveData& data, std::span<const double> weights);

// `data` posed by its skin, in world space: each vertex by sum_k weight_k x joint_matrices[joint_k]
// (normals by that matrix's inverse transpose, tangents by its linear part), where
// joint_matrices[j] = world transform of joint j x its inverse bind matrix. Weights that do not
// sum to 1 are rescaled to 1 (exporters round them); a vertex whose weights are all 0 is an
// error naming `label`, as is a joint index outside the joints. Where the pose mirrors (negative
// determinant) the tangents' handedness flips and the triangles are rewound to stay
// counter-clockwise, as append_instance does for a mirroring node.
PrimitiveData skinned(const GltfSource& source, const PrimitiveData& data, std::span<const glm::dmat4> joint_matrices,
                      const std::string& label);

}  // namespace vplkit::scene::detail
