// The node tree, walked without recursion, every transform checked before it is used.

#include "scene/gltf_nodes.hpp"

#include "scene/gltf_checks.hpp"

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <utility>

namespace vplkit::scene::detail {

glm::dmat4 local_transform(const GltfSource& source, const tinygltf::Node& node, const std::string& label) {
    auto check_finite = [&](const std::vector<double>& values, const char* what) {
        for (double v : values) {
            if (!finite(v)) source.fail(label + ": " + what + " is not finite");
        }
    };
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) source.fail(label + ": matrix does not have 16 components");
        check_finite(node.matrix, "matrix");
        glm::dmat4 m;
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[size_t(4 * c + r)];  // column-major
        }
        return m;
    }
    glm::dmat4 t(1.0), r(1.0), s(1.0);
    if (!node.translation.empty()) {
        if (node.translation.size() != 3) source.fail(label + ": translation does not have 3 components");
        check_finite(node.translation, "translation");
        t[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4) source.fail(label + ": rotation does not have 4 components");
        check_finite(node.rotation, "rotation");
        // glTF stores (x, y, z, w); glm's constructor takes w first.
        glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        const double length = glm::length(q);
        if (!(length > 0.0)) source.fail(label + ": rotation quaternion is zero");
        r = glm::mat4_cast(q / length);
    }
    if (!node.scale.empty()) {
        if (node.scale.size() != 3) source.fail(label + ": scale does not have 3 components");
        check_finite(node.scale, "scale");
        s = glm::dmat4(glm::dvec4(node.scale[0], 0, 0, 0), glm::dvec4(0, node.scale[1], 0, 0),
                       glm::dvec4(0, 0, node.scale[2], 0), glm::dvec4(0, 0, 0, 1));
    }
    return t * r * s;
}

// Depth-first, pre-order (a parent before its children, children in the file's order), without
// recursion: a corrupt file's deep chain must not overflow the stack.
std::vector<NodeInstance> traverse(const GltfSource& source, LoadWarnings& warnings) {
    const auto& model = source.model;
    std::vector<int> roots;
    if (!model.scenes.empty()) {
        int scene = model.defaultScene;
        if (scene < 0) scene = 0;
        check_index(source, scene, model.scenes, "scene", "the default scene");
        roots = model.scenes[size_t(scene)].nodes;
        if (model.scenes.size() > 1) {
            warnings.messages.push_back("the file has " + std::to_string(model.scenes.size()) +
                                        " scenes; loaded scene " + std::to_string(scene));
        }
    } else {
        // No scene: every node nobody lists as a child is a root.
        std::vector<bool> is_child(model.nodes.size(), false);
        for (const auto& node : model.nodes) {
            for (int child : node.children) {
                if (child >= 0 && size_t(child) < model.nodes.size()) is_child[size_t(child)] = true;
            }
        }
        for (size_t i = 0; i < model.nodes.size(); ++i) {
            if (!is_child[i]) roots.push_back(int(i));
        }
    }

    std::vector<NodeInstance> out;
    std::vector<bool> seen(model.nodes.size(), false);
    std::vector<std::pair<int, glm::dmat4>> stack;
    std::vector<std::string> referrer;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
        check_index(source, *it, model.nodes, "node", "the scene");
        stack.emplace_back(*it, glm::dmat4(1.0));
    }
    while (!stack.empty()) {
        const auto [index, parent] = stack.back();
        stack.pop_back();
        const tinygltf::Node& node = model.nodes[size_t(index)];
        const std::string label = "node " + std::to_string(index) + quoted_name(node.name);
        if (seen[size_t(index)]) {
            source.fail(label +
                        " appears twice in the node hierarchy (glTF 2.0 requires disjoint trees: a cycle "
                        "or a node with two parents)");
        }
        seen[size_t(index)] = true;
        const glm::dmat4 world = parent * local_transform(source, node, label);
        out.push_back({index, world});
        for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) {
            check_index(source, *child, model.nodes, "node", label + " (as a child)");
            stack.emplace_back(*child, world);
        }
    }
    return out;
}

