// `vplkit bench bvh`: the host's binned SAH BVH (vplkit/bvh.hpp) against the GPU LBVH
// (vplkit/bvh_gpu_build.hpp) on random triangle soups of several sizes and on scenes: build
// time (host wall clock; GPU timestamps, median over runs, per stage), refit time, the trees'
// size, depth and SAH cost, and rays per second traced through each (the same rays, the same
// traversal: the difference is the tree's quality). Checks both trees give the same hits.

#include "bench_timing.hpp"
#include "cli.hpp"
#include "cli_checks.hpp"
#include "device_options.hpp"
#include "commands.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/bvh_gpu_build.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_setups.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#ifndef VPLKIT_SETUPS_FILE
#error "VPLKIT_SETUPS_FILE (the repository's scenes/setups.txt) must be defined by the build"
#endif

namespace vplkit::cli {

namespace {

using Triangles = std::vector<glm::vec3>;

// `count` random triangles, centres uniform in [-1, 1]^3, edges up to 2 / cbrt(count) long (a
// soup about as dense at every size).
Triangles random_soup(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    const float size = 2.0f / std::cbrt(float(count));
    Triangles out;
    out.reserve(size_t(count) * 3);
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 centre(unit(rng), unit(rng), unit(rng));
        for (int k = 0; k < 3; ++k) out.push_back(centre + 0.5f * size * glm::vec3(unit(rng), unit(rng), unit(rng)));
    }
    return out;
}

// Half the rays from random points in the scene box in random directions (unbounded), half
// segments between random points on two random triangles (tmax 1: shadow rays), as a
// renderer's visibility queries are.
std::vector<shaders::BvhRay> random_rays(const Triangles& triangles, uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> fraction(0.0f, 1.0f);
    std::normal_distribution<float> gauss;
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const auto& v : triangles) lo = glm::min(lo, v), hi = glm::max(hi, v);
    const uint32_t n = uint32_t(triangles.size() / 3);
    auto surface_point = [&]() {
        const uint32_t t = std::min(n - 1, uint32_t(fraction(rng) * float(n)));
        float u = fraction(rng), v = fraction(rng);
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        return triangles[3 * t] + u * (triangles[3 * t + 1] - triangles[3 * t]) +
               v * (triangles[3 * t + 2] - triangles[3 * t]);
    };
    std::vector<shaders::BvhRay> rays(count);
    for (uint32_t i = 0; i < count; ++i) {
        glm::vec3 origin, direction;
        float tmin = 0.0f, tmax = INFINITY;
        if (i % 2 == 0) {
            origin = lo + (hi - lo) * glm::vec3(fraction(rng), fraction(rng), fraction(rng));
            do direction = glm::vec3(gauss(rng), gauss(rng), gauss(rng));
            while (glm::length(direction) < 1e-3f);
        } else {
            origin = surface_point();
            direction = surface_point() - origin;
            tmin = 1e-4f, tmax = 1.0f - 1e-4f;
        }
        rays[i].origin = {origin.x, origin.y, origin.z};
        rays[i].direction = {direction.x, direction.y, direction.z};
        rays[i].tmin = tmin;
        rays[i].tmax = tmax;
    }
    return rays;
}

double box_area(const shaders::BvhNode& n) {
    const double dx = double(n.hi.x) - n.lo.x, dy = double(n.hi.y) - n.lo.y, dz = double(n.hi.z) - n.lo.z;
    return 2.0 * (dx * dy + dy * dz + dz * dx);
}

// The SAH cost of a tree as build_bvh states it (traversal and triangle cost 1), from its stored
// (padded) boxes, so that both trees are measured alike.
double sah_cost(const std::vector<shaders::BvhNode>& nodes) {
    double sum = 0.0;
    for (const auto& n : nodes) sum += box_area(n) * (bvh_is_leaf(n) ? double(bvh_leaf_triangles(n)) : 1.0);
    const double root = box_area(nodes.at(0));
    return root > 0.0 ? sum / root : 0.0;
}

struct Case {
    std::string name;
    Triangles triangles;
};

// A standard set-up's name, or a .gltf / .glb file.
Case scene_case(const std::string& scene) {
    const bool file = scene.size() > 5 && (scene.ends_with(".gltf") || scene.ends_with(".glb"));
    const scene::Scene loaded =
        file ? scene::load_gltf(scene) : scene::load_setup_scene(scene::load_setups(VPLKIT_SETUPS_FILE).find(scene));
    return {scene, scene::triangle_positions(loaded)};
}

double median_of(const std::vector<StageStats>& stats, const std::string& stage) {
    for (const auto& s : stats) {
        if (s.stage == stage) return s.median_ms;
    }
    return 0.0;
}

