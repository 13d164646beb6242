// Materials and textures: each value the file states checked (finite, in range, a known mode)
// before it is used; textures and images kept only when a material uses them.

#include "scene/gltf_materials.hpp"

#include "scene/gltf_checks.hpp"

#include <algorithm>
#include <utility>

namespace vplkit::scene::detail {

template <typename Info>
int32_t TextureTable::use(const Info& info, bool srgb, const std::string& slot, UvTransform& uv,
                          LoadWarnings& warnings) {
    const int gltf_texture = info.index;
    if (gltf_texture < 0) return kNoTexture;
    const auto& model = source_.model;
    check_index(source_, gltf_texture, model.textures, "texture", slot);
    uv = uv_transform(info.texCoord, info.extensions, slot, warnings);
    const tinygltf::Texture& texture = model.textures[size_t(gltf_texture)];
    const std::string texture_label = "texture " + std::to_string(gltf_texture);
    if (texture.source < 0) {
        source_.fail(texture_label + " (" + slot +
                     ") has no image source in core glTF 2.0 (an image only an extension can read)");
    }
    check_index(source_, texture.source, model.images, "image", texture_label);
    uint32_t image;
    if (auto it = image_index_.find(texture.source); it != image_index_.end()) {
        image = it->second;
    } else {
        image = uint32_t(image_uses_.size());
        image_index_.emplace(texture.source, image);
        image_uses_.push_back({texture.source, slot, false, false});
    }
    (srgb ? image_uses_[image].srgb : image_uses_[image].linear) = true;

    if (auto it = texture_index_.find(gltf_texture); it != texture_index_.end()) return it->second;
    Texture out;
    out.image = image;
    if (texture.sampler >= 0) {
        check_index(source_, texture.sampler, model.samplers, "sampler", texture_label);
        out.sampler = convert_sampler(model.samplers[size_t(texture.sampler)], texture.sampler);
    }
    const int32_t index = int32_t(textures_.size());
    textures_.push_back(out);
    texture_index_.emplace(gltf_texture, index);
    return index;
}

UvTransform TextureTable::uv_transform(int tex_coord, const tinygltf::ExtensionMap& extensions, const std::string& slot,
                                       LoadWarnings& warnings) const {
    UvTransform out;
    if (auto it = extensions.find(kTextureTransformExtension); it != extensions.end()) {
        const tinygltf::Value& ext = it->second;
        const std::string label = slot + ": " + kTextureTransformExtension;
        if (!ext.IsObject()) source_.fail(label + " is not an object");
        auto number = [&](const tinygltf::Value& v, const char* what) {
            const double d = v.IsNumber() ? v.GetNumberAsDouble() : std::nan("");
            if (!finite(d)) source_.fail(label + " " + what + " is not a finite number");
            return float(d);
        };
        auto pair = [&](const char* key, glm::vec2 fallback) {
            if (!ext.Has(key)) return fallback;
            const tinygltf::Value& v = ext.Get(key);
            if (!v.IsArray() || v.ArrayLen() != 2) source_.fail(label + " " + key + " is not an array of 2 numbers");
            return glm::vec2(number(v.Get(0), key), number(v.Get(1), key));
        };
        out.offset = pair("offset", out.offset);
        out.scale = pair("scale", out.scale);
        if (ext.Has("rotation")) out.rotation = number(ext.Get("rotation"), "rotation");
        if (ext.Has("texCoord")) {
            const tinygltf::Value& v = ext.Get("texCoord");
            if (!v.IsInt() || v.GetNumberAsInt() < 0) source_.fail(label + " texCoord is not an index >= 0");
            tex_coord = v.GetNumberAsInt();
        }
    }
    if (tex_coord > 1) {
        warnings.messages.push_back(slot + " uses TEXCOORD_" + std::to_string(tex_coord) +
                                    "; vplkit keeps TEXCOORD_0 and TEXCOORD_1 and reads it with TEXCOORD_0");
        tex_coord = 0;
    }
    out.tex_coord = uint32_t(tex_coord);
    return out;
}

Sampler TextureTable::convert_sampler(const tinygltf::Sampler& s, int index) const {
    const std::string label = "sampler " + std::to_string(index);
    auto wrap = [&](int mode, const char* axis) {
        switch (mode) {
            case TINYGLTF_TEXTURE_WRAP_REPEAT:
                return Wrap::repeat;
            case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
                return Wrap::clamp_to_edge;
            case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
                return Wrap::mirrored_repeat;
            default:
                source_.fail(label + " has " + axis + " " + std::to_string(mode) +
                             ", not a glTF wrap mode (10497, 33071, 33648)");
        }
    };
    Sampler out;
    out.wrap_s = wrap(s.wrapS, "wrapS");
    out.wrap_t = wrap(s.wrapT, "wrapT");
    switch (s.magFilter) {
        case -1:
        case TINYGLTF_TEXTURE_FILTER_LINEAR:
            out.mag_filter = Filter::linear;
            break;
        case TINYGLTF_TEXTURE_FILTER_NEAREST:
            out.mag_filter = Filter::nearest;
            break;
        default:
            source_.fail(label + " has magFilter " + std::to_string(s.magFilter) + ", not 9728 or 9729");
    }
    switch (s.minFilter) {
        case -1:
        case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR:
            out.min_filter = Filter::linear, out.mipmap_mode = MipmapMode::linear;
            break;
        case TINYGLTF_TEXTURE_FILTER_NEAREST:
            out.min_filter = Filter::nearest, out.mipmap_mode = MipmapMode::none;
            break;
        case TINYGLTF_TEXTURE_FILTER_LINEAR:
            out.min_filter = Filter::linear, out.mipmap_mode = MipmapMode::none;
            break;
        case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
            out.min_filter = Filter::nearest, out.mipmap_mode = MipmapMode::nearest;
            break;
        case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
            out.min_filter = Filter::linear, out.mipmap_mode = MipmapMode::nearest;
            break;
        case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
            out.min_filter = Filter::nearest, out.mipmap_mode = MipmapMode::linear;
            break;
        default:
            source_.fail(label + " has minFilter " + std::to_string(s.minFilter) + ", not a glTF filter");
    }
    return out;
}

Material convert_material(const GltfSource& source, int index, TextureTable& textures, LoadWarnings& warnings) {
    const tinygltf::Material& m = source.model.materials[size_t(index)];
    const std::string label = "material " + std::to_string(index) + quoted_name(m.name);
    Material out;
    out.name = m.name.empty() ? "material " + std::to_string(index) : m.name;

    // Factors outside glTF's [0, 1] are clamped with a warning (exporters round past 1); only
    // a value that is not a number at all is an error. Emissive factors above 1 are kept: they
    // are what files without KHR_materials_emissive_strength use for bright emitters.
    bool clamped = false;
    auto unit_factor = [&](double v, const char* what) {
        if (!finite(v)) source.fail(label + ": " + what + " is not finite");
        clamped |= v < 0.0 || v > 1.0;
        return float(std::clamp(v, 0.0, 1.0));
    };
    const auto& pbr = m.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() != 4) source.fail(label + ": baseColorFactor does not have 4 components");
    for (int c = 0; c < 4; ++c)
        out.base_color_factor[c] = unit_factor(pbr.baseColorFactor[size_t(c)], "baseColorFactor");
    out.metallic_factor = unit_factor(pbr.metallicFactor, "metallicFactor");
    out.roughness_factor = unit_factor(pbr.roughnessFactor, "roughnessFactor");
    if (clamped)
        warnings.messages.push_back(label + ": a base colour, metallic or roughness factor outside [0, 1] was clamped");

