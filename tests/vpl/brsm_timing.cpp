// Times the BRSM passes on a standard set-up (PassList GPU timings, medians of 5 runs after one
// warm-up run, so lavapipe's compile-at-first-dispatch is not counted), and beside them the host's
// wall clock around each submission: a GPU total far below it means the timestamps missed work.
// Usage: brsm_timing [SETUP [VPL_COUNT...]]   (default: sponza-sun 4096 100000; RSM faces 512^2)

#include "vplkit/bvh.hpp"
#include "vplkit/context.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_setups.hpp"
#include "vplkit/brsm_buffers.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/shadow_map.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    const std::string setup_name = argc > 1 ? argv[1] : "sponza-sun";
    std::vector<uint32_t> counts;
    for (int i = 2; i < argc; ++i) counts.push_back(uint32_t(std::strtoul(argv[i], nullptr, 10)));
    if (counts.empty()) counts = {4096, 100000};
    constexpr int kRuns = 5;
    constexpr uint32_t kRsmResolution = 512;
    try {
        const auto setups = vplkit::scene::load_setups(VPLKIT_SOURCE_DIR "/scenes/setups.txt");
        const auto& setup = setups.find(setup_name);
        const auto scene = vplkit::scene::load_setup_scene(setup);
        auto ctx = vplkit::Context::create(vplkit::ContextOptions{});
        std::printf("device: %s; set-up %s, %zu triangles, %zu lights, RSM faces %u^2\n", ctx->info().name.c_str(),
                    setup.name.c_str(), scene.triangle_count(), scene.lights.size(), kRsmResolution);
        const float scene_scale = vplkit::build_bvh(vplkit::scene::triangle_positions(scene)).scene_scale;
        auto gpu = vplkit::GpuScene::create(*ctx, scene);
        const uint32_t w = setup.width ? setup.width : 640, h = setup.height ? setup.height : 360;
        auto gbuffer = vplkit::GbufferImages::create(*ctx, w, h);
        const auto view = vplkit::camera_view(scene.camera(), w, h);
        std::vector<vplkit::ShadowMap> maps;
        for (const auto& light : scene.lights)
            maps.push_back(vplkit::ShadowMap::create(*ctx, light, gpu.bounds(), kRsmResolution));
        vplkit::PassList raster("brsm timing raster");
        vplkit::stages::add_gbuffer_pass(*ctx, raster, gpu, view, gbuffer);
        vplkit::add_shadow_map_passes(*ctx, raster, gpu, maps);
        raster.run(*ctx);
        double shadow_ms = 0;
        for (const auto& t : raster.timings()) shadow_ms += t.name.rfind("shadow map", 0) == 0 ? t.gpu_ms : 0.0;
        std::printf("G-buffer %ux%u; shadow maps %.3f ms (one run, includes the raster pipelines' first use)\n", w, h,
                    shadow_ms);

        for (uint32_t n : counts) {
            vplkit::stages::BrsmOptions options;
            options.vpl_count = n;
            auto out = vplkit::BrsmOutput::create(*ctx, maps, gpu.bounds(), options);
            std::vector<std::string> order;
            std::map<std::string, std::vector<double>> per_stage;
            for (int run = 0; run <= kRuns; ++run) {
                std::fprintf(stderr, "\r[brsm timing] %u VPLs: run %d/%d", n, run, kRuns);
                options.seed = uint32_t(run);
                vplkit::PassList passes("brsm timing");
                vplkit::add_brsm_passes(*ctx, passes, gbuffer, view, maps, scene_scale, options, out);
                const auto start = std::chrono::steady_clock::now();
                passes.run(*ctx);
                const double wall =
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
                if (run == 0) continue;  // warm-up: shaders compile at their first dispatch on lavapipe
                std::map<std::string, double> sums;
                for (const auto& t : passes.timings()) {
                    if (!sums.count(t.name) && per_stage[t.name].empty()) order.push_back(t.name);
                    sums[t.name] += t.gpu_ms;
                }
                double total = 0;
                for (const auto& [name, ms] : sums) {
                    per_stage[name].push_back(ms);
                    total += ms;
                }
                per_stage["total"].push_back(total);
                per_stage["wall clock (host)"].push_back(wall);
            }
            std::fprintf(stderr, "\r%60s\r", "");
            order.push_back("total");
            order.push_back("wall clock (host)");
            std::printf("%u VPLs (%u placed), medians of %d runs:\n", n, vplkit::download_brsm_vpl_count(out), kRuns);
            for (const auto& name : order) {
                auto v = per_stage[name];
                std::sort(v.begin(), v.end());
                std::printf("  %-20s %9.3f ms\n", name.c_str(), v[v.size() / 2]);
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "brsm_timing: %s\n", e.what());
        return 1;
    }
    return 0;
}
