// load_gltf: tinygltf parses the file and loads its buffers; everything it does not check
// (indices into arrays, accessor and bufferView bounds, finite values, required extensions) is
// checked here before the data is used, and each failure is one Error naming file and problem.

#include "scene/gltf_accessors.hpp"
#include "scene/gltf_geometry.hpp"
#include "scene/gltf_images.hpp"
#include "scene/gltf_pose.hpp"
#include "vplkit/error.hpp"
#include "vplkit/scene.hpp"

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

namespace vplkit::scene {
namespace {

using detail::GltfSource;
using detail::JointSet;
using detail::MorphTarget;
using detail::PrimitiveData;

constexpr const char* kLightsExtension = "KHR_lights_punctual";
constexpr const char* kEmissiveStrengthExtension = "KHR_materials_emissive_strength";
constexpr const char* kTextureTransformExtension = "KHR_texture_transform";
constexpr const char* kQuantizationExtension = "KHR_mesh_quantization";
const std::set<std::string> kSupportedExtensions = {kLightsExtension, kEmissiveStrengthExtension,
                                                    kTextureTransformExtension, kQuantizationExtension};

std::string one_line(const std::string& text) {
    std::string out;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        while (!line.empty() && (line.back() == ' ' || line.back() == '\r')) line.pop_back();
        if (line.empty()) continue;
        if (!out.empty()) out += "; ";
        out += line;
    }
    return out;
}

std::string quoted_name(const std::string& name) {
    return name.empty() ? "" : " '" + name + "'";
}

bool finite(double v) {
    return std::isfinite(v);
}

template <typename T>
void check_index(const GltfSource& source, int index, const std::vector<T>& items, const char* kind,
                 const std::string& referrer) {
    if (index < 0 || size_t(index) >= items.size()) {
        source.fail(referrer + " refers to " + kind + " " + std::to_string(index) + ", but the file has " +
                    std::to_string(items.size()) + " " + kind + (items.size() == 1 ? "" : "s"));
    }
}

// --- Materials and textures -----------------------------------------------------------------

// Turns the file's textures and images into the scene's, keeping only those materials use, each
// once, in order of first use.
class TextureTable {
public:
    explicit TextureTable(const GltfSource& source) : source_(source) {}

