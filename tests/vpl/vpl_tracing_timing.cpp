// vpl_tracing_timing: GPU time of the "trace vpls" pass on a real scene (not a test: timings are
// never asserted). Prints the median over runs of the pass's timestamp time (and of the three
// passes that pack the VPLs by path), the VPL count and
// the total VPL flux per bounce.
//
//   vpl_tracing_timing [SCENE.gltf] [--paths N] [--bounces B] [--runs K] [--point X,Y,Z,R,G,B,I] [--sun ...]
//
// Default scene: scenes/cornell_point/cornell_point.gltf with its own light; 100000 paths, 3
// bounces, 5 runs. --point / --sun add a light (the vplkit command-line syntax).

#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_lights.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/vpl_tracing_buffers.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    try {
        std::string path = std::string(VPLKIT_SOURCE_DIR) + "/scenes/cornell_point/cornell_point.gltf";
        vplkit::stages::VplTracingOptions options{100000, 3, 1};
        uint32_t runs = 5;
        std::vector<vplkit::scene::Light> extra;
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            auto next = [&]() -> std::string {
                if (i + 1 >= argc) throw vplkit::Error(a + " needs a value");
                return argv[++i];
            };
            if (a == "--paths") {
                options.paths = uint32_t(std::stoul(next()));
            } else if (a == "--bounces") {
                options.max_bounces = uint32_t(std::stoul(next()));
            } else if (a == "--runs") {
                runs = std::max(1u, uint32_t(std::stoul(next())));
            } else if (a == "--point") {
                extra.push_back(vplkit::scene::parse_point(next()));
            } else if (a == "--sun") {
                extra.push_back(vplkit::scene::parse_sun(next()));
            } else if (!a.empty() && a[0] == '-') {
                throw vplkit::Error("unknown option " + a);
            } else {
                path = a;
            }
        }
        vplkit::scene::Scene scene = vplkit::scene::load_gltf(path);
        scene.lights.insert(scene.lights.end(), extra.begin(), extra.end());

        auto ctx = vplkit::Context::create(vplkit::ContextOptions{});
        std::printf("device: %s\nscene: %s (%zu triangles, %zu lights, %zu emissive triangles)\n",
                    ctx->info().name.c_str(), path.c_str(), scene.triangle_count(), scene.lights.size(),
                    scene.emissive_triangles.size());
        const auto bvh = vplkit::upload_bvh(*ctx, vplkit::build_bvh(vplkit::scene::triangle_positions(scene)));
        const auto sources = vplkit::upload_vpl_sources(*ctx, scene);
        auto output = vplkit::VplTracingOutput::create(*ctx, options);
        std::vector<double> ms, packing_ms;
        uint32_t count = 0;
        for (uint32_t r = 0; r < runs; ++r) {
            vplkit::PassList passes("vpl tracing timing");
            options.seed = 1 + r;
            vplkit::stages::add_trace_vpls_passes(*ctx, passes, bvh, sources, options, output);
            passes.run(*ctx);
            const auto timings = passes.timings();
            ms.push_back(timings[1].gpu_ms);
            // vpl block counts, vpl block offsets, compact vpls: the packing in path order.
            packing_ms.push_back(timings[2].gpu_ms + timings[3].gpu_ms + timings[4].gpu_ms);
            count = vplkit::download_vpl_count(output);
        }
        std::vector<double> sorted = ms;
        std::sort(sorted.begin(), sorted.end());
        std::printf("trace vpls: %u paths, %u bounces: %.2f ms median of %u (min %.2f, max %.2f), %u VPLs\n",
                    options.paths, options.max_bounces, sorted[sorted.size() / 2], runs, sorted.front(), sorted.back(),
                    count);
        std::sort(packing_ms.begin(), packing_ms.end());
        std::printf("packing them by path (3 passes): %.2f ms median (min %.2f, max %.2f)\n",
                    packing_ms[packing_ms.size() / 2], packing_ms.front(), packing_ms.back());
        const auto vpls = output.vpls.download<vplkit::shaders::Vpl>(count);
        const auto bounces = output.bounces.download<uint32_t>(count);
        std::vector<double> flux(options.max_bounces + 1, 0.0);
        std::vector<uint32_t> per_bounce(options.max_bounces + 1, 0);
        for (uint32_t i = 0; i < count; ++i) {
            flux[bounces[i]] += double(vpls[i].flux.x) + vpls[i].flux.y + vpls[i].flux.z;
            ++per_bounce[bounces[i]];
        }
        std::printf("emitted power (R+G+B): %.4f W\n",
                    double(sources.total_power.x + sources.total_power.y + sources.total_power.z));
        for (uint32_t k = 1; k <= options.max_bounces; ++k) {
            std::printf("bounce %u: %u VPLs, flux (R+G+B) %.4f W\n", k, per_bounce[k], flux[k]);
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vpl_tracing_timing: %s\n", e.what());
        return 1;
    }
}
