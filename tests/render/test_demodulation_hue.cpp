// Demodulation on a texture whose channels span 0..1 per texel (the issue: green and cyan specks
// on Sponza's dark-red curtains). The in-repo Cornell box (point light), every material white under
// a 16 x 16 texture of random sRGB bytes (nearest filtering, so neighbouring pixels see unrelated
// albedos; about 15% of the channels are below 0.02 in linear, 1.5% below 0.001), 64 x 64, hybrid
// 8 spp over 512 one-bounce instant-radiosity VPLs. Three ways of filtering the indirect light (half
// resolution alone, svgf alone, both: the main job's options), each averaged over 16 frames, against
// the per-pixel mean of 16 raw full-resolution frames.
//
// A hue outlier: a pixel whose share of one channel in its indirect light (c / (r + g + b)) is more
// than 0.3 above the raw mean's. The light is about grey everywhere (white materials), so a
// correctly filtered pixel keeps its albedo's hue: the filters blur irradiance and the pixel's own
// albedo brings the hue back. A channel that takes its neighbours' irradiance times 1 instead of
// times its ~0 albedo (the old "divide only above min_albedo" rule) shifts that share by 0.3 to 1.
// Only pixels whose raw mean is brighter than a tenth of the image's median are judged (the hue of
// a near-black pixel is noise).
// Measured (outliers of 4096: half / svgf / both): the old rule 292 / 35 / 35; a floor of 0.02:
// 1 / 0 / 0 (a specular term divided by a dark channel's floor); the floor of 0.04: 0 / 0 / 0.

#include "vplkit/context.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#ifndef VPLKIT_SOURCE_DIR
#error "VPLKIT_SOURCE_DIR must be defined by the build"
#endif

namespace {

constexpr const char* kCornellPoint = VPLKIT_SOURCE_DIR "/scenes/cornell_point/cornell_point.gltf";
constexpr uint32_t kSize = 64;

// Every material multiplied by one noisy texture, mapped by a planar projection along each
// vertex's dominant normal axis (the box's faces are axis-aligned), twice across the box.
vplkit::scene::Scene noisy_texture_scene() {
    auto scene = vplkit::scene::load_gltf(kCornellPoint);
    vplkit::scene::Image image;
    image.name = "noise";
    image.width = image.height = 16;
    image.srgb = true;
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> byte(0, 255);
    image.rgba.resize(size_t(image.width) * image.height * 4);
    for (size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = uint8_t(i % 4 == 3 ? 255 : byte(rng));
    vplkit::scene::Texture texture;
    texture.image = uint32_t(scene.images.size());
    texture.sampler.mag_filter = vplkit::scene::Filter::nearest;
    texture.sampler.min_filter = vplkit::scene::Filter::nearest;
    texture.sampler.mipmap_mode = vplkit::scene::MipmapMode::none;
    scene.images.push_back(image);
    const int32_t texture_index = int32_t(scene.textures.size());
    scene.textures.push_back(texture);
    for (auto& material : scene.materials) {
        if (material.emits()) continue;
        // White under the texture: the indirect light is then about grey everywhere, and each
        // pixel's hue is its albedo's (no red and green walls tinting the light).
        material.base_color_factor = glm::vec4(1.0f);
        material.base_color_texture = texture_index;
        material.base_color_uv = {};
    }
    const glm::vec3 lo = scene.bounds.min, extent = scene.bounds.max - scene.bounds.min;
    for (auto& v : scene.vertices) {
        const glm::vec3 n = glm::abs(v.normal);
        const glm::vec3 t = (v.position - lo) / extent * 2.0f;
        v.uv0 = n.x >= n.y && n.x >= n.z ? glm::vec2(t.y, t.z) : n.y >= n.z ? glm::vec2(t.x, t.z) : glm::vec2(t.x, t.y);
    }
    return scene;
}

vplkit::RenderSettings frame_settings() {
    vplkit::RenderSettings s;
    s.width = kSize;
    s.height = kSize;
    s.method = vplkit::GiMethod::hybrid;
    // Instant radiosity: the same VPLs at full and half resolution (BRSM places them through the
    // G-buffer, so half resolution would also change the VPL set).
    s.vpl_source = vplkit::VplSource::ir;
    s.vpl_paths = 512;
    s.vpl_bounces = 1;
    s.samples_per_pixel = 8;
    return s;
}

// The mean of `frames` consecutive frames' indirect light (from frame 0: the denoiser's history
// starts afresh), so that one frame's noise does not pass for a hue shift.
std::vector<double> mean_of_frames(vplkit::Renderer& renderer, const vplkit::scene::Scene& scene,
                                   vplkit::RenderSettings s, uint32_t frames) {
    std::vector<double> mean;
    for (uint32_t f = 0; f < frames; ++f) {
        s.frame = f;
        const auto image = renderer.render(scene.camera(), s);
        if (mean.empty()) mean.assign(image.indirect.size(), 0.0);
        for (size_t i = 0; i < mean.size(); ++i) mean[i] += image.indirect[i] / double(frames);
    }
    return mean;
}

int hue_outliers(const std::vector<double>& image, const std::vector<double>& reference) {
    std::vector<double> sums;
    for (size_t p = 0; p < reference.size() / 3; ++p)
        sums.push_back(reference[3 * p] + reference[3 * p + 1] + reference[3 * p + 2]);
    std::vector<double> sorted = sums;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double bright_enough = 0.1 * sorted[sorted.size() / 2];
    int outliers = 0;
    for (size_t p = 0; p < sums.size(); ++p) {
        const double sum = image[3 * p] + image[3 * p + 1] + image[3 * p + 2];
        if (sums[p] <= bright_enough || sum <= 0.0) continue;
        bool outlier = false;
        for (int c = 0; c < 3; ++c) outlier |= image[3 * p + c] / sum - reference[3 * p + c] / sums[p] > 0.3;
        outliers += outlier ? 1 : 0;
    }
    return outliers;
}

}  // namespace

TEST_CASE("denoise render: no hue outliers on a texture whose channels span 0..1 (half resolution, svgf)") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto scene = noisy_texture_scene();
    vplkit::Renderer renderer(ctx, scene);

    constexpr uint32_t kFrames = 16;
    const std::vector<double> raw = mean_of_frames(renderer, scene, frame_settings(), kFrames);

    auto half = frame_settings();
    half.half_resolution_gi = true;
    auto svgf = frame_settings();
    svgf.denoise = vplkit::DenoiseMode::svgf;
    auto both = svgf;
    both.half_resolution_gi = true;
    const int half_outliers = hue_outliers(mean_of_frames(renderer, scene, half, kFrames), raw);
    const int svgf_outliers = hue_outliers(mean_of_frames(renderer, scene, svgf, kFrames), raw);
    const int both_outliers = hue_outliers(mean_of_frames(renderer, scene, both, kFrames), raw);
    INFO("hue outliers of 4096 pixels: half " << half_outliers << ", svgf " << svgf_outliers << ", half + svgf "
                                              << both_outliers);
    CHECK(half_outliers == 0);
    CHECK(svgf_outliers == 0);
    CHECK(both_outliers == 0);
}
