// GpuScene: a scene::Scene uploaded for the raster stages (gpu_scene.hpp).

#include "vplkit/gpu_scene.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/shaders/types.hpp"

#include <glm/common.hpp>

#include <cstddef>
#include <map>
#include <string>
#include <tuple>
#include <utility>

namespace vplkit {
namespace {

namespace vs = vplkit::shaders;

// The vertex buffer is the scene's vertex array as it is; the shaders' struct must match it.
static_assert(sizeof(scene::Vertex) == sizeof(vs::SceneVertex));
static_assert(offsetof(scene::Vertex, position) == offsetof(vs::SceneVertex, position));
static_assert(offsetof(scene::Vertex, normal) == offsetof(vs::SceneVertex, normal));
static_assert(offsetof(scene::Vertex, tangent) == offsetof(vs::SceneVertex, tangent));
static_assert(offsetof(scene::Vertex, uv0) == offsetof(vs::SceneVertex, uv0));
static_assert(offsetof(scene::Vertex, uv1) == offsetof(vs::SceneVertex, uv1));
static_assert(offsetof(scene::Vertex, color) == offsetof(vs::SceneVertex, color));

constexpr VkBufferUsageFlags kVertexUsage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

// raster_material.glsl's flag bits.
constexpr uint32_t kAlphaTest = 1u;
constexpr uint32_t kNormalTexture = 2u;
constexpr uint32_t kDoubleSided = 4u;
// glTF leaves blending to the renderer; a G-buffer has one surface per pixel, so a blended
// surface is drawn where it is at least half opaque.
constexpr float kBlendAsMaskCutoff = 0.5f;

VkSamplerAddressMode address_mode(scene::Wrap wrap) {
    switch (wrap) {
        case scene::Wrap::repeat:
            return VK_SAMPLER_ADDRESS_MODE_REPEAT;
        case scene::Wrap::clamp_to_edge:
            return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        case scene::Wrap::mirrored_repeat:
            return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    }
    throw Error("vplkit: unknown texture wrap mode " + std::to_string(uint32_t(wrap)));
}

VkFilter filter(scene::Filter f) {
    return f == scene::Filter::nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
}

VkSampler create_sampler(Context& context, const scene::Sampler& s) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = filter(s.mag_filter);
    info.minFilter = filter(s.min_filter);
    info.addressModeU = address_mode(s.wrap_s);
    info.addressModeV = address_mode(s.wrap_t);
    info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    info.minLod = 0.0f;
    if (s.mipmap_mode == scene::MipmapMode::none) {
        // The Vulkan specification's recipe for a non-mipmapped minification filter: level 0 only,
        // while the level of detail still chooses between the min and mag filters.
        info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
        info.maxLod = 0.25f;
    } else {
        info.mipmapMode = s.mipmap_mode == scene::MipmapMode::nearest ? VK_SAMPLER_MIPMAP_MODE_NEAREST
                                                                      : VK_SAMPLER_MIPMAP_MODE_LINEAR;
        info.maxLod = VK_LOD_CLAMP_NONE;
    }
    VkSampler sampler = VK_NULL_HANDLE;
    VPLKIT_CHECK(vkCreateSampler(context.device(), &info, nullptr, &sampler));
    return sampler;
}

scene::Image solid_image(const char* name, uint8_t r, uint8_t g, uint8_t b, bool srgb, bool linear) {
    scene::Image image;
    image.name = name;
    image.width = 1;
    image.height = 1;
    image.rgba = {r, g, b, 255};
    image.srgb = srgb;
    image.linear = linear;
    return image;
}

vs::vec3 to_vec3(glm::vec3 v) {
    return {v.x, v.y, v.z};
}
vs::vec4 to_vec4(glm::vec4 v) {
    return {v.x, v.y, v.z, v.w};
}

}  // namespace

