// `vplkit bench sort`: GPU time of the VPL key passes and the sort (bitonic, radix or both) for
// several VPL counts, from timestamp queries, median over many runs, as a table and optionally CSV.
// Random VPLs (uniform in a unit box, uniform normals) stand in for a scene's until scenes load.

#include "cli.hpp"
#include "cli_checks.hpp"
#include "device_options.hpp"
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

namespace {

struct BenchSortOptions {
    ContextOptions context;
    std::optional<std::string> counts, csv;
    uint32_t runs = 20;
    std::string algorithm = "both";
    std::optional<uint32_t> workgroup_size;
};

int run_bench_sort(const BenchSortOptions& o) {
    const ContextOptions& options = o.context;
    const std::vector<uint32_t> counts = vpl_counts(o.counts);
    const uint32_t runs = o.runs;
    std::vector<stages::SortAlgorithm> algorithms = {stages::SortAlgorithm::bitonic, stages::SortAlgorithm::radix};
    if (o.algorithm != "both") algorithms = {*stages::parse_sort_algorithm(o.algorithm)};
    stages::SortOptions sort_options;
    if (o.workgroup_size) sort_options.workgroup_size = *o.workgroup_size;
    const std::optional<std::string>& csv_path = o.csv;

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
            csv << csv_field(device.name) << ',' << count << ',' << algorithm_name << ',' << s.stage << ',' << runs
                << ',' << s.median_ms << ',' << s.min_ms << ',' << s.max_ms << ',' << dispatches << '\n';
        }
    }

    write_csv_if_asked(csv_path, csv.str());
    return 0;
}

}  // namespace

void add_bench(CLI::App& vplkit, Runners& runners) {
    CLI::App* bench = add_command(
        vplkit, "bench",
        "GPU timings of the kit's stages (sort, tree, bvh) and accuracy against time (gi, direct; bench alone: gi)",
        "The benchmarks below, each with its own options ('vplkit bench NAME --help'). Without a name, 'vplkit "
        "bench [options]' runs bench gi: 'vplkit bench --scene cornell --quick --out DIR' is 'vplkit bench gi "
        "--scene cornell --quick --out DIR'.");
    bench->footer("");
    auto sort_command = add_command(
        *bench, "sort", "GPU time of the VPL key passes and the key sort (bitonic, radix)",
        "Times the VPL key passes (bounds, Morton/normal keys) and the sort of the (key, index) pairs on the GPU "
        "with timestamp queries: one warm-up run, then R timed runs per count and algorithm; prints median, min "
        "and max per stage. Checks the last run's output is sorted. Random VPLs (uniform in a unit box, uniform "
        "normals).");
    auto o = std::make_shared<BenchSortOptions>();
    add_device_options(*sort_command, o->context, false);
    add_vpl_counts_option(*sort_command, o->counts);
    whole_number(sort_command->add_option("--runs", o->runs, "timed runs per count")->capture_default_str(), "R", 1,
                 100000);
    one_of(sort_command->add_option("--algorithm", o->algorithm, "the sort, or both")->capture_default_str(),
           {"bitonic", "radix", "both"});
    whole_number(sort_command->add_option_function<uint32_t>(
                     "--workgroup-size", [o](uint32_t v) { o->workgroup_size = v; },
                     "sort workgroup size (default: bitonic 256, radix 32; bitonic: a power of two)"),
                 "W", 1, 1024);
    sort_command
        ->add_option_function<std::string>(
            "--csv", [o](const std::string& v) { o->csv = v; }, "also write every statistic as CSV")
        ->option_text("FILE");
    runners.push_back({sort_command, [o] { return run_bench_sort(*o); }});
    add_bench_tree(*bench, runners);
    add_bench_bvh(*bench, runners);
    add_bench_gi(*bench, runners);
    add_bench_direct(*bench, runners);
    // bench alone: main reads options without a name as gi's, so what is left here is no benchmark.
    runners.push_back({bench,
                       [bench]() -> int {
                           const std::vector<std::string> left = bench->remaining();
                           if (left.empty()) {
                               throw UsageError(
                                   "bench needs a benchmark name: sort, tree, bvh, gi or direct (options alone run "
                                   "gi: vplkit bench --scene NAME ...)");
                           }
                           throw UsageError("unknown benchmark '" + left.front() +
                                            "' (available: sort, tree, bvh, gi, direct)");
                       },
                       true});
}

}  // namespace vplkit::cli