    // `info` is a material's textureInfo (or normal texture info); `uv` receives its texture
    // coordinate set and KHR_texture_transform. `slot` names the use for messages ("base colour
    // texture of material 0 'floor'").
    template <typename Info>
    int32_t use(const Info& info, bool srgb, const std::string& slot, UvTransform& uv, LoadWarnings& warnings) {
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

    std::vector<Texture> take_textures() { return std::move(textures_); }
    const std::vector<detail::ImageUse>& image_uses() const { return image_uses_; }

private:
    UvTransform uv_transform(int tex_coord, const tinygltf::ExtensionMap& extensions, const std::string& slot,
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
                if (!v.IsArray() || v.ArrayLen() != 2)
                    source_.fail(label + " " + key + " is not an array of 2 numbers");
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

    Sampler convert_sampler(const tinygltf::Sampler& s, int index) const {
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

    const GltfSource& source_;
    std::map<int, int32_t> texture_index_;
    std::map<int, uint32_t> image_index_;
    std::vector<Texture> textures_;
    std::vector<detail::ImageUse> image_uses_;
};

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

// --- Node hierarchy -------------------------------------------------------------------------

glm::dmat4 local_transform(const GltfSource& source, const tinygltf::Node& node, const std::string& label) {
    auto check_finite = [&](const std::vector<double>& values, const char* what) {
        for (double v : values) {
            if (!finite(v)) source.fail(label + ": " + what + " is not finite");
        }
    };
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) source.fail(label + ": matrix does not have 16 components");
        check_finite(node.matrix, "matrix");
        glm::dmat4 m;
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[size_t(4 * c + r)];  // column-major
        }
        return m;
    }
    glm::dmat4 t(1.0), r(1.0), s(1.0);
    if (!node.translation.empty()) {
        if (node.translation.size() != 3) source.fail(label + ": translation does not have 3 components");
        check_finite(node.translation, "translation");
        t[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4) source.fail(label + ": rotation does not have 4 components");
        check_finite(node.rotation, "rotation");
        // glTF stores (x, y, z, w); glm's constructor takes w first.
        glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        const double length = glm::length(q);
        if (!(length > 0.0)) source.fail(label + ": rotation quaternion is zero");
        r = glm::mat4_cast(q / length);
    }
    if (!node.scale.empty()) {
        if (node.scale.size() != 3) source.fail(label + ": scale does not have 3 components");
        check_finite(node.scale, "scale");
        s = glm::dmat4(glm::dvec4(node.scale[0], 0, 0, 0), glm::dvec4(0, node.scale[1], 0, 0),
                       glm::dvec4(0, 0, node.scale[2], 0), glm::dvec4(0, 0, 0, 1));
    }
    return t * r * s;
}

struct NodeInstance {
    int node;
    glm::dmat4 world;
};

// Depth-first, pre-order (a parent before its children, children in the file's order), without
// recursion: a corrupt file's deep chain must not overflow the stack.
std::vector<NodeInstance> traverse(const GltfSource& source, LoadWarnings& warnings) {
    const auto& model = source.model;
    std::vector<int> roots;
    if (!model.scenes.empty()) {
        int scene = model.defaultScene;
        if (scene < 0) scene = 0;
        check_index(source, scene, model.scenes, "scene", "the default scene");
        roots = model.scenes[size_t(scene)].nodes;
        if (model.scenes.size() > 1) {
            warnings.messages.push_back("the file has " + std::to_string(model.scenes.size()) +
                                        " scenes; loaded scene " + std::to_string(scene));
        }
    } else {
        // No scene: every node nobody lists as a child is a root.
        std::vector<bool> is_child(model.nodes.size(), false);
        for (const auto& node : model.nodes) {
            for (int child : node.children) {
                if (child >= 0 && size_t(child) < model.nodes.size()) is_child[size_t(child)] = true;
            }
        }
        for (size_t i = 0; i < model.nodes.size(); ++i) {
            if (!is_child[i]) roots.push_back(int(i));
        }
    }

    std::vector<NodeInstance> out;
    std::vector<bool> seen(model.nodes.size(), false);
    std::vector<std::pair<int, glm::dmat4>> stack;
    std::vector<std::string> referrer;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
        check_index(source, *it, model.nodes, "node", "the scene");
        stack.emplace_back(*it, glm::dmat4(1.0));
    }
    while (!stack.empty()) {
        const auto [index, parent] = stack.back();
        stack.pop_back();
        const tinygltf::Node& node = model.nodes[size_t(index)];
        const std::string label = "node " + std::to_string(index) + quoted_name(node.name);
        if (seen[size_t(index)]) {
            source.fail(label +
                        " appears twice in the node hierarchy (glTF 2.0 requires disjoint trees: a cycle "
                        "or a node with two parents)");
        }
        seen[size_t(index)] = true;
        const glm::dmat4 world = parent * local_transform(source, node, label);
        out.push_back({index, world});
        for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) {
            check_index(source, *child, model.nodes, "node", label + " (as a child)");
            stack.emplace_back(*child, world);
        }
    }
    return out;
}

// World transforms of nodes: those the scene's traversal reached, and on demand any other (a
// skin's joint outside the scene) through its parents.
class NodeWorlds {
public:
    NodeWorlds(const GltfSource& source, const std::vector<NodeInstance>& instances)
        : source_(source), parent_(source.model.nodes.size(), -1), world_(source.model.nodes.size()) {
        const auto& nodes = source.model.nodes;
        for (size_t i = 0; i < nodes.size(); ++i) {
            for (int child : nodes[i].children) {
                if (child >= 0 && size_t(child) < nodes.size() && parent_[size_t(child)] < 0) {
                    parent_[size_t(child)] = int(i);
                }
            }
        }
        for (const NodeInstance& instance : instances) world_[size_t(instance.node)] = instance.world;
    }

    glm::dmat4 operator()(int node) {
        std::vector<int> chain;  // nodes without a known world, from `node` up
        glm::dmat4 base(1.0);
        for (int n = node;;) {
            if (world_[size_t(n)]) {
                base = *world_[size_t(n)];
                break;
            }
            chain.push_back(n);
            if (chain.size() > parent_.size()) source_.fail("node " + std::to_string(node) + " has a cycle above it");
            if (parent_[size_t(n)] < 0) break;
            n = parent_[size_t(n)];
        }
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            const tinygltf::Node& n = source_.model.nodes[size_t(*it)];
            base = base * local_transform(source_, n, "node " + std::to_string(*it) + quoted_name(n.name));
            world_[size_t(*it)] = base;
        }
        return base;
    }

