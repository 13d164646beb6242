#pragma once
// Every node of the scene's traversal flattened into the Scene: its camera, its light and its
// mesh's primitives posed (morphed, skinned) in world space, in traversal order. load_gltf and
// the re-pose (vplkit/scene_pose.hpp) both call it, so a scene posed again at t is the scene
// loaded at t.

#include "scene/gltf_accessors.hpp"
#include "scene/gltf_geometry.hpp"
#include "scene/gltf_images.hpp"
#include "vplkit/scene.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <optional>
#include <span>
#include <vector>

namespace vplkit::scene::detail {

// Each mesh's primitives decoded in object space, on first use (nullopt: not yet decoded; a
// primitive that is skipped stays nullopt within its mesh). Kept between poses: decoding does not
// depend on the pose.
using DecodedMeshes = std::vector<std::optional<std::vector<std::optional<PrimitiveData>>>>;

// Appends to `scene` the cameras, lights, vertices, triangles and primitive instances of the
// model's nodes as they stand (posed by pose_animations). `materials` are the file's (without the
// default one, whose index is `default_material`). Returns whether some primitive uses the
// default material. Fails naming the node for a bad camera, light, mesh or morph weight count.
// Without `primitives`, only cameras and lights are appended (a pose whose vertices the GPU poses).
bool append_node_instances(const GltfSource& source, std::span<const Material> materials, uint32_t default_material,
                           DecodedMeshes& decoded, Scene& scene, bool primitives = true);

// load_gltf after reading the file: `model` is posed in place (its nodes take the animations'
// values at options.time), `decoded` keeps the decoded primitives for a later pose.
Scene scene_from_model(const std::filesystem::path& path, tinygltf::Model& model, const CapturedImages& captured,
                       const std::string& warn, const LoadOptions& options, DecodedMeshes& decoded);

}  // namespace vplkit::scene::detail
