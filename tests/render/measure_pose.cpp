// measure_pose: what following an animated scene costs, on this machine's device (not a test;
// its figures are in the report / README). Writes a skinned grid of N x N quads (two joints, the
// second turning over t in [0, 1]) with a 1024 x 1024 texture, then times:
//   load_gltf at t (the whole file: parse, decode primitives and the image, pose, flatten),
//   PosableScene::pose(t) (the kept model re-posed), Renderer::update_pose (upload, GPU refit),
// and, for the rebuild rule, scatters a growing fraction of the quads: the refitted tree's SAH
// cost over its build's against the time to trace closest-hit rays through it and a fresh build.
//   measure_pose [N=256] [out_dir=/tmp/measure_pose]

#include "animation_files.hpp"

#include "vplkit/bvh_gpu_build.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_pose.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// n x n quads over [0, 1]^2 (z = 0), skinned: joint 0 at the origin, joint 1 at x = 0.5 turning
// about y by 0 .. 60 degrees over t in [0, 1]; weights blend across the middle.
std::filesystem::path write_skinned_grid(const std::filesystem::path& dir, uint32_t n) {
    scene_test::GltfBuilder b;
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec4> weights;
    std::vector<uint16_t> joints;
    std::vector<uint32_t> indices;
    for (uint32_t y = 0; y <= n; ++y) {
        for (uint32_t x = 0; x <= n; ++x) {
            const float u = float(x) / float(n), v = float(y) / float(n);
            positions.push_back({u, v, 0.0f});
            normals.push_back({0.0f, 0.0f, 1.0f});
            uvs.push_back({u, v});
            const float w = std::clamp((u - 0.4f) / 0.2f, 0.0f, 1.0f);
            weights.push_back({1.0f - w, w, 0.0f, 0.0f});
            joints.insert(joints.end(), {0, 1, 0, 0});
        }
    }
    for (uint32_t y = 0; y < n; ++y) {
        for (uint32_t x = 0; x < n; ++x) {
            const uint32_t a = y * (n + 1) + x;
            indices.insert(indices.end(), {a, a + 1, a + n + 2, a, a + n + 2, a + n + 1});
        }
    }
    const int p = b.vec3s(positions), nr = b.vec3s(normals), uv = b.vec2s(uvs), wt = b.vec4s(weights);
    const int jt = b.accessor(b.view(joints.data(), joints.size() * sizeof(uint16_t)), scene_test::kUnsignedShort,
                              joints.size() / 4, "VEC4");
    const int ix = b.indices(indices, scene_test::kUnsignedInt);
    std::vector<uint8_t> texels(1024 * 1024 * 4);
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = uint8_t((i * 2654435761u) >> 24);  // not compressible
    b.images.push_back("{\"bufferView\":" + std::to_string(b.image_view(scene_test::png(1024, 1024, texels))) +
                       ",\"mimeType\":\"image/png\"}");
    b.textures.push_back(R"({"source":0})");
    b.materials.push_back(R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0},"metallicFactor":0}})");
    const std::vector<glm::mat4> inverse_bind = {
        glm::mat4(1.0f),
        glm::mat4(glm::vec4(1, 0, 0, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, 1, 0), glm::vec4(-0.5f, 0, 0, 1))};
    const int ibm = b.accessor(b.view(inverse_bind.data(), sizeof(glm::mat4) * 2), scene_test::kFloat, 2, "MAT4");
    const int mesh =
        b.mesh("[{\"attributes\":{\"POSITION\":" + std::to_string(p) + ",\"NORMAL\":" + std::to_string(nr) +
               ",\"TEXCOORD_0\":" + std::to_string(uv) + ",\"JOINTS_0\":" + std::to_string(jt) +
               ",\"WEIGHTS_0\":" + std::to_string(wt) + "},\"indices\":" + std::to_string(ix) + ",\"material\":0}]");
    const int arm = b.node(R"({"name":"arm","translation":[0.5,0,0]})");  // node 0
    const int hip = b.node(R"({"name":"hip","children":[0]})");           // node 1
    b.roots.push_back(hip);
    b.roots.push_back(b.node("{\"mesh\":" + std::to_string(mesh) + ",\"skin\":0}"));
    b.lights.push_back(R"({"type":"point","color":[1,1,1],"intensity":4})");
    b.roots.push_back(b.node(R"({"translation":[0.5,0.5,1.5],"extensions":{"KHR_lights_punctual":{"light":0}}})"));
    b.top_level_extra += ",\"skins\":[{\"joints\":[" + std::to_string(hip) + "," + std::to_string(arm) +
                         "],\"inverseBindMatrices\":" + std::to_string(ibm) + "}]";
    const float s = 0.5f, c = 0.8660254f;  // a 60 degree turn about y: sin and cos of 30 degrees
    gltf_features::add_animations(b, {{"bend", {{arm, "rotation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, s, 0, c}}}}});
    return b.write(dir, "skinned_grid");
}

template <class F>
double best_of(int runs, F&& f) {
    double best = 1e30;
    for (int r = 0; r < runs; ++r) {
        const auto start = Clock::now();
        f(r);
        best = std::min(best, ms_since(start));
    }
    return best;
}

// Closest-hit rays from random points above the grid down through it: the GPU time of one pass.
double trace_ms(vplkit::Context& context, const vplkit::GpuBvh& bvh, const vplkit::Buffer& rays,
                const vplkit::Buffer& results, uint32_t count) {
    double best = 1e30;
    for (int r = 0; r < 3; ++r) {
        vplkit::PassList passes("trace");
        vplkit::add_trace_rays_pass(context, passes, bvh, rays, results, count, vplkit::TraceMode::closest_hit);
        passes.run(context);
        best = std::min(best, passes.total_gpu_ms());
    }
    return best;
}

}  // namespace

int main(int argc, char** argv) {
    const uint32_t n = argc > 1 ? uint32_t(std::atoi(argv[1])) : 256;
    const std::filesystem::path dir = argc > 2 ? argv[2] : "/tmp/measure_pose";
    std::filesystem::create_directories(dir);
    const auto path = write_skinned_grid(dir, n);
    auto context = vplkit::Context::create();
    std::printf("device: %s\nfile: %s (%u triangles, skinned, 1024^2 texture)\n", context->info().name.c_str(),
                path.string().c_str(), 2 * n * n);

    // 1. Posing at t: the whole load against the kept model's pose.
    vplkit::scene::LoadOptions options;
    options.time = 0.0;
    const double load = best_of(3, [&](int r) { vplkit::scene::load_gltf(path, {{}, 0.1 * (r + 1), {}}); });
    vplkit::scene::PosableScene posable(path, options);
    const double pose = best_of(5, [&](int r) { posable.pose(0.1 * (r + 1)); });
    std::printf("load_gltf at t: %.1f ms; PosableScene::pose(t): %.1f ms (%.1fx faster)\n", load, pose, load / pose);

    // 2. The renderer following the pose.
    vplkit::Renderer renderer(*context, posable.scene());
    std::printf("renderer: host BVH build at construction %.1f ms\n", renderer.bvh_build_ms());
    for (int step = 0; step < 4; ++step) {
        const auto change = posable.pose(0.6 + 0.1 * step);
        const vplkit::PoseUpdate u = renderer.update_pose(change);
        std::printf("update_pose %d: %s; upload %.2f ms, BVH %.2f ms (GPU %.2f ms), SAH ratio %.3f\n", step,
                    u.bvh == vplkit::BvhUpdate::refit ? "refit" : "rebuild", u.upload_ms, u.bvh_ms, u.bvh_gpu_ms,
                    u.bvh_cost_ratio);
    }

    // 3. The rebuild rule: a fraction of the quads scattered, refit against a fresh build.
    std::vector<glm::vec3> base = vplkit::scene::triangle_positions(vplkit::scene::load_gltf(path));
    const uint32_t quads = uint32_t(base.size() / 6);
    constexpr uint32_t kRays = 1u << 18;
    std::vector<vplkit::shaders::BvhRay> rays(kRays);
    uint32_t state = 7u;
    auto next = [&state] {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / 16777216.0f;
    };
    for (auto& ray : rays) {
        const glm::vec3 from{next(), next(), 1.5f}, to{next(), next(), 0.0f};
        ray.origin = {from.x, from.y, from.z};
        const glm::vec3 d = to - from;
        ray.direction = {d.x, d.y, d.z};
        ray.tmin = 0.0f;
        ray.tmax = 2.0f;  // through the grid: each ray finds its closest hit on it
    }
    auto ray_buffer = vplkit::Buffer::create(*context, rays.size() * sizeof(rays[0]),
                                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "rays");
    ray_buffer.upload(rays);
    auto results = vplkit::Buffer::create(*context, kRays * sizeof(vplkit::shaders::BvhHit),
                                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device, "results");
    auto sah = [](const vplkit::GpuBvh& bvh) {
        return vplkit::bvh_sah_cost(bvh.nodes.download<vplkit::shaders::BvhNode>(bvh.node_count));
    };
    vplkit::GpuBvhBuild refitted(*context, base);
    const double built_cost = sah(refitted.bvh());
    std::printf("GPU build of the flat grid: %.2f ms GPU, SAH cost %.2f; %u closest-hit rays per trace\n",
                refitted.stats().gpu_ms, built_cost, kRays);
    std::printf(
        "scattered  refit-SAH-ratio  fresh-SAH-ratio  trace-refit-ms  trace-fresh-ms  refit-gpu-ms  "
        "build-gpu-ms\n");
    for (double fraction : {0.0, 0.0001, 0.0003, 0.001, 0.003, 0.01}) {
        std::vector<glm::vec3> moved = base;
        // Swaps pairs of random quads (6 vertices each): the same surfaces, leaves stretched.
        const uint32_t swaps = uint32_t(fraction * quads / 2.0);
        for (uint32_t i = 0; i < swaps; ++i) {
            const uint32_t a = uint32_t(next() * float(quads)) % quads, c = uint32_t(next() * float(quads)) % quads;
            for (uint32_t k = 0; k < 6; ++k) std::swap(moved[6 * a + k], moved[6 * c + k]);
        }
        refitted.refit(moved);
        const double refit_ratio = sah(refitted.bvh()) / built_cost;
        const double refit_gpu = refitted.stats().gpu_ms;
        vplkit::GpuBvhBuild fresh(*context, moved);
        const double fresh_ratio = sah(fresh.bvh()) / built_cost;
        const double trace_refit = trace_ms(*context, refitted.bvh(), ray_buffer, results, kRays);
        const double trace_fresh = trace_ms(*context, fresh.bvh(), ray_buffer, results, kRays);
        std::printf("%9.4f  %15.3f  %15.3f  %14.2f  %14.2f  %12.2f  %12.2f\n", fraction, refit_ratio, fresh_ratio,
                    trace_refit, trace_fresh, refit_gpu, fresh.stats().gpu_ms);
    }
    return 0;
}
