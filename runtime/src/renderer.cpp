#include "vplkit/renderer.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/stages/gbuffer.hpp"
#include "vplkit/stages/gbuffer_images.hpp"
#include "vplkit/stages/tonemap.hpp"

#include <array>
#include <chrono>
#include <string>

namespace vplkit {

DirectRenderer::DirectRenderer(Context& context, const scene::Scene& scene) : context_(context) {
    if (scene.lights.empty() && scene.emissive_triangles.empty()) {
        throw Error(scene.source.string() +
                    ": the scene has no light (no punctual light, no emissive triangle): its image would be black; "
                    "add one with --sun or --point");
    }
    scene_ = GpuScene::create(context, scene);
    const auto start = std::chrono::steady_clock::now();
    bvh_ = build_bvh(scene::triangle_positions(scene));
    bvh_build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    gpu_bvh_ = upload_bvh(context, bvh_);
    lights_ = stages::upload_lights(context, scene.lights);
    emitters_ = stages::upload_emitters(context, scene);
}

RenderedImage DirectRenderer::render(const scene::Camera& camera, const RenderSettings& settings) {
    auto gbuffer = stages::GbufferImages::create(context_, settings.width, settings.height);
    auto radiance = Image::create(context_, settings.width, settings.height, VK_FORMAT_R32G32B32A32_SFLOAT,
                                  VK_IMAGE_USAGE_STORAGE_BIT, "radiance");
    auto display = Image::create(context_, settings.width, settings.height, VK_FORMAT_R8G8B8A8_UNORM,
                                 VK_IMAGE_USAGE_STORAGE_BIT, "display");
    auto stats = Buffer::create(context_, stages::kTonemapStatsBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                MemoryUse::device, "tonemap stats");
    const stages::CameraView view = stages::camera_view(camera, settings.width, settings.height);

    PassList passes("direct frame");
    stages::add_gbuffer_pass(context_, passes, scene_, view, gbuffer);
    stages::add_direct_light_pass(context_, passes, gbuffer, gpu_bvh_, lights_, {view.position, settings.background},
                                  radiance);
    stages::add_direct_emissive_pass(context_, passes, gbuffer, gpu_bvh_, emitters_,
                                     {view.position, settings.emissive_samples, settings.seed}, radiance);
    stages::add_tonemap_passes(context_, passes, radiance, display, stats, settings.exposure);
    passes.run(context_);

    RenderedImage out;
    out.width = settings.width;
    out.height = settings.height;
    out.timings = passes.timings();
    out.rgba8 = display.download<uint8_t>();
    const auto texels = radiance.download<std::array<float, 4>>();
    out.radiance.reserve(texels.size() * 3);
    for (const auto& t : texels) {
        out.radiance.insert(out.radiance.end(), {t[0], t[1], t[2]});
    }
    out.non_finite_pixels = stats.download<uint32_t>(1)[0];
    return out;
}

}  // namespace vplkit