// The build's stages by name, its per-depth box passes summed into one ("levels").
std::vector<std::pair<std::string, double>> stage_medians(const std::vector<StageStats>& stats) {
    std::vector<std::pair<std::string, double>> out;
    for (const auto& s : stats) {
        std::string name = s.stage.rfind("bvh build ", 0) == 0 ? s.stage.substr(10) : s.stage;
        if (name.rfind("level ", 0) == 0) name = "levels";
        if (name == "total") continue;
        auto it = std::find_if(out.begin(), out.end(), [&](const auto& p) { return p.first == name; });
        if (it == out.end()) {
            out.emplace_back(name, s.median_ms);
        } else {
            it->second += s.median_ms;
        }
    }
    return out;
}

}  // namespace

namespace {

struct BenchBvhOptions {
    ContextOptions context;
    std::optional<std::string> scene, counts, csv;
    uint32_t runs = 5;
    uint32_t rays = 1u << 18;
};

int run_bench_bvh(const BenchBvhOptions& o) {
    const ContextOptions& options = o.context;
    const std::optional<std::string>& scene = o.scene;
    // Soups by default; with --scene only the scene unless --counts asks for soups too.
    std::vector<uint32_t> counts;
    if (o.counts) {
        counts = parse_whole_number_list("--counts", *o.counts, kBvhCountMask - 1);
    } else if (!scene) {
        counts = {50000, 200000, 1000000};
    }
    const uint32_t runs = o.runs;
    const uint32_t ray_count = o.rays;
    const std::optional<std::string>& csv_path = o.csv;

    std::vector<Case> cases;
    if (scene) cases.push_back(scene_case(*scene));  // first: a bad name fails before any device work
    for (uint32_t count : counts) cases.push_back({"soup " + std::to_string(count), random_soup(count, count)});

    auto context = Context::create(options);
    const DeviceInfo& device = context->info();
    std::printf("device: %s (%s) - %s\n", device.name.c_str(), device.type_name.c_str(), device.reason.c_str());
    std::printf(
        "%u rays (half unbounded from the scene box, half segments between surface points); GPU times: "
        "median of %u runs\n",
        ray_count, runs);
    std::ostringstream csv;
    csv << "device,case,triangles,tree,build_ms,refit_ms,nodes,depth,lbvh_depth,capped_leaves,sah,closest_mrays_s,"
           "occlusion_mrays_s,mismatches\n";
    for (const Case& c : cases) {
        const uint32_t triangles = uint32_t(c.triangles.size() / 3);
        std::printf("\n%s: %u triangles\n", c.name.c_str(), triangles);

        const auto start = std::chrono::steady_clock::now();
        const Bvh host_bvh = build_bvh(c.triangles);
        const double host_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        const GpuBvh host = upload_bvh(*context, host_bvh);

        GpuBvhBuild gpu(*context, c.triangles);
        PassList build_passes("bench bvh build");
        gpu.add_build_passes(build_passes);
        const auto build_stats = time_passes(*context, build_passes, runs, c.name + " GPU build");
        PassList refit_passes("bench bvh refit");
        gpu.add_refit_passes(refit_passes);
        const auto refit_stats = time_passes(*context, refit_passes, runs, c.name + " GPU refit");
        const auto gpu_nodes = gpu.bvh().nodes.download<shaders::BvhNode>(gpu.bvh().node_count);

        const auto rays = random_rays(c.triangles, ray_count, triangles);
        auto ray_buffer = Buffer::create(*context, rays.size() * sizeof(shaders::BvhRay),
                                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "rays");
        ray_buffer.upload(rays);
        auto trace = [&](const GpuBvh& bvh, TraceMode mode, const char* label, std::vector<shaders::BvhHit>* hits) {
            const VkDeviceSize bytes =
                uint64_t(ray_count) * (mode == TraceMode::closest_hit ? sizeof(shaders::BvhHit) : sizeof(uint32_t));
            auto results =
                Buffer::create(*context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "results");
            PassList passes("bench bvh trace");
            add_trace_rays_pass(*context, passes, bvh, ray_buffer, results, ray_count, mode);
            const double ms = median_of(time_passes(*context, passes, runs, c.name + " " + label), "total");
            if (hits) *hits = results.download<shaders::BvhHit>(ray_count);
            return double(ray_count) / (ms * 1e3);  // millions of rays per second
        };
        std::vector<shaders::BvhHit> host_hits, gpu_hits;
        const double host_closest = trace(host, TraceMode::closest_hit, "host BVH closest", &host_hits);
        const double gpu_closest = trace(gpu.bvh(), TraceMode::closest_hit, "GPU BVH closest", &gpu_hits);
        const double host_occlusion = trace(host, TraceMode::occlusion, "host BVH occlusion", nullptr);
        const double gpu_occlusion = trace(gpu.bvh(), TraceMode::occlusion, "GPU BVH occlusion", nullptr);
        // The same float triangle tests: the same nearest t (only the triangle may differ at a tie).
        uint32_t mismatches = 0;
        for (uint32_t r = 0; r < ray_count; ++r) {
            mismatches += (host_hits[r].id == kBvhNoHit) != (gpu_hits[r].id == kBvhNoHit) ||
                          std::fabs(double(host_hits[r].t) - gpu_hits[r].t) > 1e-5 * std::fabs(double(host_hits[r].t));
        }

        const auto& s = gpu.stats();
        const double gpu_ms = median_of(build_stats, "total");
        const double refit_ms = median_of(refit_stats, "total");
        const double host_sah = sah_cost(host_bvh.nodes), gpu_sah = sah_cost(gpu_nodes);
        std::printf(
            "  %-5s build %10.1f ms%s  %9zu nodes  depth %2u        SAH %6.1f  closest %7.3f Mrays/s  "
            "occlusion %7.3f Mrays/s\n",
            "host", host_ms, " (1 core)", host_bvh.nodes.size(), host_bvh.depth, host_sah, host_closest,
            host_occlusion);
        std::printf(
            "  %-5s build %10.2f ms (GPU)   %9u nodes  depth %2u (LBVH %u, %u capped leaves, largest %u)  SAH "
            "%6.1f  closest %7.3f Mrays/s  occlusion %7.3f Mrays/s\n",
            "gpu", gpu_ms, s.node_count, s.depth, s.lbvh_depth, s.capped_leaves, s.largest_leaf, gpu_sah, gpu_closest,
            gpu_occlusion);
        std::printf("  gpu   refit %10.2f ms (GPU); build by stage (median ms):", refit_ms);
        for (const auto& [name, ms] : stage_medians(build_stats)) std::printf(" %s %.2f", name.c_str(), ms);
        std::printf("\n  closest hits that differ between the trees: %u of %u\n", mismatches, ray_count);
        csv << csv_field(device.name) << ',' << csv_field(c.name) << ',' << triangles << ",host," << host_ms << ",,"
            << host_bvh.nodes.size() << ',' << host_bvh.depth << ",,," << host_sah << ',' << host_closest << ','
            << host_occlusion << ',' << mismatches << '\n';
        csv << csv_field(device.name) << ',' << csv_field(c.name) << ',' << triangles << ",gpu," << gpu_ms << ','
            << refit_ms << ',' << s.node_count << ',' << s.depth << ',' << s.lbvh_depth << ',' << s.capped_leaves << ','
            << gpu_sah << ',' << gpu_closest << ',' << gpu_occlusion << ',' << mismatches << '\n';
        if (mismatches > ray_count / 1000) {
            throw Error("bench bvh: " + std::to_string(mismatches) + " of " + std::to_string(ray_count) +
                        " closest hits differ between the host and the GPU BVH of " + c.name);
        }
    }
    write_csv_if_asked(csv_path, csv.str());
    return 0;
}

}  // namespace