    if (m.emissiveFactor.size() != 3) source.fail(label + ": emissiveFactor does not have 3 components");
    for (int c = 0; c < 3; ++c) {
        const double v = m.emissiveFactor[size_t(c)];
        if (!finite(v) || v < 0.0) source.fail(label + ": emissiveFactor is negative or not finite");
        out.emissive_factor[c] = float(v);
    }
    if (auto it = m.extensions.find(kEmissiveStrengthExtension); it != m.extensions.end()) {
        const tinygltf::Value& ext = it->second;
        if (ext.IsObject() && ext.Has("emissiveStrength")) {
            const tinygltf::Value& strength = ext.Get("emissiveStrength");
            const double v = strength.IsNumber() ? strength.GetNumberAsDouble() : -1.0;
            if (!finite(v) || v < 0.0) {
                source.fail(label + ": " + kEmissiveStrengthExtension + " emissiveStrength is not a number >= 0");
            }
            out.emissive_strength = float(v);
        }
    }

    if (m.alphaMode == "OPAQUE") {
        out.alpha_mode = AlphaMode::opaque;
    } else if (m.alphaMode == "MASK") {
        out.alpha_mode = AlphaMode::mask;
    } else if (m.alphaMode == "BLEND") {
        out.alpha_mode = AlphaMode::blend;
    } else {
        source.fail(label + ": alphaMode '" + m.alphaMode + "' is not OPAQUE, MASK or BLEND");
    }
    if (!finite(m.alphaCutoff) || m.alphaCutoff < 0.0) source.fail(label + ": alphaCutoff is negative");
    out.alpha_cutoff = float(m.alphaCutoff);
    out.double_sided = m.doubleSided;
    if (!finite(m.normalTexture.scale)) source.fail(label + ": normalTexture scale is not finite");
    out.normal_scale = float(m.normalTexture.scale);

