#pragma once
// Checks and labels the glTF loader's parts share: names for messages, indices into the file's
// arrays, finite numbers, and the extensions vplkit reads.

#include "scene/gltf_accessors.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace vplkit::scene::detail {

inline constexpr const char* kLightsExtension = "KHR_lights_punctual";
inline constexpr const char* kEmissiveStrengthExtension = "KHR_materials_emissive_strength";
inline constexpr const char* kTextureTransformExtension = "KHR_texture_transform";
inline constexpr const char* kQuantizationExtension = "KHR_mesh_quantization";

// " 'name'" for a named item, "" for an unnamed one: "material 2 'floor'", "material 2".
inline std::string quoted_name(const std::string& name) {
    return name.empty() ? "" : " '" + name + "'";
}

inline bool finite(double v) {
    return std::isfinite(v);
}

// Fails unless `index` refers to one of `items`; `referrer` says who refers to it.
template <typename T>
void check_index(const GltfSource& source, int index, const std::vector<T>& items, const char* kind,
                 const std::string& referrer) {
    if (index < 0 || size_t(index) >= items.size()) {
        source.fail(referrer + " refers to " + kind + " " + std::to_string(index) + ", but the file has " +
                    std::to_string(items.size()) + " " + kind + (items.size() == 1 ? "" : "s"));
    }
}

}  // namespace vplkit::scene::detail
