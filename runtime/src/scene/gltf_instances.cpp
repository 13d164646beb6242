#include "scene/gltf_instances.hpp"

#include "scene/gltf_checks.hpp"
#include "scene/gltf_lights_cameras.hpp"
#include "scene/gltf_materials.hpp"
#include "scene/gltf_nodes.hpp"
#include "scene/gltf_pose.hpp"
#include "scene/gltf_primitives.hpp"

#include <algorithm>
#include <string>

namespace vplkit::scene::detail {

bool append_node_instances(const GltfSource& source, std::span<const Material> materials, uint32_t default_material,
                           DecodedMeshes& decoded, Scene& scene, bool primitives) {
    const tinygltf::Model& model = source.model;
    decoded.resize(model.meshes.size());
    bool default_material_used = false;
    const std::vector<NodeInstance> instances = traverse(source, scene.warnings);
    NodeWorlds worlds(source, instances);
    for (const NodeInstance& instance : instances) {
        const tinygltf::Node& node = model.nodes[size_t(instance.node)];
        const std::string node_label = "node " + std::to_string(instance.node) + quoted_name(node.name);
        if (node.camera >= 0) {
            check_index(source, node.camera, model.cameras, "camera", node_label);
            scene.cameras.push_back(convert_camera(source, node.camera, instance.world, node_label));
        }
        if (auto it = node.extensions.find(kLightsExtension); it != node.extensions.end()) {
            const tinygltf::Value& ext = it->second;
            if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsNumber()) {
                source.fail(node_label + ": " + kLightsExtension + " has no light index");
            }
            const int light = ext.Get("light").GetNumberAsInt();
            check_index(source, light, model.lights, "light", node_label);
            scene.lights.push_back(convert_light(source, light, instance.world, node_label));
        }
        if (node.mesh < 0 || !primitives) continue;
        check_index(source, node.mesh, model.meshes, "mesh", node_label);
        auto& primitives = decoded[size_t(node.mesh)];
        const tinygltf::Mesh& mesh = model.meshes[size_t(node.mesh)];
        if (!primitives) {
            primitives.emplace();
            for (size_t p = 0; p < mesh.primitives.size(); ++p) {
                primitives->push_back(decode_primitive(source, node.mesh, int(p), default_material, scene.warnings));
            }
        }
        const std::vector<double> weights = morph_weights(source, node, mesh, node_label);
        std::vector<glm::dmat4> joints;
        if (node.skin >= 0 && node.mesh >= 0) joints = joint_matrices(source, node.skin, worlds, node_label);
        for (size_t p = 0; p < primitives->size(); ++p) {
            if (!(*primitives)[p]) continue;
            const std::string where = node_label + " mesh " + std::to_string(node.mesh) + quoted_name(mesh.name) +
                                      " primitive " + std::to_string(p);
            // The still frame's pose: morphed, then skinned (world space; the node's own transform
            // is then ignored, glTF 2.0 3.7.3).
            const PrimitiveData* data = &*(*primitives)[p];
            std::optional<PrimitiveData> posed;
            glm::dmat4 world = instance.world;
            if (!data->targets.empty() &&
                std::any_of(weights.begin(), weights.end(), [](double w) { return w != 0; })) {
                if (weights.size() != data->targets.size()) {
                    source.fail(where + " has " + std::to_string(data->targets.size()) + " morph targets, but " +
                                std::to_string(weights.size()) + " weights are given");
                }
                posed = morphed(*data, weights);
                data = &*posed;
            }
            if (node.skin >= 0) {
                if (data->joint_sets.empty()) {
                    scene.warnings.messages.push_back(where +
                                                      " has a skin but no JOINTS_0: drawn with the node's transform");
                } else {
                    posed = skinned(source, *data, joints, where);
                    data = &*posed;
                    world = glm::dmat4(1.0);
                }
            }
            default_material_used |= data->material == default_material;
            if (data->material != default_material) {
                const std::string missing =
                    missing_tex_coords(materials[data->material], !data->uvs.empty(), !data->uvs1.empty());
                if (!missing.empty()) {
                    scene.warnings.messages.push_back(where + ": its material's textures read " + missing +
                                                      ", which the primitive lacks (read as (0, 0))");
                }
            }
            const bool wants_tangents =
                data->material != default_material && materials[data->material].normal_texture != kNoTexture;
            PrimitiveInstance info;
            info.node = uint32_t(instance.node);
            info.mesh = uint32_t(node.mesh);
            info.primitive = uint32_t(p);
            append_instance(source, scene, *data, world, wants_tangents, info, where);
        }
    }
    return default_material_used;
}

}  // namespace vplkit::scene::detail
