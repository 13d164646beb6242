#pragma once
// KHR_lights_punctual lights and glTF cameras, placed by the world transform of the node that
// carries them.

#include "scene/gltf_accessors.hpp"
#include "vplkit/scene.hpp"

#include <glm/mat4x4.hpp>

#include <string>

namespace vplkit::scene::detail {

// Light `index` of the file (checked to exist) on a node with world transform `world`; the light
// shines along the node's -Z. `node_label` names that node in messages.
Light convert_light(const GltfSource& source, int index, const glm::dmat4& world, const std::string& node_label);

// Camera `index` of the file (checked to exist) on a node with world transform `world`; it looks
// along the node's -Z with +Y up. `node_label` names that node in messages.
Camera convert_camera(const GltfSource& source, int index, const glm::dmat4& world, const std::string& node_label);

}  // namespace vplkit::scene::detail