NodeWorlds::NodeWorlds(const GltfSource& source, const std::vector<NodeInstance>& instances)
    : source_(source), parent_(source.model.nodes.size(), -1), world_(source.model.nodes.size()) {
    const auto& nodes = source.model.nodes;
    for (size_t i = 0; i < nodes.size(); ++i) {
        for (int child : nodes[i].children) {
            if (child >= 0 && size_t(child) < nodes.size() && parent_[size_t(child)] < 0) {
                parent_[size_t(child)] = int(i);
            }
        }
    }
    for (const NodeInstance& instance : instances) world_[size_t(instance.node)] = instance.world;
}

glm::dmat4 NodeWorlds::operator()(int node) {
    std::vector<int> chain;  // nodes without a known world, from `node` up
    glm::dmat4 base(1.0);
    for (int n = node;;) {
        if (world_[size_t(n)]) {
            base = *world_[size_t(n)];
            break;
        }
        chain.push_back(n);
        if (chain.size() > parent_.size()) source_.fail("node " + std::to_string(node) + " has a cycle above it");
        if (parent_[size_t(n)] < 0) break;
        n = parent_[size_t(n)];
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
        const tinygltf::Node& n = source_.model.nodes[size_t(*it)];
        base = base * local_transform(source_, n, "node " + std::to_string(*it) + quoted_name(n.name));
        world_[size_t(*it)] = base;
    }
    return base;
}

// Each joint's world transform times its inverse bind matrix (glTF 2.0 3.7.3): what a vertex
// bound to that joint is multiplied by. No inverseBindMatrices: identities.
std::vector<glm::dmat4> joint_matrices(const GltfSource& source, int skin_index, NodeWorlds& worlds,
                                       const std::string& node_label) {
    check_index(source, skin_index, source.model.skins, "skin", node_label);
    const tinygltf::Skin& skin = source.model.skins[size_t(skin_index)];
    const std::string label = "skin " + std::to_string(skin_index) + quoted_name(skin.name);
    if (skin.joints.empty()) source.fail(label + " has no joints");
    std::vector<glm::mat4> inverse_bind(skin.joints.size(), glm::mat4(1.0f));
    if (skin.inverseBindMatrices >= 0) {
        inverse_bind = detail::read_mat4s(source, skin.inverseBindMatrices, "inverseBindMatrices of " + label);
        if (inverse_bind.size() < skin.joints.size()) {
            source.fail(label + " has " + std::to_string(skin.joints.size()) + " joints but " +
                        std::to_string(inverse_bind.size()) + " inverse bind matrices");
        }
        for (const glm::mat4& m : inverse_bind) {
            for (int c = 0; c < 4; ++c) {
                for (int r = 0; r < 4; ++r) {
                    if (!std::isfinite(m[c][r])) source.fail(label + ": an inverse bind matrix is not finite");
                }
            }
        }
    }
    std::vector<glm::dmat4> out;
    for (size_t j = 0; j < skin.joints.size(); ++j) {
        check_index(source, skin.joints[j], source.model.nodes, "node", label + " (joint " + std::to_string(j) + ")");
        out.push_back(worlds(skin.joints[j]) * glm::dmat4(inverse_bind[j]));
    }
    return out;
}

// The morph weights of a node's mesh: the node's, else the mesh's, else none (all zero).
std::vector<double> morph_weights(const GltfSource& source, const tinygltf::Node& node, const tinygltf::Mesh& mesh,
                                  const std::string& node_label) {
    const std::vector<double>& weights = !node.weights.empty() ? node.weights : mesh.weights;
    for (double w : weights) {
        if (!finite(w)) source.fail(node_label + ": a morph target weight is not finite");
    }
    return weights;
}

}  // namespace vplkit::scene::detail