    out.base_color_texture =
        textures.use(pbr.baseColorTexture, true, "base colour texture of " + label, out.base_color_uv, warnings);
    out.metallic_roughness_texture =
        textures.use(pbr.metallicRoughnessTexture, false, "metallic-roughness texture of " + label,
                     out.metallic_roughness_uv, warnings);
    out.normal_texture = textures.use(m.normalTexture, false, "normal texture of " + label, out.normal_uv, warnings);
    out.emissive_texture =
        textures.use(m.emissiveTexture, true, "emissive texture of " + label, out.emissive_uv, warnings);
    if (out.normal_texture != kNoTexture && (out.normal_uv.tex_coord != 0 || out.normal_uv.rotation != 0.0f)) {
        // The tangent frame comes from the file's TANGENT or from TEXCOORD_0 as it is.
        warnings.messages.push_back(label + ": the normal texture reads " +
                                    (out.normal_uv.tex_coord != 0 ? std::string("TEXCOORD_1") : "rotated UVs") +
                                    ", but its tangent frame follows TEXCOORD_0 unrotated (normal map approximated)");
    }
    if (m.occlusionTexture.index >= 0) {
        warnings.messages.push_back(label + ": occlusion texture ignored (VPLs compute indirect light)");
    }
    return out;
}

// The texture coordinate sets `m`'s textures read that a primitive lacks ("TEXCOORD_1", ...).
std::string missing_tex_coords(const Material& m, bool has_uv0, bool has_uv1) {
    bool reads[2] = {false, false};
    const std::pair<int32_t, const UvTransform*> uses[] = {{m.base_color_texture, &m.base_color_uv},
                                                           {m.metallic_roughness_texture, &m.metallic_roughness_uv},
                                                           {m.normal_texture, &m.normal_uv},
                                                           {m.emissive_texture, &m.emissive_uv}};
    for (const auto& [texture, uv] : uses) {
        if (texture != kNoTexture) reads[uv->tex_coord] = true;
    }
    std::string out;
    if (reads[0] && !has_uv0) out = "TEXCOORD_0";
    if (reads[1] && !has_uv1) out += (out.empty() ? "" : " and ") + std::string("TEXCOORD_1");
    return out;
}

}  // namespace vplkit::scene::detail
