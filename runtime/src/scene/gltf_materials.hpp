#pragma once
// Materials and the textures they use: glTF's metallic-roughness factors and textures, alpha modes,
// emissive strength, KHR_texture_transform per texture reference, samplers.

#include "scene/gltf_accessors.hpp"
#include "scene/gltf_images.hpp"
#include "vplkit/scene.hpp"

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace vplkit::scene::detail {

// Turns the file's textures and images into the scene's, keeping only those materials use, each
// once, in order of first use.
class TextureTable {
public:
    explicit TextureTable(const GltfSource& source) : source_(source) {}

    // `info` is a material's textureInfo (or normal texture info); `uv` receives its texture
    // coordinate set and KHR_texture_transform. `slot` names the use for messages ("base colour
    // texture of material 0 'floor'").
    template <typename Info>
    int32_t use(const Info& info, bool srgb, const std::string& slot, UvTransform& uv, LoadWarnings& warnings);

    std::vector<Texture> take_textures() { return std::move(textures_); }
    const std::vector<detail::ImageUse>& image_uses() const { return image_uses_; }

private:
    UvTransform uv_transform(int tex_coord, const tinygltf::ExtensionMap& extensions, const std::string& slot,
                             LoadWarnings& warnings) const;
    Sampler convert_sampler(const tinygltf::Sampler& s, int index) const;

    const GltfSource& source_;
    std::map<int, int32_t> texture_index_;
    std::map<int, uint32_t> image_index_;
    std::vector<Texture> textures_;
    std::vector<detail::ImageUse> image_uses_;
};

// Material `index` of the file (checked to exist), its textures entered in `textures`.
Material convert_material(const GltfSource& source, int index, TextureTable& textures, LoadWarnings& warnings);

// The texture coordinate sets `m`'s textures read that a primitive lacks ("TEXCOORD_1", ...).
std::string missing_tex_coords(const Material& m, bool has_uv0, bool has_uv1);

}  // namespace vplkit::scene::detail
