// measure_motion_ghosting: how much of a turning block's old light the denoiser drags along (not a
// test; its figures are in the report). The animated box (scenes/animated_box) with only its
// 'turn' animation (the light still), F frames at 24 per second, each filtered frame's indirect
// light against the exact gather over the same VPLs (the same seed: only the gather's noise and
// the filter's history differ), on the block's pixels (those with motion) and on the rest, for
// each RenderSettings::denoise_motion: follow (the G-buffer's motion), camera_only (the history
// reprojected with the camera alone: the trail), drop (history started again every moving frame).
//   measure_motion_ghosting [frames=12] [size=64] [temporal|svgf] [spp=8]

#include "vplkit/context.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_pose.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

const std::string kScene = std::string(VPLKIT_SOURCE_DIR) + "/scenes/animated_box/animated_box.gltf";

struct Residual {
    double block = 0.0, rest = 0.0;  // sum |filtered - exact| / sum exact over the pixels' channels
};

Residual residual(const vplkit::RenderedImage& filtered, const vplkit::RenderedImage& exact) {
    double block_error = 0.0, block_sum = 0.0, rest_error = 0.0, rest_sum = 0.0;
    for (size_t i = 0; i < exact.indirect.size(); i += 3) {
        const bool moving =
            filtered.motion[i] != 0.0f || filtered.motion[i + 1] != 0.0f || filtered.motion[i + 2] != 0.0f;
        for (size_t c = 0; c < 3; ++c) {
            const double e = std::abs(double(filtered.indirect[i + c]) - exact.indirect[i + c]);
            (moving ? block_error : rest_error) += e;
            (moving ? block_sum : rest_sum) += exact.indirect[i + c];
        }
    }
    return {block_sum > 0.0 ? block_error / block_sum : 0.0, rest_sum > 0.0 ? rest_error / rest_sum : 0.0};
}

}  // namespace

int main(int argc, char** argv) {
    const uint32_t frames = argc > 1 ? uint32_t(std::atoi(argv[1])) : 12;
    const uint32_t size = argc > 2 ? uint32_t(std::atoi(argv[2])) : 64;
    const bool svgf = argc > 3 && std::strcmp(argv[3], "svgf") == 0;
    const uint32_t spp = argc > 4 ? uint32_t(std::atoi(argv[4])) : 8;
    if (frames < 2 || size < 8 || spp < 1) {
        std::fprintf(stderr, "usage: measure_motion_ghosting [frames>=2] [size>=8] [temporal|svgf] [spp>=1]\n");
        return 2;
    }
    auto context = vplkit::Context::create({});
    vplkit::scene::LoadOptions load;
    load.animation = "turn";
    vplkit::RenderSettings settings;
    settings.width = settings.height = size;
    settings.method = vplkit::GiMethod::hybrid;
    settings.vpl_source = vplkit::VplSource::ir;
    settings.vpl_paths = 1024;
    settings.samples_per_pixel = spp;
    settings.denoise = svgf ? vplkit::DenoiseMode::svgf : vplkit::DenoiseMode::temporal;
    settings.read_back_aovs = true;
    vplkit::RenderSettings exact_settings = settings;
    exact_settings.method = vplkit::GiMethod::exact;
    exact_settings.denoise = vplkit::DenoiseMode::off;

    std::printf(
        "animated box, 'turn' only, %u frames at 24 fps, %ux%u, hybrid %u spp, %s; residual = sum |filtered "
        "- exact| / sum exact (indirect light, same VPLs)\n",
        frames, size, size, spp, svgf ? "svgf" : "temporal");
    std::printf("%-12s %8s %14s %14s %14s\n", "motion", "frame", "block", "rest", "block pixels");
    const struct {
        vplkit::DenoiseMotion motion;
        const char* name;
    } variants[] = {{vplkit::DenoiseMotion::follow, "follow"},
                    {vplkit::DenoiseMotion::camera_only, "camera_only"},
                    {vplkit::DenoiseMotion::drop, "drop"}};
    for (const auto& variant : variants) {
        vplkit::scene::PosableScene posable(kScene, load);
        vplkit::Renderer renderer(*context, posable.scene());
        vplkit::Renderer exact(*context, posable.scene());
        const vplkit::scene::Camera camera = posable.scene().camera();
        settings.denoise_motion = variant.motion;
        double block_mean = 0.0, rest_mean = 0.0;
        uint32_t counted = 0;
        for (uint32_t f = 0; f < frames; ++f) {
            if (f > 0) {
                const vplkit::scene::PoseChange change = posable.pose(double(f) / 24.0);
                renderer.update_pose(change);
                exact.update_pose(change);
            }
            settings.frame = exact_settings.frame = f;
            const vplkit::RenderedImage filtered = renderer.render(camera, settings);
            const vplkit::RenderedImage reference = exact.render(camera, exact_settings);
            const Residual r = residual(filtered, reference);
            size_t block_pixels = 0;
            for (size_t i = 0; i < filtered.motion.size(); i += 3) {
                block_pixels +=
                    filtered.motion[i] != 0.0f || filtered.motion[i + 1] != 0.0f || filtered.motion[i + 2] != 0.0f ? 1
                                                                                                                   : 0;
            }
            std::printf("%-12s %8u %14.4f %14.4f %14zu\n", variant.name, f + 1, r.block, r.rest, block_pixels);
            if (f >= frames / 2) {  // the second half: the history has had time to build (or trail)
                block_mean += r.block;
                rest_mean += r.rest;
                ++counted;
            }
        }
        std::printf("%-12s mean of frames %u-%u: block %.4f, rest %.4f\n", variant.name, frames / 2 + 1, frames,
                    block_mean / counted, rest_mean / counted);
    }
    return 0;
}