private:
    const GltfSource& source_;
    std::vector<int> parent_;
    std::vector<std::optional<glm::dmat4>> world_;
};

// Each joint's world transform times its inverse bind matrix (glTF 2.0 3.7.3): what a vertex
// bound to that joint is multiplied by. No inverseBindMatrices: identities.
std::vector<glm::dmat4> joint_matrices(const GltfSource& source, int skin_index, NodeWorlds& worlds,
                                       const std::string& node_label) {
    check_index(source, skin_index, source.model.skins, "skin", node_label);
    const tinygltf::Skin& skin = source.model.skins[size_t(skin_index)];
    const std::string label = "skin " + std::to_string(skin_index) + quoted_name(skin.name);
    if (skin.joints.empty()) source.fail(label + " has no joints");
    std::vector<glm::mat4> inverse_bind(skin.joints.size(), glm::mat4(1.0f));
    if (skin.inverseBindMatrices >= 0) {
        inverse_bind = detail::read_mat4s(source, skin.inverseBindMatrices, "inverseBindMatrices of " + label);
        if (inverse_bind.size() < skin.joints.size()) {
            source.fail(label + " has " + std::to_string(skin.joints.size()) + " joints but " +
                        std::to_string(inverse_bind.size()) + " inverse bind matrices");
        }
        for (const glm::mat4& m : inverse_bind) {
            for (int c = 0; c < 4; ++c) {
                for (int r = 0; r < 4; ++r) {
                    if (!std::isfinite(m[c][r])) source.fail(label + ": an inverse bind matrix is not finite");
                }
            }
        }
    }
    std::vector<glm::dmat4> out;
    for (size_t j = 0; j < skin.joints.size(); ++j) {
        check_index(source, skin.joints[j], source.model.nodes, "node", label + " (joint " + std::to_string(j) + ")");
        out.push_back(worlds(skin.joints[j]) * glm::dmat4(inverse_bind[j]));
    }
    return out;
}

// The morph weights of a node's mesh: the node's, else the mesh's, else none (all zero).
std::vector<double> morph_weights(const GltfSource& source, const tinygltf::Node& node, const tinygltf::Mesh& mesh,
                                  const std::string& node_label) {
    const std::vector<double>& weights = !node.weights.empty() ? node.weights : mesh.weights;
    for (double w : weights) {
        if (!finite(w)) source.fail(node_label + ": a morph target weight is not finite");
    }
    return weights;
}

// --- Meshes ---------------------------------------------------------------------------------

