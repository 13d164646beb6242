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

// The cutoff a material's alpha is tested against; negative for an OPAQUE material.
float cutoff_of(const scene::Material& material) {
    switch (material.alpha_mode) {
        case scene::AlphaMode::opaque:
            return -1.0f;
        case scene::AlphaMode::blend:
            return kBlendAsMaskCutoff;
        case scene::AlphaMode::mask:
            return material.alpha_cutoff;
    }
    return -1.0f;
}

// The corners' alpha (base colour factor x COLOR_0 alpha) of scene triangle t, and whether it can
// fall below `cutoff` somewhere: with a texture the texels decide; without, alpha is linear over
// the triangle, so it passes everywhere when it passes at the corners.
bool may_cut_out(const scene::Scene& scene, uint32_t t, float cutoff, float alpha[3]) {
    const scene::Material& material = scene.materials[scene.triangle_materials[t]];
    bool all_pass = material.base_color_texture == scene::kNoTexture;
    for (int k = 0; k < 3; ++k) {
        alpha[k] = material.base_color_factor.a * scene.vertices[scene.indices[3 * t + k]].color.a;
        all_pass = all_pass && alpha[k] >= cutoff;
    }
    return !all_pass;
}

}  // namespace

std::vector<uint8_t> alpha_tested_triangles(const scene::Scene& scene) {
    const size_t triangle_count = scene.indices.size() / 3;
    std::vector<uint8_t> tested(triangle_count, 0);
    for (size_t t = 0; t < triangle_count; ++t) {
        const float cutoff = cutoff_of(scene.materials[scene.triangle_materials[t]]);
        float alpha[3];
        tested[t] = cutoff >= 0.0f && may_cut_out(scene, uint32_t(t), cutoff, alpha) ? 1 : 0;
    }
    return tested;
}

Bvh build_scene_bvh(const scene::Scene& scene, AlphaTestStats* stats) {
    const std::vector<uint8_t> tested = alpha_tested_triangles(scene);
    Bvh bvh = build_bvh_split(scene::triangle_positions(scene), tested);
    const AlphaTestStats s = add_alpha_tests(bvh, scene);
    if (stats) *stats = s;
    return bvh;
}

AlphaTestStats add_alpha_tests(Bvh& bvh, const scene::Scene& scene) {
    AlphaTestStats stats;
    bvh.alpha.clear();
    for (auto& tri : bvh.triangles) tri.alpha = 0;
    const size_t triangle_count = scene.indices.size() / 3;

    // Material records, for the materials that may cut something out; 0 = opaque.
    std::vector<uint32_t> material_record(scene.materials.size(), 0);
    std::vector<float> cutoffs(scene.materials.size(), 0.0f);
    // The header's words (bvh.glsl): no record starts there; the upload fills all but word 0.
    std::vector<uint32_t> words(kBvhHeaderWords, 0u);
    std::vector<int32_t> texture_data(scene.images.size(), -1);
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const scene::Material& material = scene.materials[m];
        if (material.alpha_mode == scene::AlphaMode::opaque) continue;
        cutoffs[m] = cutoff_of(material);
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
        if (!may_cut_out(scene, t, cutoffs[m], alpha)) continue;  // no cost where nothing is cut out
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
    if (stats.tested_triangles == 0) return stats;
    // A split BVH (build_bvh_split) is traversed as two subtrees only when its opaque subtree holds
    // no triangle with a record (built with alpha_tested_triangles' flags); otherwise word 0 stays
    // 0 and the traversal tests the whole tree from node 0, which is right for any tree.
    bool split = bvh.masked_root != 0;
    for (uint32_t i = 0; split && i < bvh.opaque_triangles && i < bvh.triangles.size(); ++i) {
        split = bvh.triangles[i].alpha == 0;
    }
    words[0] = split ? bvh.masked_root : 0u;
    bvh.alpha = std::move(words);
    return stats;
}

}  // namespace vplkit