GpuScene GpuScene::create(Context& context, const scene::Scene& scene, const GpuSceneOptions& options) {
    const std::string what = "GPU scene '" + scene.source.string() + "'";
    const size_t triangles = scene.indices.size() / 3;
    if (triangles == 0 || scene.indices.size() % 3 != 0) {
        throw Error("vplkit: " + what + ": " + std::to_string(scene.indices.size()) +
                    " indices (needs a positive multiple of 3)");
    }
    if (scene.triangle_materials.size() != triangles) {
        throw Error("vplkit: " + what + ": " + std::to_string(scene.triangle_materials.size()) +
                    " triangle materials for " + std::to_string(triangles) + " triangles");
    }
    for (uint32_t index : scene.indices) {
        if (index >= scene.vertices.size()) {
            throw Error("vplkit: " + what + ": vertex index " + std::to_string(index) + " is outside the " +
                        std::to_string(scene.vertices.size()) + " vertices");
        }
    }
    for (uint32_t material : scene.triangle_materials) {
        if (material >= scene.materials.size()) {
            throw Error("vplkit: " + what + ": material " + std::to_string(material) + " is outside the " +
                        std::to_string(scene.materials.size()) + " materials");
        }
    }
    for (const scene::Texture& texture : scene.textures) {
        if (texture.image >= scene.images.size()) {
            throw Error("vplkit: " + what + ": a texture uses image " + std::to_string(texture.image) + " of " +
                        std::to_string(scene.images.size()));
        }
    }

    GpuScene g;
    g.context_ = &context;
    g.triangle_count_ = uint32_t(triangles);
    g.vertex_count_ = uint32_t(scene.vertices.size());

    // Draws: maximal runs of triangles of one material (primitive instances of one material that
    // the loader placed one after the other become one draw).
    for (uint32_t t = 0; t < triangles; ++t) {
        const uint32_t material = scene.triangle_materials[t];
        if (!g.draws_.empty() && g.draws_.back().material == material) {
            ++g.draws_.back().triangle_count;
        } else {
            g.draws_.push_back({t, 1, material});
        }
    }
    g.bounds_.min = g.bounds_.max = scene.vertices[scene.indices[0]].position;
    for (uint32_t index : scene.indices) {
        g.bounds_.min = glm::min(g.bounds_.min, scene.vertices[index].position);
        g.bounds_.max = glm::max(g.bounds_.max, scene.vertices[index].position);
    }

    // Device addresses for buffers past a binding's range (raster_scene.glsl; slower on lavapipe,
    // so only then); the usage is there either way, for a caller that forces the path.
    const uint64_t vertex_bytes = uint64_t(scene.vertices.size()) * sizeof(scene::Vertex);
    const uint64_t index_bytes = uint64_t(scene.indices.size()) * sizeof(uint32_t);
    const uint64_t range = context.info().max_storage_buffer_range;
    g.addressed_ = vertex_bytes > range || index_bytes > range;
    g.vertices_ = Buffer::create(context, vertex_bytes, kVertexUsage, MemoryUse::device, "scene vertices");
    g.vertices_.upload(scene.vertices);
    g.indices_ = Buffer::create(context, index_bytes,
                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT |
                                    VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                                MemoryUse::device, "scene indices");
    g.indices_.upload(scene.indices);

    std::vector<vs::SceneMaterial> materials(scene.materials.size());
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        const scene::Material& m = scene.materials[i];
        vs::SceneMaterial& out = materials[i];
        out.base_color_factor = to_vec4(m.base_color_factor);
        out.emission = to_vec3(m.emission());
        out.metallic_factor = m.metallic_factor;
        out.roughness_factor = m.roughness_factor;
        out.normal_scale = m.normal_scale;
        out.alpha_cutoff = m.alpha_mode == scene::AlphaMode::blend ? kBlendAsMaskCutoff : m.alpha_cutoff;
        auto rows = [](const scene::UvTransform& t, vs::vec4& u_row, vs::vec4& v_row) {
            u_row = to_vec4(glm::vec4(t.u_row(), float(t.tex_coord)));
            v_row = to_vec4(glm::vec4(t.v_row(), 0.0f));
        };
        rows(m.base_color_uv, out.base_color_u_row, out.base_color_v_row);
        rows(m.metallic_roughness_uv, out.metallic_roughness_u_row, out.metallic_roughness_v_row);
        rows(m.normal_uv, out.normal_u_row, out.normal_v_row);
        rows(m.emissive_uv, out.emissive_u_row, out.emissive_v_row);
        out.flags = (m.alpha_mode != scene::AlphaMode::opaque ? kAlphaTest : 0u) |
                    (m.normal_texture != scene::kNoTexture ? kNormalTexture : 0u) |
                    (m.double_sided ? kDoubleSided : 0u);
    }
    g.materials_ = Buffer::create(context, materials.size() * sizeof(vs::SceneMaterial),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "scene materials");
    g.materials_.upload(materials);

    g.images_.reserve(scene.images.size());
    for (size_t i = 0; i < scene.images.size(); ++i) {
        g.images_.push_back(TextureImage::create(context, scene.images[i], options.mipmaps, scene.images[i].name));
    }
    g.defaults_[0] = TextureImage::create(context, solid_image("default white", 255, 255, 255, true, true), false);
    g.defaults_[1] = TextureImage::create(context, solid_image("default normal", 128, 128, 255, false, true), false);

    g.samplers_.push_back(
        create_sampler(context, {scene::Wrap::clamp_to_edge, scene::Wrap::clamp_to_edge, scene::Filter::nearest,
                                 scene::Filter::nearest, scene::MipmapMode::none}));
    context.set_name(g.samplers_.back(), "default texture sampler");
    std::map<std::tuple<uint32_t, uint32_t, uint32_t, uint32_t, uint32_t>, VkSampler> samplers;
    auto sampler_for = [&](const scene::Sampler& s) {
        const auto key = std::make_tuple(uint32_t(s.wrap_s), uint32_t(s.wrap_t), uint32_t(s.mag_filter),
                                         uint32_t(s.min_filter), uint32_t(s.mipmap_mode));
        auto found = samplers.find(key);
        if (found != samplers.end()) return found->second;
        g.samplers_.push_back(create_sampler(context, s));
        samplers.emplace(key, g.samplers_.back());
        return g.samplers_.back();
    };

    constexpr VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    // A texture's image through the view its use calls for; the default when there is none.
    auto bind = [&](int32_t texture, bool srgb, const TextureImage& fallback, const char* use, size_t material) {
        if (texture == scene::kNoTexture) {
            return VkDescriptorImageInfo{g.samplers_[0], srgb ? fallback.srgb_view() : fallback.unorm_view(), layout};
        }
        if (texture < 0 || size_t(texture) >= scene.textures.size()) {
            throw Error("vplkit: " + what + ": material " + std::to_string(material) + " (" +
                        scene.materials[material].name + ") uses texture " + std::to_string(texture) + " of " +
                        std::to_string(scene.textures.size()));
        }
        const scene::Texture& t = scene.textures[size_t(texture)];
        const TextureImage& image = g.images_[t.image];
        const VkImageView view = srgb ? image.srgb_view() : image.unorm_view();
        if (!view) {
            throw Error("vplkit: " + what + ": image '" + image.name() + "' is the " + use + " texture of material '" +
                        scene.materials[material].name + "' but is not marked as " +
                        (srgb ? "colour (srgb)" : "data (linear)"));
        }
        return VkDescriptorImageInfo{sampler_for(t.sampler), view, layout};
    };
    g.material_textures_.resize(scene.materials.size());
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        const scene::Material& m = scene.materials[i];
        MaterialTextures& out = g.material_textures_[i];
        out.base_color = bind(m.base_color_texture, true, g.defaults_[0], "base colour", i);
        out.metallic_roughness = bind(m.metallic_roughness_texture, false, g.defaults_[0], "metallic-roughness", i);
        out.normal = bind(m.normal_texture, false, g.defaults_[1], "normal", i);
        // glTF: emission = factor x texture, and a missing texture counts as white (the factor alone).
        out.emissive = bind(m.emissive_texture, true, g.defaults_[0], "emissive", i);
    }
    return g;
}