// One glTF primitive decoded and validated once, however many nodes instance its mesh.
std::optional<PrimitiveData> decode_primitive(const GltfSource& source, int mesh_index, int primitive_index,
                                              uint32_t default_material, LoadWarnings& warnings) {
    const tinygltf::Mesh& mesh = source.model.meshes[size_t(mesh_index)];
    const tinygltf::Primitive& primitive = mesh.primitives[size_t(primitive_index)];
    const std::string label =
        "mesh " + std::to_string(mesh_index) + quoted_name(mesh.name) + " primitive " + std::to_string(primitive_index);
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES) {
        ++warnings.skipped_primitives;
        return std::nullopt;
    }
    auto attribute = [&](const char* name) {
        const auto it = primitive.attributes.find(name);
        return it == primitive.attributes.end() ? -1 : it->second;
    };
    const int position_accessor = attribute("POSITION");
    if (position_accessor < 0) {
        warnings.messages.push_back(label + " has no POSITION: skipped");
        return std::nullopt;
    }

    PrimitiveData data;
    data.positions = detail::read_positions(source, position_accessor, "POSITION of " + label);
    const size_t vertex_count = data.positions.size();
    auto check_count = [&](size_t count, const char* name) {
        if (count != vertex_count) {
            source.fail(label + ": " + name + " has " + std::to_string(count) + " elements but POSITION has " +
                        std::to_string(vertex_count));
        }
    };
    auto check_finite = [&](const float* values, size_t components, const char* name) {
        for (size_t i = 0; i < vertex_count * components; ++i) {
            if (!std::isfinite(values[i])) {
                std::ostringstream value;
                value << values[i];
                source.fail(label + ": " + name + " of vertex " + std::to_string(i / components) + " is " +
                            value.str() + " (NaN or infinite)");
            }
        }
    };
    check_finite(&data.positions[0].x, 3, "POSITION");
    if (const int a = attribute("NORMAL"); a >= 0) {
        data.normals = detail::read_normals(source, a, "NORMAL of " + label);
        check_count(data.normals.size(), "NORMAL");
        check_finite(&data.normals[0].x, 3, "NORMAL");
    }
    if (const int a = attribute("TANGENT"); a >= 0) {
        data.tangents = detail::read_tangents(source, a, "TANGENT of " + label);
        check_count(data.tangents.size(), "TANGENT");
        check_finite(&data.tangents[0].x, 4, "TANGENT");
    }
    if (const int a = attribute("TEXCOORD_0"); a >= 0) {
        data.uvs = detail::read_texcoords(source, a, "TEXCOORD_0 of " + label);
        check_count(data.uvs.size(), "TEXCOORD_0");
        check_finite(&data.uvs[0].x, 2, "TEXCOORD_0");
    }
    if (const int a = attribute("TEXCOORD_1"); a >= 0) {
        data.uvs1 = detail::read_texcoords(source, a, "TEXCOORD_1 of " + label);
        check_count(data.uvs1.size(), "TEXCOORD_1");
        check_finite(&data.uvs1[0].x, 2, "TEXCOORD_1");
    }
    if (const int a = attribute("COLOR_0"); a >= 0) {
        data.colors = detail::read_colors(source, a, "COLOR_0 of " + label);
        check_count(data.colors.size(), "COLOR_0");
        check_finite(&data.colors[0].x, 4, "COLOR_0");
    }

    for (size_t t = 0; t < primitive.targets.size(); ++t) {
        const std::string target_label = "morph target " + std::to_string(t) + " of " + label;
        const auto& attributes = primitive.targets[t];
        MorphTarget target;
        auto displacement = [&](const char* name, auto read) {
            const auto it = attributes.find(name);
            if (it == attributes.end()) return std::vector<glm::vec3>{};
            auto values = read(source, it->second, std::string(name) + " of " + target_label);
            const std::string what = "morph target " + std::to_string(t) + " " + name;
            check_count(values.size(), what.c_str());
            check_finite(&values[0].x, 3, what.c_str());
            return values;
        };
        target.positions = displacement("POSITION", detail::read_target_positions);
        target.normals = displacement("NORMAL", detail::read_target_directions);
        target.tangents = displacement("TANGENT", detail::read_target_directions);
        for (const auto& [name, accessor] : attributes) {
            if (name != "POSITION" && name != "NORMAL" && name != "TANGENT") {
                warnings.messages.push_back(target_label + ": " + name + " displacements ignored");
            }
        }
        data.targets.push_back(std::move(target));
    }
    for (int set = 0;; ++set) {
        const std::string joints_name = "JOINTS_" + std::to_string(set);
        const std::string weights_name = "WEIGHTS_" + std::to_string(set);
        const int joints = attribute(joints_name.c_str()), weights = attribute(weights_name.c_str());
        if (joints < 0 && weights < 0) break;
        if (joints < 0 || weights < 0) {
            source.fail(
                label + " has " +
                (joints < 0 ? weights_name + " without " + joints_name : joints_name + " without " + weights_name));
        }
        JointSet joint_set;
        joint_set.joints = detail::read_joints(source, joints, joints_name + " of " + label);
        joint_set.weights = detail::read_weights(source, weights, weights_name + " of " + label);
        check_count(joint_set.joints.size(), joints_name.c_str());
        check_count(joint_set.weights.size(), weights_name.c_str());
        check_finite(&joint_set.weights[0].x, 4, weights_name.c_str());
        data.joint_sets.push_back(std::move(joint_set));
    }

    if (primitive.indices >= 0) {
        data.indices = detail::read_indices(source, primitive.indices, "indices of " + label);
        for (size_t i = 0; i < data.indices.size(); ++i) {
            if (data.indices[i] >= vertex_count) {
                source.fail(label + ": index " + std::to_string(i) + " is " + std::to_string(data.indices[i]) +
                            ", but the primitive has " + std::to_string(vertex_count) + " vertices");
            }
        }
    } else {
        data.indices.resize(vertex_count);
        for (size_t i = 0; i < vertex_count; ++i) data.indices[i] = uint32_t(i);
    }
    if (data.indices.size() % 3 != 0) {
        source.fail(label + ": " + std::to_string(data.indices.size()) +
                    (primitive.indices >= 0 ? " indices" : " vertices") + " do not make whole triangles");
    }

    if (primitive.material >= 0) {
        check_index(source, primitive.material, source.model.materials, "material", label);
        data.material = uint32_t(primitive.material);
    } else {
        data.material = default_material;
    }
    return data;
}

