// `vplkit bench tree`: GPU time of every stage from VPLs to both light trees (keys, sort, leaves,
// RTSLC light tree, SST), from timestamp queries, median over many runs, as a table and CSV.
// VPLs are random or sampled on the surfaces of a standard set-up's scene.

#include "cli.hpp"
#include "cli_checks.hpp"
#include "device_options.hpp"
#include "commands.hpp"
#include "bench_timing.hpp"
#include "vpl_sources.hpp"

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene_setups.hpp"
#include "vplkit/stages/leaves.hpp"
#include "vplkit/stages/light_tree.hpp"
#include "vplkit/stages/sort.hpp"
#include "vplkit/stages/sst.hpp"
#include "vplkit/stages/vpl_keys.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#ifndef VPLKIT_SETUPS_FILE
#error "VPLKIT_SETUPS_FILE (the repository's scenes/setups.txt) must be defined by the build"
#endif

namespace vplkit::cli {

namespace {

// Both roots must hold all the flux (within float summation error): a benchmark of a wrong
// tree is worth nothing.
void check_roots(const std::vector<shaders::Vpl>& vpls, const Buffer& light_tree, const Buffer& sst) {
    double sum_rgb = 0.0;
    for (const auto& v : vpls) sum_rgb += double(v.flux.x) + v.flux.y + v.flux.z;
    const auto light_root = light_tree.download<shaders::LightTreeNode>(1)[0];
    const auto sst_root = sst.download<shaders::SstNode>(1)[0];
    const double sst_rgb = double(sst_root.colour.x) + sst_root.colour.y + sst_root.colour.z;
    const double tolerance = 1e-4 * sum_rgb;
    if (std::abs(light_root.intensity - sum_rgb) > tolerance || std::abs(sst_rgb - sum_rgb) > tolerance ||
        light_root.vpl_count != vpls.size() || sst_root.leaf_count != vpls.size()) {
        throw Error("bench tree: a tree root does not hold all " + std::to_string(vpls.size()) + " VPLs' flux");
    }
}

}  // namespace

namespace {

struct BenchTreeOptions {
    ContextOptions context;
    std::optional<std::string> counts, csv;
    std::optional<uint32_t> group_levels;
    uint32_t runs = 10;
    std::string source = "random";
    std::string sort = "radix";
};

int run_bench_tree(const BenchTreeOptions& o) {
    const ContextOptions& options = o.context;
    const std::vector<uint32_t> counts = vpl_counts(o.counts);
    const uint32_t runs = o.runs;
    const std::string& source = o.source;
    stages::SortOptions sort_options;
    sort_options.algorithm = *stages::parse_sort_algorithm(o.sort);
    stages::LightTreeOptions tree_options;
    if (o.group_levels) tree_options.group_levels = *o.group_levels;
    const std::optional<std::string>& csv_path = o.csv;

    // The scene first: a bad set-up name fails before any device work.
    std::optional<scene::Scene> surfaces;
    if (source != "random") {
        const scene::Setups setups = scene::load_setups(VPLKIT_SETUPS_FILE);
        surfaces = scene::load_setup_scene(setups.find(source));
    }

    auto context = Context::create(options);
    const DeviceInfo& device = context->info();
    std::printf("device: %s (%s) - %s\n", device.name.c_str(), device.type_name.c_str(), device.reason.c_str());
    std::printf("VPLs: %s; sort: %s\n", source.c_str(), stages::sort_algorithm_name(sort_options.algorithm));
    std::printf("%10s  %-22s %10s %10s %10s\n", "vpls", "stage", "median ms", "min ms", "max ms");

    std::ostringstream csv;
    csv << "device,source,sort,vpls,stage,runs,median_ms,min_ms,max_ms\n";
    for (uint32_t count : counts) {
        const auto vpls = surfaces ? surface_vpls(*surfaces, count, count) : random_vpls(count, count);
        const uint32_t leaves = stages::leaf_count(count);
        constexpr VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        auto vpl_buffer =
            Buffer::create(*context, uint64_t(count) * sizeof(shaders::Vpl), storage, MemoryUse::device, "vpls");
        auto bounds = Buffer::create(*context, stages::kVplBoundsBytes, storage, MemoryUse::device, "vpl bounds");
        auto keys = Buffer::create(*context, uint64_t(count) * 8, storage, MemoryUse::device, "vpl keys");
        auto values = Buffer::create(*context, uint64_t(count) * 4, storage, MemoryUse::device, "vpl key values");
        auto leaf_buffer =
            Buffer::create(*context, uint64_t(leaves) * sizeof(shaders::Vpl), storage, MemoryUse::device, "leaves");
        auto light_tree =
            Buffer::create(*context, uint64_t(stages::light_tree_node_count(count)) * sizeof(shaders::LightTreeNode),
                           storage, MemoryUse::device, "light tree");
        auto sst = Buffer::create(*context, uint64_t(stages::sst_node_count(count)) * sizeof(shaders::SstNode), storage,
                                  MemoryUse::device, "sst");
        auto counters = Buffer::create(*context, uint64_t(stages::sst_counter_count(count)) * 4, storage,
                                       MemoryUse::device, "sst counters");
        vpl_buffer.upload(vpls);

        stages::KeyValueSorter sorter(*context, count, sort_options);
        PassList passes("bench tree");
        stages::add_vpl_key_passes(*context, passes, {vpl_buffer, bounds, keys, values}, count);
        sorter.add_pass(passes, keys, values, count);
        stages::add_gather_leaves_pass(*context, passes, vpl_buffer, values, leaf_buffer, count);
        stages::add_light_tree_passes(*context, passes, leaf_buffer, light_tree, count, tree_options);
        stages::add_sst_passes(*context, passes, leaf_buffer, sst, counters, count);

        const auto stats = time_passes(*context, passes, runs, std::to_string(count) + " VPLs");
        check_roots(vpls, light_tree, sst);

        for (const StageStats& s : stats) {
            std::printf("%10u  %-22s %10.3f %10.3f %10.3f\n", count, s.stage.c_str(), s.median_ms, s.min_ms, s.max_ms);
            csv << csv_field(device.name) << ',' << csv_field(source) << ','
                << stages::sort_algorithm_name(sort_options.algorithm) << ',' << count << ',' << s.stage << ',' << runs
                << ',' << s.median_ms << ',' << s.min_ms << ',' << s.max_ms << '\n';
        }
    }
    write_csv_if_asked(csv_path, csv.str());
    return 0;
}

}  // namespace

void add_bench_tree(CLI::App& bench, Runners& runners) {
    CLI::App* tree = add_command(
        bench, "tree", "GPU time of every stage from VPLs to both light trees",
        "Times, per VPL count, every stage from a VPL buffer to both light trees: bounds and keys, the key sort, "
        "gathering the leaves, the RTSLC light tree and the SST. One warm-up run, then R timed runs; prints "
        "median, min and max per stage, and checks the last run's trees.");
    auto o = std::make_shared<BenchTreeOptions>();
    add_device_options(*tree, o->context, false);
    add_vpl_counts_option(*tree, o->counts);
    whole_number(tree->add_option("--runs", o->runs, "timed runs per count")->capture_default_str(), "R", 1, 100000);
    tree->add_option("--source", o->source,
                     "random, or a standard set-up (scenes/setups.txt) whose scene surfaces the VPLs are sampled "
                     "on, e.g. sponza-sun")
        ->capture_default_str()
        ->option_text("random|SETUP");
    one_of(tree->add_option("--sort", o->sort, "the key sort")->capture_default_str(), {"radix", "bitonic"});
    whole_number(tree->add_option_function<uint32_t>(
                     "--group-levels", [o](uint32_t v) { o->group_levels = v; },
                     "light-tree levels built per dispatch (default: the device's)"),
                 "G", 1, stages::kLightTreeMaxGroupLevels);
    tree->add_option_function<std::string>(
            "--csv", [o](const std::string& v) { o->csv = v; }, "also write every statistic as CSV")
        ->option_text("FILE");
    runners.push_back({tree, [o] { return run_bench_tree(*o); }});
}

}  // namespace vplkit::cli
