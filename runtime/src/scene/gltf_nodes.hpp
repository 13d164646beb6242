#pragma once
// The node tree: each node's local transform, the scene's traversal to world transforms, skins'
// joint matrices and the morph weights a node gives its mesh.

#include "scene/gltf_accessors.hpp"
#include "vplkit/scene.hpp"

#include <glm/mat4x4.hpp>

#include <optional>
#include <string>
#include <vector>

namespace vplkit::scene::detail {

// A node's TRS or matrix as one transform; fails naming `label` on a malformed or non-finite one.
glm::dmat4 local_transform(const GltfSource& source, const tinygltf::Node& node, const std::string& label);

struct NodeInstance {
    int node;
    glm::dmat4 world;
};

// Depth-first, pre-order (a parent before its children, children in the file's order), without
// recursion: a corrupt file's deep chain must not overflow the stack.
std::vector<NodeInstance> traverse(const GltfSource& source, LoadWarnings& warnings);

// World transforms of nodes: those the scene's traversal reached, and on demand any other (a
// skin's joint outside the scene) through its parents.
class NodeWorlds {
public:
    NodeWorlds(const GltfSource& source, const std::vector<NodeInstance>& instances);
    glm::dmat4 operator()(int node);

private:
    const GltfSource& source_;
    std::vector<int> parent_;
    std::vector<std::optional<glm::dmat4>> world_;
};

// Each joint's world transform times its inverse bind matrix (glTF 2.0 3.7.3): what a vertex
// bound to that joint is multiplied by. No inverseBindMatrices: identities.
std::vector<glm::dmat4> joint_matrices(const GltfSource& source, int skin_index, NodeWorlds& worlds,
                                       const std::string& node_label);

// The morph weights of a node's mesh: the node's, else the mesh's, else none (all zero).
std::vector<double> morph_weights(const GltfSource& source, const tinygltf::Node& node, const tinygltf::Mesh& mesh,
                                  const std::string& node_label);

}  // namespace vplkit::scene::detail