GpuScene::~GpuScene() {
    release();
}

GpuScene::GpuScene(GpuScene&& other) noexcept {
    *this = std::move(other);
}

GpuScene& GpuScene::operator=(GpuScene&& other) noexcept {
    if (this != &other) {
        release();
        context_ = std::exchange(other.context_, nullptr);
        vertices_ = std::move(other.vertices_);
        previous_vertices_ = std::move(other.previous_vertices_);
        motion_ = std::exchange(other.motion_, false);
        addressed_ = std::exchange(other.addressed_, false);
        indices_ = std::move(other.indices_);
        materials_ = std::move(other.materials_);
        draws_ = std::move(other.draws_);
        images_ = std::move(other.images_);
        defaults_ = std::move(other.defaults_);
        samplers_ = std::exchange(other.samplers_, {});
        material_textures_ = std::move(other.material_textures_);
        bounds_ = other.bounds_;
        triangle_count_ = std::exchange(other.triangle_count_, 0);
        vertex_count_ = std::exchange(other.vertex_count_, 0);
    }
    return *this;
}

void GpuScene::release() {
    if (!context_) return;
    for (VkSampler sampler : samplers_) vkDestroySampler(context_->device(), sampler, nullptr);
    samplers_.clear();
    context_ = nullptr;
}

