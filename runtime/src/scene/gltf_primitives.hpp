#pragma once
// Decoding one glTF primitive: its attributes, morph targets, joint sets and indices read through
// the bounds-checked accessors, counted against POSITION, checked finite and in range.

#include "scene/gltf_accessors.hpp"
#include "scene/gltf_geometry.hpp"
#include "vplkit/scene.hpp"

#include <cstdint>
#include <optional>

namespace vplkit::scene::detail {

// Primitive `primitive_index` of mesh `mesh_index` (both checked to exist) in its mesh's object
// space; nullopt for a primitive that is skipped (not triangles, or no POSITION), counted or
// warned in `warnings`. A primitive without a material gets `default_material`.
std::optional<PrimitiveData> decode_primitive(const GltfSource& source, int mesh_index, int primitive_index,
                                              uint32_t default_material, LoadWarnings& warnings);

}  // namespace vplkit::scene::detail
