// raster_timing: GPU time of the G-buffer pass and of one shadow map pass on a real scene (not a
// test: timings are never asserted). Prints the median over runs of each pass's timestamp time.
//
//   raster_timing SCENE.gltf [--size WxH] [--rsm N] [--sun DX,DY,DZ,R,G,B,I] [--runs K]

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_lights.hpp"
#include "vplkit/stages/gbuffer.hpp"
#include "vplkit/stages/gbuffer_images.hpp"
#include "vplkit/stages/shadow_maps.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    try {
        if (argc < 2) {
            std::fprintf(stderr, "usage: raster_timing SCENE.gltf [--size WxH] [--rsm N] [--sun DX,DY,DZ,R,G,B,I] [--runs K]\n");
            return 2;
        }
        std::string path = argv[1];
        uint32_t width = 640, height = 360, rsm = 512, runs = 5;
        std::string sun = "0.3,-1,-0.15,1,0.95,0.85,5";
        for (int i = 2; i + 1 < argc; i += 2) {
            const std::string key = argv[i], value = argv[i + 1];
            if (key == "--size") {
                if (std::sscanf(value.c_str(), "%ux%u", &width, &height) != 2) throw vplkit::Error("bad --size " + value);
            } else if (key == "--rsm") {
                rsm = uint32_t(std::stoul(value));
            } else if (key == "--sun") {
                sun = value;
            } else if (key == "--runs") {
                runs = uint32_t(std::stoul(value));
            } else {
                throw vplkit::Error("unknown option " + key);
            }
        }
        vplkit::ContextOptions options;
        auto ctx = vplkit::Context::create(options);
        std::printf("device: %s\n", ctx->info().name.c_str());
        const auto t0 = std::chrono::steady_clock::now();
        const vplkit::scene::Scene scene = vplkit::scene::load_gltf(path);
        const auto t1 = std::chrono::steady_clock::now();
        auto gpu = vplkit::GpuScene::create(*ctx, scene);
        const auto t2 = std::chrono::steady_clock::now();
        std::printf("scene: %zu triangles, %zu materials, %zu images, %zu draws; load %.0f ms, upload %.0f ms\n",
                    scene.triangle_count(), scene.materials.size(), scene.images.size(), gpu.draws().size(),
                    std::chrono::duration<double, std::milli>(t1 - t0).count(),
                    std::chrono::duration<double, std::milli>(t2 - t1).count());

        auto images = vplkit::stages::GbufferImages::create(*ctx, width, height);
        const auto view = vplkit::stages::camera_view(scene.camera(), width, height);
        auto map = vplkit::stages::ShadowMap::create(*ctx, vplkit::scene::parse_sun(sun), gpu.bounds(), rsm);
        vplkit::PassList passes("raster timing");
        vplkit::stages::add_gbuffer_pass(*ctx, passes, gpu, view, images);
        vplkit::stages::add_shadow_map_pass(*ctx, passes, gpu, map);
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
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raster_timing: %s\n", e.what());
        return 1;
    }
}
