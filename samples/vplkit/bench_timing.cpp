#include "bench_timing.hpp"

#include "cli.hpp"
#include "cli_checks.hpp"

#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/vpl_keys.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include <unistd.h>

namespace vplkit::cli {

std::vector<StageStats> time_passes(Context& context, PassList& passes, uint32_t runs, const std::string& label) {
    std::map<std::string, std::vector<double>> samples;  // stage -> ms per run
    std::vector<std::string> order;
    const bool terminal = isatty(fileno(stderr));
    if (!terminal) {
        std::fprintf(stderr, "[%s] 1 warm-up + %u timed runs\n", label.c_str(), runs);
    }
    for (uint32_t run = 0; run <= runs; ++run) {
        if (terminal) {  // a progress line that rewrites itself; logs get the one line above
            std::fprintf(stderr, "\r[%s] run %u/%u", label.c_str(), run, runs);
            std::fflush(stderr);
        }
        passes.run(context);
        if (run == 0) continue;
        double total = 0.0;
        for (const PassTiming& t : passes.timings()) {
            if (samples.find(t.name) == samples.end()) order.push_back(t.name);
            samples[t.name].push_back(t.gpu_ms);
            total += t.gpu_ms;
        }
        samples["total"].push_back(total);
    }
    if (terminal) std::fprintf(stderr, "\r%60s\r", "");

    order.push_back("total");
    std::vector<StageStats> stats;
    for (const std::string& stage : order) {
        std::vector<double> s = samples[stage];
        std::sort(s.begin(), s.end());
        const size_t n = s.size();
        stats.push_back({stage, n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]), s.front(), s.back()});
    }
    return stats;
}

void write_csv(const std::string& path, const std::string& text) {
    const std::string temporary = path + ".tmp" + std::to_string(::getpid());
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file << text;
    file.close();
    std::error_code error;
    if (!file) {
        std::filesystem::remove(temporary, error);
        throw Error("could not write " + path + " (is the folder there and writable?)");
    }
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        throw Error("could not write " + path + ": " + error.message());
    }
}

std::string csv_field(std::string_view text) {
    std::string field = "\"";
    for (char c : text) {
        if (c == '"') field += '"';
        field += c;
    }
    return field + '"';
}

void write_csv_if_asked(const std::optional<std::string>& path, const std::string& text) {
    if (!path) return;
    write_csv(*path, text);
    std::printf("wrote %s\n", path->c_str());
}

void add_vpl_counts_option(CLI::App& command, std::optional<std::string>& counts) {
    whole_number_list(
        command.add_option_function<std::string>(
            "--counts", [&counts](const std::string& v) { counts = v; }, "VPL counts (default 4096,65536,1048576)"),
        "N", stages::kMaxKeyedVpls);
}

std::vector<uint32_t> vpl_counts(const std::optional<std::string>& counts) {
    if (!counts) return {4096, 65536, 1048576};
    return parse_whole_number_list("--counts", *counts, stages::kMaxKeyedVpls);
}

}  // namespace vplkit::cli