// --- Lights and cameras ---------------------------------------------------------------------

Light convert_light(const GltfSource& source, int index, const glm::dmat4& world, const std::string& node_label) {
    const tinygltf::Light& l = source.model.lights[size_t(index)];
    const std::string label = "light " + std::to_string(index) + quoted_name(l.name) + " (on " + node_label + ")";
    Light out;
    out.origin = LightOrigin::file;
    out.name = l.name.empty() ? "light " + std::to_string(index) : l.name;
    if (l.type == "directional") {
        out.type = LightType::directional;
    } else if (l.type == "point") {
        out.type = LightType::point;
    } else if (l.type == "spot") {
        out.type = LightType::spot;
    } else {
        source.fail(label + ": type '" + l.type + "' is not directional, point or spot");
    }
    if (!l.color.empty()) {
        if (l.color.size() != 3) source.fail(label + ": color does not have 3 components");
        for (int c = 0; c < 3; ++c) {
            if (!finite(l.color[size_t(c)]) || l.color[size_t(c)] < 0.0)
                source.fail(label + ": color is negative or not finite");
            out.color[c] = float(l.color[size_t(c)]);
        }
    }
    if (!finite(l.intensity) || l.intensity < 0.0) source.fail(label + ": intensity is negative or not finite");
    out.intensity = float(l.intensity);
    if (!finite(l.range) || l.range < 0.0) source.fail(label + ": range is negative or not finite");
    out.range = float(l.range);
    if (out.type == LightType::spot) {
        const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
        // Tolerance for exporters that write pi/2 rounded up in the last digit.
        if (!(inner >= 0.0 && inner < outer && outer <= std::numbers::pi / 2 + 1e-6)) {
            source.fail(label + ": cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2");
        }
        out.inner_cone_angle = float(inner);
        out.outer_cone_angle = float(std::min(outer, std::numbers::pi / 2));
    }
    out.position = glm::vec3(world[3]);
    const glm::dvec3 direction = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
    const double length = glm::length(direction);
    if (out.type != LightType::point && !(length > 0.0)) {
        source.fail(label + ": the node's transform has a zero scale, so the light has no direction");
    }
    if (length > 0.0) out.direction = glm::vec3(direction / length);
    return out;
}

Camera convert_camera(const GltfSource& source, int index, const glm::dmat4& world, const std::string& node_label) {
    const tinygltf::Camera& c = source.model.cameras[size_t(index)];
    const std::string label = "camera " + std::to_string(index) + quoted_name(c.name) + " (on " + node_label + ")";
    Camera out;
    if (c.type == "perspective") {
        const auto& p = c.perspective;
        if (!(finite(p.yfov) && p.yfov > 0.0 && p.yfov < std::numbers::pi))
            source.fail(label + ": yfov is not in (0, pi)");
        if (!(finite(p.znear) && p.znear > 0.0)) source.fail(label + ": znear is not > 0");
        if (!(finite(p.zfar) && (p.zfar == 0.0 || p.zfar > p.znear))) source.fail(label + ": zfar is not > znear");
        if (!(finite(p.aspectRatio) && p.aspectRatio >= 0.0)) source.fail(label + ": aspectRatio is negative");
        out.projection = Projection::perspective;
        out.yfov = float(p.yfov);
        out.aspect = float(p.aspectRatio);
        out.znear = float(p.znear);
        out.zfar = float(p.zfar);
    } else if (c.type == "orthographic") {
        const auto& o = c.orthographic;
        // glTF 2.0 5.13: xmag and ymag must not be 0, zfar must be > znear >= 0.
        if (!(finite(o.xmag) && o.xmag > 0.0 && finite(o.ymag) && o.ymag > 0.0)) {
            source.fail(label + ": orthographic xmag and ymag must be > 0 (half the view's width and height)");
        }
        if (!(finite(o.znear) && o.znear >= 0.0)) source.fail(label + ": orthographic znear is not >= 0");
        if (!(finite(o.zfar) && o.zfar > o.znear)) source.fail(label + ": orthographic zfar is not > znear");
        out.projection = Projection::orthographic;
        out.xmag = float(o.xmag);
        out.ymag = float(o.ymag);
        out.znear = float(o.znear);
        out.zfar = float(o.zfar);
    } else {
        source.fail(label + ": type '" + c.type + "' is neither perspective nor orthographic");
    }
    const glm::dmat3 linear(world);
    const glm::dvec3 forward = linear * glm::dvec3(0.0, 0.0, -1.0);
    const glm::dvec3 up = linear * glm::dvec3(0.0, 1.0, 0.0);
    const double forward_length = glm::length(forward);
    const glm::dvec3 f = forward / forward_length;
    const glm::dvec3 u = up - f * glm::dot(f, up);
    const double up_length = glm::length(u);
    if (!(forward_length > 0.0) || !(up_length > 0.0)) {
        source.fail(label + ": the node's transform is singular, so the camera has no orientation");
    }
    out.name = c.name.empty() ? "camera " + std::to_string(index) : c.name;
    out.origin = CameraOrigin::file;
    out.position = glm::vec3(world[3]);
    out.forward = glm::vec3(f);
    out.up = glm::vec3(u / up_length);
    return out;
}

