#pragma once
// A scene::Scene uploaded once for the raster stages (G-buffer, shadow maps): vertex, index and
// material buffers, textures with mip chains and the views they are sampled through, samplers,
// and the 1x1 default textures a material without a texture binds. Shaders read it through
// shaders/include/vplkit/raster_scene.glsl (vertices, indices) and raster_material.glsl
// (materials, textures).
//
//   auto gpu = vplkit::GpuScene::create(context, scene);
//   for (const vplkit::GpuDraw& d : gpu.draws()) { /* push gpu.textures(d.material), draw d */ }

#include "vplkit/buffer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/stages/scene_buffers.hpp"
#include "vplkit/steps.hpp"

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace vplkit {

class Context;

// An RGBA8 2D texture with a mip chain and up to two views of the same texels: sRGB (colour data,
// decoded to linear by the sampler) and UNORM (plain data). The image's own format is the sRGB one
// when only the sRGB view exists, else UNORM (then mip levels are averaged in UNORM space, which
// is wrong by a few percent for the sRGB view of an image used both ways: rare, glTF images are
// either colour or data). After create() the whole chain is in SHADER_READ_ONLY_OPTIMAL and never
// changes, so passes that sample it need no barrier and need not declare it in a PassList.
class TextureImage {
public:
    // Uploads `image` (rows top to bottom) and, when `mipmaps` is true, generates every level down
    // to 1x1 with linear-filtered vkCmdBlitImage (each level the box average of the one above).
    // Where the device cannot blit the format with linear filtering, the texture keeps one level
    // (mip_levels() == 1). Throws Error for an empty image, a size that does not match its bytes,
    // or an image that is neither srgb nor linear.
    static TextureImage create(Context& context, const scene::Image& image, bool mipmaps, std::string_view name = {});

    TextureImage() = default;
    ~TextureImage();
    TextureImage(TextureImage&& other) noexcept;
    TextureImage& operator=(TextureImage&& other) noexcept;
    TextureImage(const TextureImage&) = delete;
    TextureImage& operator=(const TextureImage&) = delete;
    // Exchanges everything the two hold; the moves are built on it (a moved-from texture is empty).
    void swap(TextureImage& other) noexcept;

    VkImage handle() const { return image_; }
    VkFormat format() const { return format_; }
    // VK_NULL_HANDLE for a view the image was not created with.
    VkImageView srgb_view() const { return srgb_view_; }
    VkImageView unorm_view() const { return unorm_view_; }
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    uint32_t mip_levels() const { return mip_levels_; }
    const std::string& name() const { return name_; }

    // The texels of one mip level (RGBA8 rows, top to bottom), read back through a staging buffer.
    std::vector<uint8_t> download(uint32_t level) const;

private:
    void release();

    Context* context_ = nullptr;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView srgb_view_ = VK_NULL_HANDLE;
    VkImageView unorm_view_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    uint32_t width_ = 0;
    uint32_t height_ = 0;
    uint32_t mip_levels_ = 0;
    std::string name_;
};

struct GpuSceneOptions {
    // Generate mip chains (without them, minified textures alias: Sponza's floor shimmers).
    bool mipmaps = true;
};

class GpuScene {
public:
    // Uploads `scene` (blocking). Reads vertices, indices, triangle_materials, materials, textures
    // and images (not primitives or bounds: bounds() is computed from the indexed vertices, so a
    // scene built by hand needs only those). Throws Error for a scene without triangles, an index,
    // material, texture or image out of range, or a texture used as colour (data) whose image is
    // not marked srgb (linear).
    static GpuScene create(Context& context, const scene::Scene& scene, const GpuSceneOptions& options = {});

    GpuScene() = default;
    GpuScene(GpuScene&& other) noexcept;
    GpuScene& operator=(GpuScene&& other) noexcept;
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;
    ~GpuScene();

    // A pose's new vertices (vplkit/scene_pose.hpp: the same triangles, moved): uploaded, bounds()
    // recomputed. The pose drawn last stays as the previous pose (the G-buffer's motion: a second
    // buffer, made at the first pose, the two swapped after that: no copy) until settle_motion.
    // Throws Error for a scene of another vertex count.
    void update_vertices(const scene::Scene& scene);
    // A pose written on the device instead (GpuPose::add_pose_pass into the returned buffer,
    // recorded after this call's steps): the previous pose is kept as update_vertices keeps it
    // (the two buffers swapped; at the first pose a "scene vertices copy" step fills the second
    // buffer, so what does not move stays as it was). bounds() stays as it was until set_bounds.
    // Nothing is uploaded. The buffer stays valid until the next update.
    BufferView begin_device_pose(StepList& passes);
    // The bounds of a pose the host did not see (e.g. a refitted BVH's root box: conservative).
    void set_bounds(const scene::Bounds& bounds) { bounds_ = bounds; }

    // A frame was drawn with the current pose: it is the previous pose from now on (no motion
    // until the next update_vertices).
    void settle_motion() { motion_ = false; }
    bool has_motion() const { return motion_; }

    // scene::Vertex[] (72 bytes each; storage, vertex-buffer and device-address usage).
    const Buffer& vertices() const { return vertices_; }
    // uint32 x 3 per triangle, global vertex indices (storage, index-buffer and device-address usage).
    const Buffer& indices() const { return indices_; }
    // shaders::SceneMaterial[], one per scene material (storage usage).
    const Buffer& materials() const { return materials_; }

    std::span<const GpuDraw> draws() const { return draws_; }
    const MaterialTextures& textures(uint32_t material) const { return material_textures_.at(material); }

    // As the raster stages take it (the draws and textures stay in this object).
    // previous_vertices only while a pose has not been drawn (has_motion).
    operator stages::SceneBuffers() const {
        const BufferView previous = motion_ ? BufferView(previous_vertices_) : BufferView{};
        return {vertices_, indices_, materials_, draws_, material_textures_, previous, addressed_};
    }
    // Whether the raster stages read vertices and indices at their device addresses
    // (SceneBuffers::addressed): only when a buffer is larger than maxStorageBufferRange.
    bool addressed() const { return addressed_; }

    const scene::Bounds& bounds() const { return bounds_; }
    uint32_t triangle_count() const { return triangle_count_; }
    uint32_t vertex_count() const { return vertex_count_; }
    uint32_t material_count() const { return uint32_t(material_textures_.size()); }
    // The scene's images, in Scene::images order.
    std::span<const TextureImage> images() const { return images_; }

private:
    void release();

    Context* context_ = nullptr;
    Buffer vertices_;
    Buffer previous_vertices_;  // the pose drawn last, once the scene was posed
    bool motion_ = false;       // vertices_ moved since previous_vertices_ was drawn
    bool addressed_ = false;
    Buffer indices_;
    Buffer materials_;
    std::vector<GpuDraw> draws_;
    std::vector<TextureImage> images_;
    // White (base colour, metallic-roughness), flat normal, black (emissive).
    std::array<TextureImage, 2> defaults_;  // white (colour and data), flat normal
    // One per distinct scene::Sampler, and one for the defaults (index 0).
    std::vector<VkSampler> samplers_;
    std::vector<MaterialTextures> material_textures_;
    scene::Bounds bounds_;
    uint32_t triangle_count_ = 0;
    uint32_t vertex_count_ = 0;
};

}  // namespace vplkit
