#include "scene/gltf_pose.hpp"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <cmath>
#include <utility>
#include <vector>

namespace vplkit::scene::detail {

PrimitiveData morphed(const PrimitiveData& data, std::span<const double> weights) {
    PrimitiveData out = data;
    for (size_t t = 0; t < data.targets.size(); ++t) {
        const double w = weights[t];
        if (w == 0.0) continue;
        const MorphTarget& target = data.targets[t];
        // glTF 2.0 3.7.2.2: the morphed attribute is the base plus the weighted sum of displacements.
        for (size_t i = 0; i < target.positions.size(); ++i) {
            out.positions[i] = glm::vec3(glm::dvec3(out.positions[i]) + w * glm::dvec3(target.positions[i]));
        }
        if (!out.normals.empty()) {
            for (size_t i = 0; i < target.normals.size(); ++i) {
                out.normals[i] = glm::vec3(glm::dvec3(out.normals[i]) + w * glm::dvec3(target.normals[i]));
            }
        }
        if (!out.tangents.empty()) {
            for (size_t i = 0; i < target.tangents.size(); ++i) {
                const glm::vec3 xyz(glm::dvec3(out.tangents[i]) + w * glm::dvec3(target.tangents[i]));
                out.tangents[i] = glm::vec4(xyz, out.tangents[i].w);
            }
        }
    }
    return out;
}

PrimitiveData skinned(const GltfSource& source, const PrimitiveData& data, std::span<const glm::dmat4> joint_matrices,
                      const std::string& label) {
    PrimitiveData out = data;
    std::vector<bool> mirrors(data.positions.size(), false);
    for (size_t i = 0; i < data.positions.size(); ++i) {
        glm::dmat4 skin(0.0);
        double total = 0.0;
        for (const JointSet& set : data.joint_sets) {
            for (int k = 0; k < 4; ++k) {
                const double w = set.weights[i][k];
                if (w == 0.0) continue;  // an unused slot may name any joint, even joint 0 of an empty list
                const uint32_t joint = set.joints[i][k];
                if (joint >= joint_matrices.size()) {
                    source.fail(label + ": vertex " + std::to_string(i) + " names joint " + std::to_string(joint) +
                                ", but the skin has " + std::to_string(joint_matrices.size()) + " joints");
                }
                skin += w * joint_matrices[joint];
                total += w;
            }
        }
        if (!(total > 0.0)) {
            source.fail(label + ": vertex " + std::to_string(i) + " has no joint weight above 0, so no pose");
        }
        skin /= total;
        out.positions[i] = glm::vec3(skin * glm::dvec4(glm::dvec3(data.positions[i]), 1.0));
        const glm::dmat3 linear(skin);
        mirrors[i] = glm::determinant(linear) < 0.0;
        if (!out.normals.empty()) {
            // The inverse transpose up to a positive factor: the cofactor matrix keeps a singular
            // blend (joints scaled to zero) finite; append_instance renormalizes.
            // Columns b x c, c x a, a x b of the matrix (a, b, c) are det x its inverse transpose.
            const glm::dmat3 cofactor(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
                                      glm::cross(linear[0], linear[1]));
            const glm::dvec3 n = cofactor * glm::dvec3(data.normals[i]);
            out.normals[i] = glm::vec3(glm::determinant(linear) < 0.0 ? -n : n);
        }
        if (!out.tangents.empty()) {
            // A mirroring pose flips the handedness of the tangent frame, as a mirroring node does.
            const float w = mirrors[i] ? -data.tangents[i].w : data.tangents[i].w;
            out.tangents[i] = glm::vec4(glm::vec3(linear * glm::dvec3(data.tangents[i])), w);
        }
    }
    // A triangle whose corners are mirrored (most of them) turns clockwise: two corners are
    // swapped so it stays counter-clockwise on the side the file made its front.
    for (size_t t = 0; t + 2 < out.indices.size(); t += 3) {
        const int mirrored =
            int(mirrors[out.indices[t]]) + int(mirrors[out.indices[t + 1]]) + int(mirrors[out.indices[t + 2]]);
        if (mirrored >= 2) std::swap(out.indices[t + 1], out.indices[t + 2]);
    }
    return out;
}

}  // namespace vplkit::scene::detail