void add_bench_bvh(CLI::App& bench, Runners& runners) {
    CLI::App* bvh = add_command(
        bench, "bvh", "the host and the GPU BVH builds: build and refit times, rays per second",
        "The host's binned SAH BVH against the GPU LBVH (Morton codes, radix sort, Karras 2012), on random "
        "triangle soups and a scene: build time (host: wall clock, one core; GPU: timestamps, median of R runs "
        "after a warm-up, per stage), GPU refit time, nodes, depth, SAH cost, and millions of rays per second "
        "through each tree (closest hit and occlusion, the same rays). Checks that both trees give the same "
        "nearest hits.");
    auto o = std::make_shared<BenchBvhOptions>();
    add_device_options(*bvh, o->context, false);
    whole_number_list(bvh->add_option_function<std::string>(
                          "--counts", [o](const std::string& v) { o->counts = v; },
                          "soup sizes in triangles (default 50000,200000,1000000; none with --scene unless given)"),
                      "N", kBvhCountMask - 1);
    bvh->add_option_function<std::string>(
           "--scene", [o](const std::string& v) { o->scene = v; },
           "also a standard set-up (scenes/setups.txt) or a .gltf/.glb file")
        ->option_text("NAME|FILE");
    whole_number(
        bvh->add_option("--runs", o->runs, "timed runs of each GPU build, refit and trace")->capture_default_str(), "R",
        1, 100000);
    whole_number(bvh->add_option("--rays", o->rays, "rays traced per tree")->capture_default_str(), "N", 1, 1u << 22);
    bvh->add_option_function<std::string>(
           "--csv", [o](const std::string& v) { o->csv = v; }, "also write the figures as CSV")
        ->option_text("FILE");
    runners.push_back({bvh, [o] { return run_bench_bvh(*o); }});
}

}  // namespace vplkit::cli
