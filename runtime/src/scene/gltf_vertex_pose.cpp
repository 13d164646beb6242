// The GPU pose's inputs from the loaded model: which instances can move (a static look at the
// animations' channels), their rest vertices and morph displacements, and per frame their matrices.

#include "scene/gltf_vertex_pose.hpp"

#include "scene/gltf_nodes.hpp"

#include <algorithm>
#include <string>

namespace vplkit::scene::detail {

namespace {

// Which nodes' world transforms, and which nodes' morph weights, some animation can change.
struct MovingNodes {
    std::vector<bool> transform;
    std::vector<bool> weights;
};

MovingNodes moving_nodes(const tinygltf::Model& model) {
    const size_t count = model.nodes.size();
    MovingNodes moving{std::vector<bool>(count, false), std::vector<bool>(count, false)};
    // Every animation, applied or not: a sequence may pick any (conservative: more moves, none missed).
    for (const tinygltf::Animation& animation : model.animations) {
        for (const tinygltf::AnimationChannel& channel : animation.channels) {
            const int node = channel.target_node;
            if (node < 0 || size_t(node) >= count) continue;
            if (channel.target_path == "weights") {
                moving.weights[size_t(node)] = true;
            } else {
                moving.transform[size_t(node)] = true;
            }
        }
    }
    // A moving node moves its descendants (the file is a tree: each child has one parent).
    std::vector<int> parent(count, -1);
    for (size_t n = 0; n < count; ++n) {
        for (int child : model.nodes[n].children) {
            if (child >= 0 && size_t(child) < count) parent[size_t(child)] = int(n);
        }
    }
    for (size_t n = 0; n < count; ++n) {
        size_t steps = 0;  // a corrupt file's cycle must not loop forever
        for (int p = parent[n]; p >= 0 && !moving.transform[n] && steps <= count; p = parent[size_t(p)], ++steps) {
            moving.transform[n] = moving.transform[size_t(p)];
        }
    }
    return moving;
}

std::string instance_name(const PrimitiveInstance& info) {
    return "node " + std::to_string(info.node) + " mesh " + std::to_string(info.mesh) + " primitive " +
           std::to_string(info.primitive);
}

shaders::vec3 to_vec3(glm::vec3 v) {
    return {v.x, v.y, v.z};
}

shaders::vec4 to_vec4(glm::vec4 v) {
    return {v.x, v.y, v.z, v.w};
}

}  // namespace

VertexPoseSetup vertex_pose_setup(const GltfSource& source, const DecodedMeshes& decoded, const Scene& scene) {
    const tinygltf::Model& model = source.model;
    const MovingNodes moving = moving_nodes(model);
    VertexPoseSetup setup;
    VertexPoseRest& rest = setup.rest;
    for (const PrimitiveInstance& info : scene.primitives) {
        const tinygltf::Node& node = model.nodes[info.node];
        const PrimitiveData& data = *(*decoded[info.mesh])[info.primitive];
        const bool skinned = node.skin >= 0 && !data.joint_sets.empty();
        bool moves = moving.weights[info.node] && !data.targets.empty();
        if (skinned) {
            const tinygltf::Skin& skin = model.skins[size_t(node.skin)];
            moves |= std::any_of(skin.joints.begin(), skin.joints.end(),
                                 [&](int joint) { return moving.transform[size_t(joint)]; });
        } else {
            moves |= moving.transform[info.node];
        }
        if (!moves) continue;
        std::string why;
        if (info.normals != NormalSource::file) {
            why = "its flat normals are made from the posed triangles";
        } else if (info.tangents == TangentSource::generated) {
            why = "its tangents are made from the posed triangles";
        } else if (skinned && data.joint_sets.size() > 1) {
            why = "it has more than 4 joint influences a vertex";
        } else if (info.vertex_count != data.positions.size()) {
            why = "the loader dropped some of its vertices";
        }
        if (!why.empty()) {
            if (setup.refusal.empty()) setup.refusal = instance_name(info) + " moves, but " + why;
            continue;
        }

        shaders::PoseInstance instance{};
        instance.first_rest_vertex = uint32_t(rest.vertices.size());
        instance.vertex_count = info.vertex_count;
        instance.first_matrix = rest.matrix_count;
        instance.skinned = skinned ? 1u : 0u;
        instance.first_delta = uint32_t(rest.deltas.size());
        instance.target_count = uint32_t(data.targets.size());
        instance.first_weight = rest.weight_count;
        instance.has_tangents = info.tangents == TangentSource::file ? 1u : 0u;
        const uint32_t index = uint32_t(rest.instances.size());
        for (uint32_t v = 0; v < info.vertex_count; ++v) {
            shaders::PoseRestVertex r{};
            r.position = to_vec3(data.positions[v]);
            r.instance = index;
            r.normal = to_vec3(data.normals[v]);
            r.vertex = info.first_vertex + v;
            if (instance.has_tangents) r.tangent = to_vec4(data.tangents[v]);
            if (skinned) {
                const glm::uvec4 j = data.joint_sets[0].joints[v];
                r.joints = {j.x, j.y, j.z, j.w};
                r.weights = to_vec4(data.joint_sets[0].weights[v]);
            }
            rest.vertices.push_back(r);
        }
        for (const MorphTarget& target : data.targets) {
            for (uint32_t v = 0; v < info.vertex_count; ++v) {
                shaders::MorphDelta d{};
                if (!target.positions.empty()) d.position = to_vec4(glm::vec4(target.positions[v], 0.0f));
                if (!target.normals.empty()) d.normal = to_vec4(glm::vec4(target.normals[v], 0.0f));
                if (!target.tangents.empty()) d.tangent = to_vec4(glm::vec4(target.tangents[v], 0.0f));
                rest.deltas.push_back(d);
            }
        }
        rest.matrix_count += skinned ? uint32_t(model.skins[size_t(node.skin)].joints.size()) : 1u;
        rest.weight_count += instance.target_count;
        rest.instances.push_back(instance);
        setup.sources.push_back({int(info.node), skinned ? node.skin : -1, int(info.mesh), instance.target_count});
    }
    return setup;
}

VertexPoseFrame vertex_pose_frame(const GltfSource& source, const VertexPoseSetup& setup) {
    const tinygltf::Model& model = source.model;
    LoadWarnings ignored;  // the traversal's warnings were given at load
    NodeWorlds worlds(source, traverse(source, ignored));
    VertexPoseFrame frame;
    frame.matrices.reserve(setup.rest.matrix_count);
    frame.morph_weights.reserve(setup.rest.weight_count);
    for (const VertexPoseSource& s : setup.sources) {
        const tinygltf::Node& node = model.nodes[size_t(s.node)];
        const std::string label = "node " + std::to_string(s.node);
        if (s.skin >= 0) {
            for (const glm::dmat4& m : joint_matrices(source, s.skin, worlds, label)) frame.matrices.emplace_back(m);
        } else {
            frame.matrices.emplace_back(worlds(s.node));
        }
        const std::vector<double> weights = morph_weights(source, node, model.meshes[size_t(s.mesh)], label);
        const bool any = std::any_of(weights.begin(), weights.end(), [](double w) { return w != 0.0; });
        if (any && weights.size() != s.target_count) {
            source.fail(label + " mesh " + std::to_string(s.mesh) + " has " + std::to_string(s.target_count) +
                        " morph targets, but " + std::to_string(weights.size()) + " weights are given");
        }
        for (uint32_t t = 0; t < s.target_count; ++t) frame.morph_weights.push_back(any ? float(weights[t]) : 0.0f);
    }
    return frame;
}

}  // namespace vplkit::scene::detail