void GpuScene::update_vertices(const scene::Scene& scene) {
    if (scene.vertices.size() != vertex_count_ || scene.indices.size() != size_t(triangle_count_) * 3) {
        throw Error("GPU scene: a pose gave " + std::to_string(scene.vertices.size()) + " vertices and " +
                    std::to_string(scene.triangle_count()) + " triangles, the scene has " +
                    std::to_string(vertex_count_) + " and " + std::to_string(triangle_count_));
    }
    bounds_.min = bounds_.max = scene.vertices[scene.indices[0]].position;
    for (uint32_t index : scene.indices) {
        bounds_.min = glm::min(bounds_.min, scene.vertices[index].position);
        bounds_.max = glm::max(bounds_.max, scene.vertices[index].position);
    }
    // The pose drawn last becomes the previous one; a second pose before any frame keeps it.
    if (!motion_) {
        if (!previous_vertices_) {
            previous_vertices_ =
                Buffer::create(*context_, vertices_.size(), kVertexUsage, MemoryUse::device, "scene previous vertices");
        }
        std::swap(vertices_, previous_vertices_);
        motion_ = true;
    }
    vertices_.upload(scene.vertices);
}

BufferView GpuScene::begin_device_pose(StepList& passes) {
    if (!motion_) {
        const bool first = !previous_vertices_;
        if (first) {
            previous_vertices_ =
                Buffer::create(*context_, vertices_.size(), kVertexUsage, MemoryUse::device, "scene previous vertices");
        }
        std::swap(vertices_, previous_vertices_);
        motion_ = true;
        if (first) {
            // The new buffer is empty; the older pose an earlier swap leaves in it differs from
            // the previous one only in vertices every pose writes.
            const BufferView from = previous_vertices_, to = vertices_;
            passes.add("scene vertices copy", {Use::transfer_src(from), Use::transfer_dst(to)},
                       [from, to](VkCommandBuffer cmd) {
                           const VkBufferCopy region{0, 0, from.size};
                           vkCmdCopyBuffer(cmd, from.buffer, to.buffer, 1, &region);
                       });
        }
    }
    return vertices_;
}

}  // namespace vplkit