// --- Loading the file -----------------------------------------------------------------------

// tinygltf reports a missing or short buffer file as "File not found : <uri>" or
// "File size mismatch : <path>, requestedBytes N, but got M": say it in vplkit's words, with the
// full path.
std::optional<std::string> buffer_problem(const std::string& why, const std::filesystem::path& base_dir) {
    constexpr std::string_view kNotFound = "File not found : ";
    constexpr std::string_view kMismatch = "File size mismatch : ";
    if (why.rfind(kNotFound, 0) == 0) {
        const std::string uri = why.substr(kNotFound.size(), why.find(';') - kNotFound.size());
        return "buffer file " + (base_dir / uri).lexically_normal().string() + " not found";
    }
    if (why.rfind(kMismatch, 0) == 0) {
        const size_t comma = why.find(", requestedBytes ");
        const size_t got = why.find(", but got ");
        if (comma != std::string::npos && got != std::string::npos) {
            const std::string buffer = why.substr(kMismatch.size(), comma - kMismatch.size());
            const std::string requested = why.substr(comma + 17, got - comma - 17);
            const std::string actual = why.substr(got + 10, why.find(';', got) - got - 10);
            return "buffer file " + buffer + " has " + actual + " bytes, but the glTF declares " + requested +
                   " (truncated or the wrong file)";
        }
    }
    return std::nullopt;
}

// tinygltf joins every buffer and image URI to the glTF file's folder, an absolute-path reference
// too ("dir" + "/" + "/abs/b.bin": not found although /abs/b.bin exists). RFC 3986 resolves a
// reference that starts with '/' to that path alone; `base_dir` is the folder tinygltf joins
// (everything before the file name's last separator, as its GetBaseDir takes it).
std::string expand_uri_path(const std::string& joined, void* base_dir) {
    const std::string& base = *static_cast<const std::string*>(base_dir);
    const std::string absolute_join = base + "//";
    if (!base.empty() && joined.rfind(absolute_join, 0) == 0) {
        return tinygltf::ExpandFilePath(joined.substr(base.size() + 1), nullptr);
    }
    return tinygltf::ExpandFilePath(joined, nullptr);
}

bool is_glb(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    char magic[4] = {};
    file.read(magic, 4);
    return file.gcount() == 4 && std::string_view(magic, 4) == "glTF";
}

void check_extensions(const GltfSource& source, LoadWarnings& warnings) {
    for (const std::string& name : source.model.extensionsRequired) {
        if (!kSupportedExtensions.count(name)) {
            std::string supported;
            for (const std::string& e : kSupportedExtensions) supported += (supported.empty() ? "" : ", ") + e;
            source.fail("the file requires extension " + name +
                        ", which vplkit does not support (supported: " + supported + ")");
        }
    }
    for (const std::string& name : source.model.extensionsUsed) {
        if (!kSupportedExtensions.count(name)) {
            warnings.messages.push_back("extension " + name + " ignored (not required by the file)");
        }
    }
}

}  // namespace

