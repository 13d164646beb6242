// raster_timing: GPU time of the G-buffer pass and of one shadow map pass on a real scene (not a
// test: timings are never asserted). Prints the median over runs of each pass's timestamp time.
//
//   raster_timing SCENE.gltf|SETUP [--size WxH] [--rsm N] [--sun DX,DY,DZ,R,G,B,I] [--runs K] [--dump DIR]
//                 [--addressed 0|1]
//
// --addressed 1 reads vertices and indices at their device addresses (SceneBuffers::addressed)
// even where they fit a binding, 0 through bindings even where they do not (the default: the
// GpuScene's choice).
//
// --dump writes PNGs of the G-buffer's albedo and normal and the RSM's flux (normalized to its
// brightest texel) and normal into DIR, to look at.
//
// SETUP is a name from scenes/setups.txt (e.g. sponza-sun): its scene, camera and first sun.
// A .gltf/.glb path uses the file's camera (or the generated one) and --sun (default: the
// sponza-sun set-up's).

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/image.hpp"
#include "vplkit/image_io.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_lights.hpp"
#include "vplkit/scene_setups.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/shadow_map.hpp"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    try {
        if (argc < 2) {
            std::fprintf(stderr,
                         "usage: raster_timing SCENE.gltf|SETUP [--size WxH] [--rsm N] [--sun DX,DY,DZ,R,G,B,I] "
                         "[--runs K] [--dump DIR] [--addressed 0|1]\n");
            return 2;
        }
        const std::string target = argv[1];
        uint32_t width = 640, height = 360, rsm = 512, runs = 5;
        std::string sun = "0.3,-1,-0.15,1,0.95,0.85,5";
        bool sun_given = false;
        std::string dump;
        int addressed = -1;
        for (int i = 2; i + 1 < argc; i += 2) {
            const std::string key = argv[i], value = argv[i + 1];
            if (key == "--size") {
                if (std::sscanf(value.c_str(), "%ux%u", &width, &height) != 2)
                    throw vplkit::Error("bad --size " + value);
            } else if (key == "--rsm") {
                rsm = uint32_t(std::stoul(value));
            } else if (key == "--sun") {
                sun = value;
                sun_given = true;
            } else if (key == "--dump") {
                dump = value;
            } else if (key == "--addressed") {
                addressed = std::stoi(value) != 0;
            } else if (key == "--runs") {
                runs = std::max(1u, uint32_t(std::stoul(value)));
            } else {
                throw vplkit::Error("unknown option " + key);
            }
        }
        vplkit::ContextOptions options;
        auto ctx = vplkit::Context::create(options);
        std::printf("device: %s\n", ctx->info().name.c_str());
        const bool is_file = target.ends_with(".gltf") || target.ends_with(".glb");
        std::optional<vplkit::scene::Setup> setup;
        if (!is_file) {
            const auto setups =
                vplkit::scene::load_setups(std::filesystem::path(VPLKIT_SOURCE_DIR) / "scenes/setups.txt");
            setup = setups.find(target);
        }
        const auto t0 = std::chrono::steady_clock::now();
        const vplkit::scene::Scene scene =
            vplkit::scene::load_gltf(setup ? vplkit::scene::require_scene(*setup) : std::filesystem::path(target));
        const auto t1 = std::chrono::steady_clock::now();
        const vplkit::scene::Camera camera = setup ? vplkit::scene::setup_camera(*setup, scene.bounds) : scene.camera();
        vplkit::scene::Light light = vplkit::scene::parse_sun(sun);
        if (setup && !sun_given) {
            for (const auto& l : setup->lights) {
                if (l.type == vplkit::scene::LightType::directional) {
                    light = l;
                    break;
                }
            }
        }
        auto gpu = vplkit::GpuScene::create(*ctx, scene);
        const auto t2 = std::chrono::steady_clock::now();
        std::printf("scene: %zu triangles, %zu materials, %zu images, %zu draws; load %.0f ms, upload %.0f ms\n",
                    scene.triangle_count(), scene.materials.size(), scene.images.size(), gpu.draws().size(),
                    std::chrono::duration<double, std::milli>(t1 - t0).count(),
                    std::chrono::duration<double, std::milli>(t2 - t1).count());

        auto images = vplkit::GbufferImages::create(*ctx, width, height);
        const auto view = vplkit::camera_view(camera, width, height);
        auto map = vplkit::ShadowMap::create(*ctx, light, gpu.bounds(), rsm);
        vplkit::stages::SceneBuffers buffers = gpu;
        if (addressed >= 0) buffers.addressed = addressed != 0;
        std::printf("vertices and indices read %s\n", buffers.addressed ? "at device addresses" : "through bindings");
        vplkit::PassList passes("raster timing");
        vplkit::stages::add_gbuffer_pass(*ctx, passes, buffers, view, images);
        vplkit::stages::add_shadow_map_pass(*ctx, passes, buffers, map);
        std::vector<double> gbuffer_ms, rsm_ms;
        for (uint32_t run = 0; run < runs + 1; ++run) {
            passes.run(*ctx);
            if (run == 0) continue;  // the first run pays for pipeline compilation
            gbuffer_ms.push_back(passes.timings()[0].gpu_ms);
            rsm_ms.push_back(passes.timings()[1].gpu_ms);
        }
        auto median = [](std::vector<double> v) {
            std::sort(v.begin(), v.end());
            return v[v.size() / 2];
        };
        std::printf("gbuffer %ux%u: %.2f ms median of %u\n", width, height, median(gbuffer_ms), runs);
        std::printf("shadow map (sun) %ux%u: %.2f ms median of %u\n", rsm, rsm, median(rsm_ms), runs);
        if (!dump.empty()) {
            std::filesystem::create_directories(dump);
            // Unit vectors as 0.5 + 0.5 n; colours clamped; flux scaled by its maximum.
            auto write = [&](const char* name, vplkit::Image& image, float scale, float offset) {
                const auto texels = image.download<float>();
                std::vector<uint8_t> rgba(size_t(image.width()) * image.height() * 4, 255);
                for (size_t i = 0; i < rgba.size() / 4; ++i) {
                    for (int c = 0; c < 3; ++c) {
                        const float v = std::clamp(texels[4 * i + c] * scale + offset, 0.0f, 1.0f);
                        rgba[4 * i + c] = uint8_t(v * 255.0f + 0.5f);
                    }
                }
                vplkit::write_png(std::filesystem::path(dump) / name, image.width(), image.height(), rgba);
            };
            write("gbuffer_normal.png", images.normal, 0.5f, 0.5f);
            write("rsm_normal.png", map.normal, 0.5f, 0.5f);
            const auto flux = map.flux.download<float>();
            float brightest = 0.0f;
            for (float f : flux) brightest = std::max(brightest, f);
            write("rsm_flux.png", map.flux, brightest > 0.0f ? 1.0f / brightest : 1.0f, 0.0f);
            // Albedo (RGBA16F, linear) sRGB-encoded for viewing.
            const auto halves = images.albedo.download<uint16_t>();
            std::vector<uint8_t> rgba(size_t(width) * height * 4, 255);
            for (size_t i = 0; i < rgba.size() / 4; ++i) {
                for (int c = 0; c < 3; ++c) {
                    const float linear = std::clamp(glm::unpackHalf1x16(halves[4 * i + c]), 0.0f, 1.0f);
                    const float encoded =
                        linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
                    rgba[4 * i + c] = uint8_t(encoded * 255.0f + 0.5f);
                }
            }
            vplkit::write_png(std::filesystem::path(dump) / "gbuffer_albedo.png", width, height, rgba);
            std::printf("wrote %s/{gbuffer_albedo,gbuffer_normal,rsm_flux,rsm_normal}.png\n", dump.c_str());
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raster_timing: %s\n", e.what());
        return 1;
    }
}
