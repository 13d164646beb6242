#pragma once
// Bounds-checked reads of glTF accessors and bufferViews. tinygltf parses the JSON and loads the
// buffers, but does not check that an accessor's elements lie inside its bufferView, nor the
// bufferView inside its buffer: every read here checks both (and sparse substitutions) before
// touching a byte, and fails with a message naming the accessor and what it was read for.

#include <tiny_gltf.h>

#include <glm/mat4x4.hpp>
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

// Component types an attribute admits (bits). glTF 2.0 core: FLOAT, plus normalized unsigned
// for texture coordinates, colours and weights, unnormalized unsigned for joints;
// KHR_mesh_quantization adds signed normalized and unnormalized integers for positions,
// normals, tangents and texture coordinates, admitted only when the file declares it.
enum Admit : uint32_t {
    kAdmitFloat = 1,
    kAdmitNormalizedUnsigned = 2,  // normalized UNSIGNED_BYTE / UNSIGNED_SHORT
    kAdmitNormalizedSigned = 4,    // normalized BYTE / SHORT
    kAdmitIntegers = 8,            // unnormalized BYTE / UNSIGNED_BYTE / SHORT / UNSIGNED_SHORT
};
// Whether the file lists KHR_mesh_quantization in extensionsUsed.
bool quantized(const GltfSource& source);

// Reads accessor `accessor` as `components` floats per element (normalized integers mapped as
// glTF 2.0 3.11 says, unnormalized ones as their value), sparse substitutions applied; fails when
// its type or component type is neither a `core` kind nor, in a file that declares
// KHR_mesh_quantization, a `with_quantization` kind (the message says which).
std::vector<float> read_floats(const GltfSource& source, int accessor, size_t components, uint32_t core,
                               uint32_t with_quantization, const std::string& what);

// Vertex attributes (POSITION, NORMAL: VEC3; TANGENT: VEC4; TEXCOORD_n: VEC2) with the component
// types core glTF and KHR_mesh_quantization allow each.
std::vector<glm::vec3> read_positions(const GltfSource& source, int accessor, const std::string& what);
std::vector<glm::vec3> read_normals(const GltfSource& source, int accessor, const std::string& what);
std::vector<glm::vec4> read_tangents(const GltfSource& source, int accessor, const std::string& what);
std::vector<glm::vec2> read_texcoords(const GltfSource& source, int accessor, const std::string& what);
// Morph target displacements (VEC3): positions admit every quantized kind, normals and tangents
// the normalized signed ones.
std::vector<glm::vec3> read_target_positions(const GltfSource& source, int accessor, const std::string& what);
std::vector<glm::vec3> read_target_directions(const GltfSource& source, int accessor, const std::string& what);
// COLOR_n: VEC3 or VEC4 of FLOAT or normalized UNSIGNED_BYTE / UNSIGNED_SHORT, as RGBA (a = 1
// for VEC3), clamped to [0, 1] (glTF 2.0 3.7.2.1 gives that range).
std::vector<glm::vec4> read_colors(const GltfSource& source, int accessor, const std::string& what);
// JOINTS_n: VEC4 of UNSIGNED_BYTE / UNSIGNED_SHORT (not normalized); WEIGHTS_n: VEC4 of FLOAT or
// normalized UNSIGNED_BYTE / UNSIGNED_SHORT.
std::vector<glm::uvec4> read_joints(const GltfSource& source, int accessor, const std::string& what);
std::vector<glm::vec4> read_weights(const GltfSource& source, int accessor, const std::string& what);
// inverseBindMatrices: MAT4 FLOAT, column-major.
std::vector<glm::mat4> read_mat4s(const GltfSource& source, int accessor, const std::string& what);

// Triangle indices: SCALAR UNSIGNED_BYTE / UNSIGNED_SHORT / UNSIGNED_INT.
std::vector<uint32_t> read_indices(const GltfSource& source, int accessor, const std::string& what);

}  // namespace vplkit::scene::detail