Scene load_gltf(const std::filesystem::path& path, const LoadOptions& options) {
    const std::string file = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(file + ": file not found");
    if (std::filesystem::is_directory(path, ec)) throw Error(file + ": is a directory, not a glTF file");

    tinygltf::Model model;
    detail::CapturedImages captured;
    std::string warn;
    {
        tinygltf::TinyGLTF loader;
        loader.SetImageLoader(&detail::capture_image_bytes, &captured);
        const size_t separator = file.find_last_of("/\\");
        std::string base_dir = separator == std::string::npos ? std::string() : file.substr(0, separator);
        loader.SetFsCallbacks(
            {&tinygltf::FileExists, &expand_uri_path, &tinygltf::ReadWholeFile, &tinygltf::WriteWholeFile, &base_dir});
        std::string err;
        const bool ok = is_glb(path) ? loader.LoadBinaryFromFile(&model, &err, &warn, file)
                                     : loader.LoadASCIIFromFile(&model, &err, &warn, file);
        if (!ok) {
            std::string why = one_line(err.empty() ? warn : err);
            // nlohmann's "[json.exception.parse_error.101] parse error at ..." says what, not where from.
            constexpr std::string_view kJsonParse = "[json.exception.parse_error.";
            if (const size_t at = why.find(kJsonParse); at != std::string::npos) {
                const size_t end = why.find("] ", at);
                if (end != std::string::npos) why = "malformed JSON: " + why.substr(end + 2);
            }
            why = buffer_problem(why, path.parent_path()).value_or("cannot be loaded: " + why);
            throw Error(file + ": " + (why.empty() ? "cannot be loaded (tinygltf gave no reason)" : why));
        }
    }
    const GltfSource source{model, file};

    Scene scene;
    scene.source = path;
    {
        std::istringstream lines(warn);
        for (std::string line; std::getline(lines, line);) {
            if (!line.empty()) scene.warnings.messages.push_back("tinygltf: " + line);
        }
    }
    check_extensions(source, scene.warnings);
    if (!model.animations.empty()) {
        scene.warnings.messages.push_back(std::to_string(model.animations.size()) +
                                          " animation(s) ignored: the still frame is the file's rest pose (node "
                                          "transforms, default morph weights)");
    }

    // Materials first: a primitive's need for tangents depends on its material's normal texture.
    TextureTable textures(source);
    for (size_t m = 0; m < model.materials.size(); ++m) {
        scene.materials.push_back(convert_material(source, int(m), textures, scene.warnings));
    }
    const uint32_t default_material = uint32_t(model.materials.size());
    bool default_material_used = false;

    std::vector<std::optional<std::vector<std::optional<PrimitiveData>>>> decoded(model.meshes.size());
    const std::vector<NodeInstance> instances = traverse(source, scene.warnings);
    NodeWorlds worlds(source, instances);
    for (const NodeInstance& instance : instances) {
        const tinygltf::Node& node = model.nodes[size_t(instance.node)];
        const std::string node_label = "node " + std::to_string(instance.node) + quoted_name(node.name);
        if (node.camera >= 0) {
            check_index(source, node.camera, model.cameras, "camera", node_label);
            scene.cameras.push_back(convert_camera(source, node.camera, instance.world, node_label));
        }
        if (auto it = node.extensions.find(kLightsExtension); it != node.extensions.end()) {
            const tinygltf::Value& ext = it->second;
            if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsNumber()) {
                source.fail(node_label + ": " + kLightsExtension + " has no light index");
            }
            const int light = ext.Get("light").GetNumberAsInt();
            check_index(source, light, model.lights, "light", node_label);
            scene.lights.push_back(convert_light(source, light, instance.world, node_label));
        }
        if (node.mesh < 0) continue;
        check_index(source, node.mesh, model.meshes, "mesh", node_label);
        auto& primitives = decoded[size_t(node.mesh)];
        const tinygltf::Mesh& mesh = model.meshes[size_t(node.mesh)];
        if (!primitives) {
            primitives.emplace();
            for (size_t p = 0; p < mesh.primitives.size(); ++p) {
                primitives->push_back(decode_primitive(source, node.mesh, int(p), default_material, scene.warnings));
            }
        }
        const std::vector<double> weights = morph_weights(source, node, mesh, node_label);
        std::vector<glm::dmat4> joints;
        if (node.skin >= 0 && node.mesh >= 0) joints = joint_matrices(source, node.skin, worlds, node_label);
        for (size_t p = 0; p < primitives->size(); ++p) {
            if (!(*primitives)[p]) continue;
            const std::string where = node_label + " mesh " + std::to_string(node.mesh) + quoted_name(mesh.name) +
                                      " primitive " + std::to_string(p);
            // The still frame's pose: morphed, then skinned (world space; the node's own transform
            // is then ignored, glTF 2.0 3.7.3).
            const PrimitiveData* data = &*(*primitives)[p];
            std::optional<PrimitiveData> posed;
            glm::dmat4 world = instance.world;
            if (!data->targets.empty() &&
                std::any_of(weights.begin(), weights.end(), [](double w) { return w != 0; })) {
                if (weights.size() != data->targets.size()) {
                    source.fail(where + " has " + std::to_string(data->targets.size()) + " morph targets, but " +
                                std::to_string(weights.size()) + " weights are given");
                }
                posed = detail::morphed(*data, weights);
                data = &*posed;
            }
            if (node.skin >= 0) {
                if (data->joint_sets.empty()) {
                    scene.warnings.messages.push_back(where +
                                                      " has a skin but no JOINTS_0: drawn with the node's transform");
                } else {
                    posed = detail::skinned(source, *data, joints, where);
                    data = &*posed;
                    world = glm::dmat4(1.0);
                }
            }
            default_material_used |= data->material == default_material;
            if (data->material != default_material) {
                const std::string missing =
                    missing_tex_coords(scene.materials[data->material], !data->uvs.empty(), !data->uvs1.empty());
                if (!missing.empty()) {
                    scene.warnings.messages.push_back(where + ": its material's textures read " + missing +
                                                      ", which the primitive lacks (read as (0, 0))");
                }
            }
            const bool wants_tangents =
                data->material != default_material && scene.materials[data->material].normal_texture != kNoTexture;
            PrimitiveInstance info;
            info.node = uint32_t(instance.node);
            info.mesh = uint32_t(node.mesh);
            info.primitive = uint32_t(p);
            detail::append_instance(source, scene, *data, world, wants_tangents, info, where);
        }
    }
    if (scene.indices.empty()) {
        std::string why = "no triangles to render";
        if (scene.warnings.skipped_primitives) {
            why += " (" + std::to_string(scene.warnings.skipped_primitives) + " non-triangle primitive(s) skipped)";
        }
        if (scene.warnings.degenerate_triangles) {
            why += " (" + std::to_string(scene.warnings.degenerate_triangles) + " degenerate triangle(s) dropped)";
        }
        source.fail(why);
    }
    if (default_material_used) {
        Material fallback;  // glTF 2.0's default material: the member defaults
        fallback.name = "default";
        scene.materials.push_back(fallback);
    }

    scene.textures = textures.take_textures();
    scene.images = detail::decode_images(source, captured, textures.image_uses(), path.parent_path());

    scene.bounds.min = glm::vec3(std::numeric_limits<float>::max());
    scene.bounds.max = glm::vec3(std::numeric_limits<float>::lowest());
    for (uint32_t i : scene.indices) {
        scene.bounds.min = glm::min(scene.bounds.min, scene.vertices[i].position);
        scene.bounds.max = glm::max(scene.bounds.max, scene.vertices[i].position);
    }
    for (size_t t = 0; t < scene.triangle_materials.size(); ++t) {
        if (scene.materials[scene.triangle_materials[t]].emits()) scene.emissive_triangles.push_back(uint32_t(t));
    }

    const size_t file_cameras = scene.cameras.size();
    if (options.camera && *options.camera >= file_cameras) {
        source.fail("camera " + std::to_string(*options.camera) + " was asked for, but the file has " +
                    (file_cameras == 0
                         ? std::string("no camera")
                         : std::to_string(file_cameras) + " (0.." + std::to_string(file_cameras - 1) + ")"));
    }
    if (scene.cameras.empty()) scene.cameras.push_back(framing_camera(scene.bounds));
    scene.active_camera = options.camera.value_or(0);
    return scene;
}

}  // namespace vplkit::scene
