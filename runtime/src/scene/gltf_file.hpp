#pragma once
// Reading a .gltf or .glb file with tinygltf, its failures said in vplkit's words (the file, then
// the problem), and the extensions it requires checked against those vplkit reads.

#include "scene/gltf_accessors.hpp"
#include "scene/gltf_images.hpp"
#include "vplkit/scene.hpp"

#include <filesystem>
#include <string>

namespace vplkit::scene::detail {

// Parses `path` (.gltf or .glb, told apart by the GLB magic) and loads its buffers; images are
// captured undecoded into `captured`. `warn` receives tinygltf's warnings, one per line. Fails
// with one Error "<file>: <problem>" (file not found, malformed JSON, a missing or short buffer).
tinygltf::Model read_gltf_file(const std::filesystem::path& path, CapturedImages& captured, std::string& warn);

// Fails when the file requires an extension vplkit does not read; warns for each one it only uses.
void check_extensions(const GltfSource& source, LoadWarnings& warnings);

}  // namespace vplkit::scene::detail
