#pragma once
// The file's animations read and checked (glTF 2.0 3.11), and the nodes posed at a time: each
// animated node's translation, rotation, scale or morph weights replaced by the channel's value
// at t, so the rest of the loader (node tree, skins, morphs, lights, cameras) reads a posed file.

#include "scene/gltf_accessors.hpp"
#include "vplkit/scene.hpp"

#include <vector>

namespace vplkit::scene::detail {

// Reads and checks every animation of the file; when options.time or options.animation is set,
// writes the selected animations' values at that time into `model`'s nodes (the model `source`
// reads). Returns the animations' spans, `applied` set on those posed, and sets `time` to the
// time posed at (unset: the rest pose). Fails naming the file, the animation and the channel.
std::vector<Animation> pose_animations(const GltfSource& source, tinygltf::Model& model, const LoadOptions& options,
                                       std::optional<double>& time, LoadWarnings& warnings);

}  // namespace vplkit::scene::detail
