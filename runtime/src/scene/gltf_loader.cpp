// load_gltf: tinygltf parses the file and loads its buffers; everything it does not check
// (indices into arrays, accessor and bufferView bounds, finite values, required extensions) is
// checked before the data is used, and each failure is one Error naming file and problem. The
// jobs live in their own files: gltf_file (reading, extensions), gltf_animation (the nodes posed
// at the time asked for, gltf_animation_sampler interpolating), gltf_materials (materials and
// textures), gltf_nodes (the node tree, skins, morph weights), gltf_primitives (decoding),
// gltf_lights_cameras, gltf_pose (morphing and skinning), gltf_geometry (world-space triangles),
// gltf_images (decoding the images materials use). This file puts them together.

#include "scene/gltf_accessors.hpp"
#include "scene/gltf_animation.hpp"
#include "scene/gltf_checks.hpp"
#include "scene/gltf_file.hpp"
#include "scene/gltf_geometry.hpp"
#include "scene/gltf_images.hpp"
#include "scene/gltf_lights_cameras.hpp"
#include "scene/gltf_materials.hpp"
#include "scene/gltf_nodes.hpp"
#include "scene/gltf_pose.hpp"
#include "scene/gltf_primitives.hpp"
#include "vplkit/error.hpp"
#include "vplkit/scene.hpp"

#include <algorithm>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace vplkit::scene {
namespace {

using detail::check_index;
using detail::convert_camera;
using detail::convert_light;
using detail::decode_primitive;
using detail::GltfSource;
using detail::joint_matrices;
using detail::kLightsExtension;
using detail::missing_tex_coords;
using detail::morph_weights;
using detail::NodeInstance;
using detail::NodeWorlds;
using detail::PrimitiveData;
using detail::quoted_name;

}  // namespace

Scene load_gltf(const std::filesystem::path& path, const LoadOptions& options) {
    const std::string file = path.string();
    detail::CapturedImages captured;
    std::string warn;
    tinygltf::Model model = detail::read_gltf_file(path, captured, warn);
    const GltfSource source{model, file};

    Scene scene;
    scene.source = path;
    {
        std::istringstream lines(warn);
        for (std::string line; std::getline(lines, line);) {
            if (!line.empty()) scene.warnings.messages.push_back("tinygltf: " + line);
        }
    }
    detail::check_extensions(source, scene.warnings);
    // Posed first: from here on the nodes' TRS and weights are their values at options.time.
    scene.animations = detail::pose_animations(source, model, options, scene.time, scene.warnings);

    // Materials first: a primitive's need for tangents depends on its material's normal texture.
    detail::TextureTable textures(source);
    for (size_t m = 0; m < model.materials.size(); ++m) {
        scene.materials.push_back(detail::convert_material(source, int(m), textures, scene.warnings));
    }
    const uint32_t default_material = uint32_t(model.materials.size());
    bool default_material_used = false;

    std::vector<std::optional<std::vector<std::optional<PrimitiveData>>>> decoded(model.meshes.size());
    const std::vector<NodeInstance> instances = detail::traverse(source, scene.warnings);
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
        if (node.mesh < 0) continue;
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
                posed = detail::morphed(*data, weights);
                data = &*posed;
            }
            if (node.skin >= 0) {
                if (data->joint_sets.empty()) {
                    scene.warnings.messages.push_back(where +
                                                      " has a skin but no JOINTS_0: drawn with the node's transform");
                } else {
                    posed = detail::skinned(source, *data, joints, where);
                    data = &*posed;
                    world = glm::dmat4(1.0);
                }
            }
            default_material_used |= data->material == default_material;
            if (data->material != default_material) {
                const std::string missing =
                    missing_tex_coords(scene.materials[data->material], !data->uvs.empty(), !data->uvs1.empty());
                if (!missing.empty()) {
                    scene.warnings.messages.push_back(where + ": its material's textures read " + missing +
                                                      ", which the primitive lacks (read as (0, 0))");
                }
            }
            const bool wants_tangents =
                data->material != default_material && scene.materials[data->material].normal_texture != kNoTexture;
            PrimitiveInstance info;
            info.node = uint32_t(instance.node);
            info.mesh = uint32_t(node.mesh);
            info.primitive = uint32_t(p);
            detail::append_instance(source, scene, *data, world, wants_tangents, info, where);
        }
    }
    if (scene.indices.empty()) {
        std::string why = "no triangles to render";
        if (scene.warnings.skipped_primitives) {
            why += " (" + std::to_string(scene.warnings.skipped_primitives) + " non-triangle primitive(s) skipped)";
        }
        if (scene.warnings.degenerate_triangles) {
            why += " (" + std::to_string(scene.warnings.degenerate_triangles) + " degenerate triangle(s) dropped)";
        }
        source.fail(why);
    }
    if (default_material_used) {
        Material fallback;  // glTF 2.0's default material: the member defaults
        fallback.name = "default";
        scene.materials.push_back(fallback);
    }

    scene.textures = textures.take_textures();
    scene.images = detail::decode_images(source, captured, textures.image_uses(), path.parent_path());

    scene.bounds.min = glm::vec3(std::numeric_limits<float>::max());
    scene.bounds.max = glm::vec3(std::numeric_limits<float>::lowest());
    for (uint32_t i : scene.indices) {
        scene.bounds.min = glm::min(scene.bounds.min, scene.vertices[i].position);
        scene.bounds.max = glm::max(scene.bounds.max, scene.vertices[i].position);
    }
    for (size_t t = 0; t < scene.triangle_materials.size(); ++t) {
        if (scene.materials[scene.triangle_materials[t]].emits()) scene.emissive_triangles.push_back(uint32_t(t));
    }

    const size_t file_cameras = scene.cameras.size();
    if (options.camera && *options.camera >= file_cameras) {
        source.fail("camera " + std::to_string(*options.camera) + " was asked for, but the file has " +
                    (file_cameras == 0
                         ? std::string("no camera")
                         : std::to_string(file_cameras) + " (0.." + std::to_string(file_cameras - 1) + ")"));
    }
    if (scene.cameras.empty()) scene.cameras.push_back(framing_camera(scene.bounds));
    scene.active_camera = options.camera.value_or(0);
    return scene;
}

}  // namespace vplkit::scene
