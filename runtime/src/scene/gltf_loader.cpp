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
#include "scene/gltf_instances.hpp"
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

namespace vplkit::scene::detail {

Scene scene_from_model(const std::filesystem::path& path, tinygltf::Model& model, const CapturedImages& captured,
                       const std::string& warn, const LoadOptions& options, DecodedMeshes& decoded) {
    const std::string file = path.string();
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
    const bool default_material_used =
        detail::append_node_instances(source, scene.materials, default_material, decoded, scene);
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

}  // namespace vplkit::scene::detail

namespace vplkit::scene {

Scene load_gltf(const std::filesystem::path& path, const LoadOptions& options) {
    detail::CapturedImages captured;
    std::string warn;
    tinygltf::Model model = detail::read_gltf_file(path, captured, warn);
    detail::DecodedMeshes decoded;
    return detail::scene_from_model(path, model, captured, warn, options, decoded);
}

}  // namespace vplkit::scene
