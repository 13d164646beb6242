// exact_gi_timing: GPU time of the exact indirect light (every VPL at every pixel, one shadow
// ray each) on a real scene's G-buffer (not a test: timings are never asserted).
//
//   exact_gi_timing [SETUP] [--size WxH] [--vpls N] [--budget PAIRS] [--chunk VPLS]
//
// SETUP is a name from scenes/setups.txt (default: cornell). The VPLs are N points drawn
// uniformly by area on the scene's triangles (fixed seed), facing the side of their triangle
// the camera is on, with equal white flux summing to 1 W: a stand-in for traced VPLs with the
// same cost per (pixel, VPL) pair, which does not depend on where the light came from.

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/exact_gi_render.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_setups.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/exact_gi.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/gbuffer_images.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    try {
        std::string target = "cornell";
        uint32_t width = 64, height = 64, vpl_count = 4096;
        vplkit::stages::ExactGiOptions gi_options;
        int i = 1;
        if (argc > 1 && argv[1][0] != '-') {
            target = argv[1];
            i = 2;
        }
        for (; i + 1 < argc; i += 2) {
            const std::string key = argv[i], value = argv[i + 1];
            if (key == "--size") {
                if (std::sscanf(value.c_str(), "%ux%u", &width, &height) != 2)
                    throw vplkit::Error("bad --size " + value);
            } else if (key == "--vpls") {
                vpl_count = uint32_t(std::stoul(value));
            } else if (key == "--chunk") {
                gi_options.max_vpls_per_dispatch = uint32_t(std::stoul(value));
            } else if (key == "--budget") {
                gi_options.max_pairs_per_dispatch = std::stoull(value);
            } else {
                throw vplkit::Error("unknown option " + key);
            }
        }
        if (i < argc) throw vplkit::Error(std::string("option without a value: ") + argv[i]);
        if (vpl_count == 0) throw vplkit::Error("--vpls must be at least 1");
        auto ctx = vplkit::Context::create(vplkit::ContextOptions{});
        std::printf("device: %s\n", ctx->info().name.c_str());
        const auto setups = vplkit::scene::load_setups(std::filesystem::path(VPLKIT_SOURCE_DIR) / "scenes/setups.txt");
        const auto setup = setups.find(target);
        const vplkit::scene::Scene scene = vplkit::scene::load_gltf(vplkit::scene::require_scene(setup));
        const vplkit::scene::Camera camera = vplkit::scene::setup_camera(setup, scene.bounds);
        auto gpu_scene = vplkit::GpuScene::create(*ctx, scene);
        const auto positions = vplkit::scene::triangle_positions(scene);
        const auto bvh = vplkit::upload_bvh(*ctx, vplkit::build_bvh(positions));

        auto gbuffer = vplkit::GbufferImages::create(*ctx, width, height);
        const auto view = vplkit::camera_view(camera, width, height);
        {
            vplkit::PassList passes("gbuffer");
            vplkit::stages::add_gbuffer_pass(*ctx, passes, gpu_scene, view, gbuffer);
            passes.run(*ctx);
        }

        std::vector<double> cumulative;
        double area = 0.0;
        for (size_t t = 0; t + 2 < positions.size(); t += 3) {
            area += 0.5 * glm::length(glm::cross(positions[t + 1] - positions[t], positions[t + 2] - positions[t]));
            cumulative.push_back(area);
        }
        std::mt19937 rng(1);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        std::vector<vplkit::shaders::Vpl> vpls;
        while (vpls.size() < vpl_count) {
            const size_t t = std::min(
                size_t(std::lower_bound(cumulative.begin(), cumulative.end(), unit(rng) * area) - cumulative.begin()),
                cumulative.size() - 1);
            const glm::vec3 a = positions[3 * t], b = positions[3 * t + 1], c = positions[3 * t + 2];
            glm::vec3 n = glm::cross(b - a, c - a);
            if (glm::dot(n, n) == 0.0f) continue;
            n = glm::normalize(n);
            double u = unit(rng), v = unit(rng);
            if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
            const glm::vec3 p = a + float(u) * (b - a) + float(v) * (c - a);
            if (glm::dot(n, view.position - p) < 0.0f) n = -n;
            vplkit::shaders::Vpl vpl{};
            vpl.position = {p.x, p.y, p.z};
            vpl.normal = {n.x, n.y, n.z};
            const float flux = 1.0f / float(vpl_count);
            vpl.flux = {flux, flux, flux};
            vpls.push_back(vpl);
        }
        auto vpl_buffer = vplkit::Buffer::create(*ctx, vpls.size() * sizeof(vplkit::shaders::Vpl),
                                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "vpls");
        vpl_buffer.upload(vpls);
        auto indirect = vplkit::Image::create(*ctx, width, height, VK_FORMAT_R32G32B32A32_SFLOAT,
                                              VK_IMAGE_USAGE_STORAGE_BIT, "indirect");
        gi_options.progress = [](uint32_t done, uint32_t total) {
            std::fprintf(stderr, "\rexact gi: %u / %u VPLs", done, total);
            if (done == total) std::fprintf(stderr, "\n");
        };
        // A first run pays for pipeline compilation.
        vplkit::render_exact_gi(*ctx, gbuffer, bvh, vpl_buffer, 1, view.position, indirect);
        const auto start = std::chrono::steady_clock::now();
        const auto result =
            vplkit::render_exact_gi(*ctx, gbuffer, bvh, vpl_buffer, vpl_count, view.position, indirect, gi_options);
        const double wall_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        const auto texels = indirect.download<std::array<float, 4>>();
        double mean = 0.0;
        for (const auto& t : texels) mean += (t[0] + t[1] + t[2]) / 3.0;
        mean /= double(texels.size());
        const uint32_t chunk = vplkit::stages::exact_gi_chunk_size(width, height, gi_options);
        std::printf("scene %s: %zu triangles; %ux%u pixels x %u VPLs in %u dispatches of <= %u VPLs\n", target.c_str(),
                    scene.triangle_count(), width, height, vpl_count, result.dispatches, chunk);
        std::printf(
            "exact gi: %.1f ms GPU, %.1f ms wall; %.1f ns per (pixel, VPL) pair; mean indirect %.4g; dropped %u "
            "pixels, %u contributions\n",
            result.gpu_ms, wall_ms, result.gpu_ms * 1e6 / (double(width) * height * vpl_count), mean,
            result.counts.dropped_pixels, result.counts.dropped_contributions);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "exact_gi_timing: %s\n", e.what());
        return 1;
    }
}
