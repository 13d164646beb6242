// `vplkit bench sort`: GPU time of the VPL key passes and the sort (bitonic, radix or both) for
// several VPL counts, from timestamp queries, median over many runs, as a table and optionally CSV.
// Random VPLs (uniform in a unit box, uniform normals) stand in for a scene's until scenes load.

#include "cli.hpp"
#include "commands.hpp"
#include "bench_timing.hpp"
#include "vpl_sources.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/sort.hpp"
#include "vplkit/stages/vpl_keys.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

namespace vplkit::cli {

namespace {

// {bench curves} is replaced by the method table's curves (gi_methods.hpp).
const char* const kBenchUsageText =
    "usage: vplkit bench sort [--counts N,N,...] [--runs R] [--algorithm A] [--workgroup-size W] [--csv FILE]\n"
    "                         [--device SEL]\n"
    "\n"
    "Times the VPL key passes (bounds, Morton/normal keys) and the sort of the (key, index)\n"
    "pairs on the GPU with timestamp queries: one warm-up run, then R timed runs per count and\n"
    "algorithm; prints median, min and max per stage. Checks the last run's output is sorted.\n"
    "  --counts N,...        VPL counts (default 4096,65536,1048576; at most 2^25)\n"
    "  --runs R              timed runs per count (default 20)\n"
    "  --algorithm A         bitonic, radix or both (default both)\n"
    "  --workgroup-size W    sort workgroup size (default: bitonic 256, radix 32; bitonic: a power of two)\n"
    "  --csv FILE            also write every statistic as CSV\n"
    "  --device SEL          auto, gpu, cpu (lavapipe), an index, or part of a name\n"
    "\n"
    "usage: vplkit bench tree [--counts N,N,...] [--runs R] [--source random|SETUP] [--sort radix|bitonic]\n"
    "                         [--group-levels G] [--csv FILE] [--device SEL]\n"
    "\n"
    "Times, per VPL count, every stage from a VPL buffer to both light trees: bounds and keys,\n"
    "the key sort, gathering the leaves, the RTSLC light tree and the SST. One warm-up run, then\n"
    "R timed runs; prints median, min and max per stage, and checks the last run's trees.\n"
    "  --counts N,...     VPL counts (default 4096,65536,1048576)\n"
    "  --runs R           timed runs per count (default 10)\n"
    "  --source S         random (default), or a standard set-up (scenes/setups.txt) whose scene\n"
    "                     surfaces the VPLs are sampled on, e.g. sponza-sun\n"
    "  --sort A           radix (default) or bitonic\n"
    "  --group-levels G   light-tree levels built per dispatch (default: the device's)\n"
    "  --csv FILE         also write every statistic as CSV\n"
    "  --device SEL       auto, gpu, cpu (lavapipe), an index, or part of a name\n"
    "\n"
    "usage: vplkit bench gi --scene NAME|FILE [--camera N] [--sun ...] [--point ...] [--out DIR]\n"
    "                       [--width W --height H] [--frames F] [--quick]\n"
    "                       [--vpl-source ir|brsm] [--vpls N] [--seed S] [--target-ms T] [--cache DIR]\n"
    "                       [--sweeps LIST] [--methods LIST] [--device SEL] [--strict]\n"
    "                       [--position X,Y,Z --target X,Y,Z [--up X,Y,Z]] [--fov DEG]\n"
    "\n"
    "What every indirect-light method's accuracy costs on a standard set-up. Renders the exact\n"
    "ground truth once (cached in --cache, keyed by scene, camera, lights, size, VPL set and seed),\n"
    "then sweeps each method's knob: samples per pixel 1..64 (sst, rtslc, hybrid, and hybrid-lightcuts:\n"
    "hybrid's cuts with rtslc's traversal, the thesis' sec. 7.1 protocol), cut block size\n"
    "1..32 (rtslc, hybrid), GI at half resolution, interleaving (rtslc), mock cuts on/off (hybrid)\n"
    "and the VPL count 1k..1M (build times). Every point: F frames, per-stage GPU times (median\n"
    "and spread of frames 2..F), RMSE and SSIM of the tonemapped frame against the ground truth,\n"
    "relMSE of the linear radiance. Writes DIR/points.csv, points.json, plots (PNG), equal-time\n"
    "images with x10 difference pictures, and DIR/report.md.\n"
    "  --scene S        a standard set-up (scenes/setups.txt) or a .gltf/.glb file, with its own\n"
    "                   camera (--camera N) and lights plus --sun and --point, as render takes them\n"
    "  --position, --target, --up, --fov   another camera, as render takes them\n"
    "  --out DIR        output folder (default out/bench/NAME, NAME the set-up or the file's stem)\n"
    "  --width, --height  image size (default 320x180 on a CPU device, 1280x720 on a GPU)\n"
    "  --frames F       frames per point (default 3; the first is not timed when F > 1)\n"
    "  --quick          a smoke test: 48x27 (unless sized), 256 VPLs, 128^2 shadow maps, a few points,\n"
    "                   2 frames\n"
    "  --vpl-source S   default brsm when the scene has punctual lights, else ir\n"
    "  --vpls N         the VPL budget (default 4096)\n"
    "  --target-ms T    the equal-time target frame time (default: hybrid's at 8 spp)\n"
    "  --cache DIR      where ground truths are kept (default out/bench-cache)\n"
    "  --sweeps LIST    only these sweeps, comma-separated: spp, block, resolution, interleave, mock, vpls\n"
    "  --methods LIST   only these methods' curves, comma-separated (default: all): {bench curves}\n"
    "  --strict         fail when the scene has a warning (a feature of the file vplkit skips or approximates)\n"
    "\n"
    "usage: vplkit bench direct --scene NAME|FILE [--out DIR] [--width W --height H] [--frames F]\n"
    "                           [--reference-frames R] [--quick] [--device SEL] [--strict]\n"
    "                           [--position X,Y,Z --target X,Y,Z [--up X,Y,Z]] [--fov DEG]\n"
    "\n"
    "Direct light's accuracy against its cost: the flat sampler (point and spot lights one by one,\n"
    "emitters drawn by power) and the light tree over all of them (stochastic lightcuts), each at\n"
    "1..64 samples per pixel, against a reference (the flat sampler's mean over R frames of 256\n"
    "samples). Every point: F frames; error = relative RMSE of the linear direct radiance, time =\n"
    "median GPU time of the direct-light passes over frames 2..F. Writes DIR/points.csv, plots\n"
    "(PNG), a frame of each sampler and DIR/report.md with the tree / flat RMSE ratio at equal time.\n"
    "  --out DIR        output folder (default out/bench-direct/NAME)\n"
    "  --width, --height  image size (default 128x128 on a CPU device, 512x512 on a GPU)\n"
    "  --frames F       frames per point (default 3, at least 2)\n"
    "  --reference-frames R   frames averaged for the reference (default 16)\n"
    "  --quick          a smoke test: 32x32, 1 and 4 spp, 2 frames, a 2-frame reference of 16 spp\n"
    "  --position, --target, --up, --fov   another camera, as render takes them\n"
    "\n"
    "usage: vplkit bench bvh [--counts N,N,...] [--scene NAME|FILE] [--runs R] [--rays N] [--csv FILE]\n"
    "                        [--device SEL]\n"
    "\n"
    "The host's binned SAH BVH against the GPU LBVH (Morton codes, radix sort, Karras 2012), on\n"
    "random triangle soups and a scene: build time (host: wall clock, one core; GPU: timestamps,\n"
    "median of R runs after a warm-up, per stage), GPU refit time, nodes, depth, SAH cost, and\n"
    "millions of rays per second through each tree (closest hit and occlusion, the same rays).\n"
    "Checks that both trees give the same nearest hits.\n"
    "  --counts N,...   soup sizes in triangles (default 50000,200000,1000000; none with --scene\n"
    "                   unless given)\n"
    "  --scene S        also a standard set-up (scenes/setups.txt) or a .gltf/.glb file\n"
    "  --runs R         timed runs of each GPU build, refit and trace (default 5)\n"
    "  --rays N         rays traced per tree (default 262144)\n"
    "  --csv FILE       also write the figures as CSV\n"
    "  --device SEL     auto, gpu, cpu (lavapipe), an index, or part of a name\n";

}  // namespace

std::string bench_usage() {
    std::string text = kBenchUsageText;
    const std::string_view slot = "{bench curves}";
    const size_t at = text.find(slot);
    const size_t line = text.rfind('\n', at) + 1;
    text.replace(at, slot.size(), wrapped(gi_bench_curve_names(), at - line, 19));
    return text;
}

namespace {

// The last run's keys must be ascending and its values a permutation of 0..count-1: a benchmark
// of a wrong result is worth nothing.
void check_sorted(const Buffer& keys, const Buffer& values, uint32_t count) {
    auto k = keys.download<uint64_t>(count);
    auto v = values.download<uint32_t>(count);
    if (!std::is_sorted(k.begin(), k.end())) {
        throw Error("bench sort: the keys of " + std::to_string(count) + " VPLs came out unsorted");
    }
    std::vector<bool> seen(count, false);
    for (uint32_t i = 0; i < count; ++i) {
        if (v[i] >= count || seen[v[i]] || (k[i] & (stages::kMaxKeyedVpls - 1)) != v[i]) {
            throw Error("bench sort: sorted values are not the VPL indices of their keys (at " + std::to_string(i) +
                        ")");
        }
        seen[v[i]] = true;
    }
}

}  // namespace

int run_bench(Args& args) {
    // `bench --scene NAME` is the GI benchmark; take --scene first, its value is not a name.
    if (auto scene = args.value("--scene")) {
        const auto what = args.positional();
        if (what && *what == "direct") return run_bench_direct(args, *scene);
        if (what && *what == "bvh") return run_bench_bvh(args, *scene);
        if (what && *what != "gi") {
            throw UsageError("--scene is for bench gi, bench direct or bench bvh, not bench " + *what);
        }
        return run_bench_gi(args, *scene);
    }
    const auto what = args.positional();
    if (!what) {
        throw UsageError("bench needs a benchmark name: sort, tree, bvh, gi --scene NAME or direct --scene NAME");
    }
    if (*what == "tree") {
        return run_bench_tree(args);
    }
    if (*what == "bvh") {
        return run_bench_bvh(args, std::nullopt);
    }
    if (*what == "gi" || *what == "direct") {
        throw UsageError("bench " + *what + " needs --scene NAME");
    }
    if (*what != "sort") {
        throw UsageError("unknown benchmark '" + *what + "' (available: sort, tree, bvh, gi, direct)");
    }
    ContextOptions options;
    if (auto device = args.value("--device")) {
        options.device = *device;
    }
    std::vector<uint32_t> counts = {4096, 65536, 1048576};
    if (auto text = args.value("--counts")) {
        counts = parse_whole_number_list("--counts", *text, stages::kMaxKeyedVpls);
    }
    uint32_t runs = 20;
    if (auto text = args.value("--runs")) {
        runs = parse_whole_number("--runs", *text, 100000);
    }
    std::vector<stages::SortAlgorithm> algorithms = {stages::SortAlgorithm::bitonic, stages::SortAlgorithm::radix};
    if (auto text = args.value("--algorithm"); text && *text != "both") {
        auto algorithm = stages::parse_sort_algorithm(*text);
        if (!algorithm) {
            throw UsageError("--algorithm expects bitonic, radix or both, got '" + *text + "'");
        }
        algorithms = {*algorithm};
    }
    stages::SortOptions sort_options;
    if (auto text = args.value("--workgroup-size")) {
        sort_options.workgroup_size = parse_whole_number("--workgroup-size", *text, 1024);
    }
    const auto csv_path = args.value("--csv");
    args.finish();

    auto context = Context::create(options);
    const DeviceInfo& device = context->info();
    std::printf("device: %s (%s) - %s\n", device.name.c_str(), device.type_name.c_str(), device.reason.c_str());
    std::printf("%10s  %-18s %-9s %10s %10s %10s\n", "vpls", "stage", "algorithm", "median ms", "min ms", "max ms");

    std::ostringstream csv;
    csv << "device,vpls,algorithm,stage,runs,median_ms,min_ms,max_ms,sort_dispatches\n";
    std::vector<std::pair<uint32_t, stages::SortAlgorithm>> cases;  // every count with every algorithm
    for (uint32_t count : counts) {
        for (stages::SortAlgorithm algorithm : algorithms) {
            cases.emplace_back(count, algorithm);
        }
    }
    for (const auto& [count, algorithm] : cases) {
        const char* algorithm_name = stages::sort_algorithm_name(algorithm);
        auto vpls = random_vpls(count, count);
        auto vpl_buffer = Buffer::create(*context, uint64_t(count) * sizeof(shaders::Vpl),
                                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device, "vpls");
        auto bounds = Buffer::create(*context, stages::kVplBoundsBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                     MemoryUse::device, "vpl bounds");
        auto keys = Buffer::create(*context, uint64_t(count) * sizeof(uint64_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                   MemoryUse::device, "vpl keys");
        auto values = Buffer::create(*context, uint64_t(count) * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                     MemoryUse::device, "vpl key values");
        vpl_buffer.upload(vpls);

        sort_options.algorithm = algorithm;
        stages::KeyValueSorter sorter(*context, count, sort_options);
        PassList passes("bench sort");
        stages::add_vpl_key_passes(*context, passes, {vpl_buffer, bounds, keys, values}, count);
        sorter.add_pass(passes, keys, values, count);

        // The key passes rewrite the keys, so every run sorts unsorted input.
        const auto stats = time_passes(*context, passes, runs, std::to_string(count) + " VPLs, " + algorithm_name);
        check_sorted(keys, values, count);

        const uint32_t dispatches = sorter.dispatch_count(count);
        for (const StageStats& s : stats) {
            std::printf("%10u  %-18s %-9s %10.3f %10.3f %10.3f\n", count, s.stage.c_str(), algorithm_name, s.median_ms,
                        s.min_ms, s.max_ms);
            csv << '"' << device.name << "\"," << count << ',' << algorithm_name << ',' << s.stage << ',' << runs << ','
                << s.median_ms << ',' << s.min_ms << ',' << s.max_ms << ',' << dispatches << '\n';
        }
    }

    if (csv_path) {
        write_csv(*csv_path, csv.str());  // at the end: a failed run leaves no file
        std::printf("wrote %s\n", csv_path->c_str());
    }
    return 0;
}

}  // namespace vplkit::cli
