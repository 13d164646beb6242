#pragma once
// Bounds-checked reads of glTF accessors and bufferViews. tinygltf parses the JSON and loads the
// buffers, but does not check that an accessor's elements lie inside its bufferView, nor the
// bufferView inside its buffer: every read here checks both (and sparse substitutions) before
// touching a byte, and fails with a message naming the accessor and what it was read for.

#include <tiny_gltf.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace vplkit::scene::detail {

// The model being read and the file it came from: every failure is "<file>: <problem>".
struct GltfSource {
    const tinygltf::Model& model;
    std::string file;

    [[noreturn]] void fail(const std::string& problem) const;
};

// The bytes of bufferView `index`, checked to lie inside its buffer. `what` says who refers to it.
std::span<const uint8_t> buffer_view_bytes(const GltfSource& source, int index, const std::string& what);

// Element count of accessor `index` (checked to exist).
size_t accessor_count(const GltfSource& source, int index, const std::string& what);

// Vertex attributes. glTF 2.0 allows FLOAT for positions, normals and tangents, and also
// normalized UNSIGNED_BYTE / UNSIGNED_SHORT for texture coordinates.
std::vector<glm::vec3> read_vec3(const GltfSource& source, int accessor, const std::string& what);
std::vector<glm::vec4> read_vec4(const GltfSource& source, int accessor, const std::string& what);
std::vector<glm::vec2> read_texcoords(const GltfSource& source, int accessor, const std::string& what);
// COLOR_n: VEC3 or VEC4 of FLOAT or normalized UNSIGNED_BYTE / UNSIGNED_SHORT, as RGBA (a = 1
// for VEC3), clamped to [0, 1] (glTF 2.0 3.7.2.1 gives that range).
std::vector<glm::vec4> read_colors(const GltfSource& source, int accessor, const std::string& what);

// Triangle indices: SCALAR UNSIGNED_BYTE / UNSIGNED_SHORT / UNSIGNED_INT.
std::vector<uint32_t> read_indices(const GltfSource& source, int accessor, const std::string& what);

}  // namespace vplkit::scene::detail
