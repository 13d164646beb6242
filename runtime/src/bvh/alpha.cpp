// add_alpha_tests: the alpha-test records of bvh.glsl (their layout is described there).

#include "vplkit/bvh_alpha.hpp"

#include "vplkit/error.hpp"

#include <bit>
#include <string>
#include <vector>

namespace vplkit {
namespace {

// glTF leaves blending to the renderer; the G-buffer draws a blended surface where it is at
// least half opaque (gpu_scene.cpp: kBlendAsMaskCutoff), and so must every ray.
constexpr float kBlendAsMaskCutoff = 0.5f;
constexpr uint32_t kTriangleRecordWords = 10;
constexpr uint32_t kMaterialRecordWords = 5;
constexpr uint32_t kNearestBit = 16;  // bvh.glsl's kBvhAlphaNearest

uint32_t wrap_code(scene::Wrap wrap) {
    switch (wrap) {
        case scene::Wrap::repeat:
            return 0;
        case scene::Wrap::clamp_to_edge:
            return 1;
        case scene::Wrap::mirrored_repeat:
            return 2;
    }
    return 0;
}

}  // namespace

AlphaTestStats add_alpha_tests(Bvh& bvh, const scene::Scene& scene) {
    AlphaTestStats stats;
    bvh.alpha.clear();
    for (auto& tri : bvh.triangles) tri.alpha = 0;
    const size_t triangle_count = scene.indices.size() / 3;

    // Material records, for the materials that may cut something out; 0 = opaque.
    std::vector<uint32_t> material_record(scene.materials.size(), 0);
    std::vector<float> cutoffs(scene.materials.size(), 0.0f);
    std::vector<uint32_t> words = {0};  // word 0: no record starts there
    std::vector<int32_t> texture_data(scene.images.size(), -1);
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const scene::Material& material = scene.materials[m];
        if (material.alpha_mode == scene::AlphaMode::opaque) continue;
        cutoffs[m] = material.alpha_mode == scene::AlphaMode::blend ? kBlendAsMaskCutoff : material.alpha_cutoff;
        const uint32_t record = uint32_t(words.size());
        words.insert(words.end(), {std::bit_cast<uint32_t>(cutoffs[m]), 0u, 0u, 0u, 0u});
        if (material.base_color_texture != scene::kNoTexture) {
            const scene::Texture& texture = scene.textures.at(size_t(material.base_color_texture));
            const scene::Image& image = scene.images.at(texture.image);
            words[record + 1] = image.width;
            words[record + 2] = image.height;
            words[record + 3] = wrap_code(texture.sampler.wrap_s) | (wrap_code(texture.sampler.wrap_t) << 2) |
                                (texture.sampler.mag_filter == scene::Filter::nearest ? kNearestBit : 0u);
            words[record + 4] = 0;  // patched below, once the texture bytes have a place
        }
        material_record[m] = record;
        ++stats.masked_materials;
    }
    // Texture alpha bytes after the material records, each image once.
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const uint32_t record = material_record[m];
        if (!record || words[record + 1] == 0) continue;
        const uint32_t image_index = scene.textures[size_t(scene.materials[m].base_color_texture)].image;
        if (texture_data[image_index] < 0) {
            const scene::Image& image = scene.images[image_index];
            const size_t texels = size_t(image.width) * image.height;
            texture_data[image_index] = int32_t(words.size());
            words.resize(words.size() + (texels + 3) / 4, 0u);
            uint32_t* data = words.data() + texture_data[image_index];
            for (size_t i = 0; i < texels; ++i) data[i / 4] |= uint32_t(image.rgba[4 * i + 3]) << (8 * (i % 4));
            stats.texture_bytes += uint32_t(texels);
        }
        words[record + 4] = uint32_t(texture_data[image_index]);
    }
    if (stats.masked_materials == 0) return stats;

    // Triangle records, where the alpha can fall below the cutoff.
    for (auto& tri : bvh.triangles) {
        const uint32_t t = tri.id;
        if (t >= triangle_count) {
            throw Error("add_alpha_tests: BVH triangle id " + std::to_string(t) + " is not one of the scene's " +
                        std::to_string(triangle_count) + " triangles");
        }
        const uint32_t m = scene.triangle_materials[t];
        const uint32_t record = material_record[m];
        if (!record) continue;
        const scene::Material& material = scene.materials[m];
        const scene::Vertex* corner[3] = {&scene.vertices[scene.indices[3 * t]],
                                          &scene.vertices[scene.indices[3 * t + 1]],
                                          &scene.vertices[scene.indices[3 * t + 2]]};
        float alpha[3];
        bool all_pass = words[record + 1] == 0;  // with a texture, the texels decide
        for (int k = 0; k < 3; ++k) {
            alpha[k] = material.base_color_factor.a * corner[k]->color.a;
            all_pass = all_pass && alpha[k] >= cutoffs[m];
        }
        if (all_pass) continue;  // alpha is linear over the triangle: it passes everywhere
        tri.alpha = uint32_t(words.size());
        for (int k = 0; k < 3; ++k) {
            // The texture's own coordinates (set and KHR_texture_transform): the transform is
            // affine, so interpolating transformed corners is transforming the interpolation.
            const scene::UvTransform& t = material.base_color_uv;
            const glm::vec2 uv = t.apply(t.tex_coord == 1 ? corner[k]->uv1 : corner[k]->uv0);
            words.push_back(std::bit_cast<uint32_t>(uv.x));
            words.push_back(std::bit_cast<uint32_t>(uv.y));
        }
        for (int k = 0; k < 3; ++k) words.push_back(std::bit_cast<uint32_t>(alpha[k]));
        words.push_back(record);
        ++stats.tested_triangles;
    }
    static_assert(kTriangleRecordWords == 10 && kMaterialRecordWords == 5, "the layout bvh.glsl reads");
    if (stats.tested_triangles > 0) bvh.alpha = std::move(words);
    return stats;
}

}  // namespace vplkit
