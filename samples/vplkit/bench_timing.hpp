#pragma once
// What every `vplkit bench` run shares: timing a pass list over many runs (median, min, max of the
// GPU timestamps per pass, with progress on the terminal), the VPL counts bench sort and bench
// tree time, and writing the CSV whole.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace CLI {
class App;
}  // namespace CLI

namespace vplkit {
class Context;
class PassList;
}  // namespace vplkit

namespace vplkit::cli {

struct StageStats {
    std::string stage;  // a pass name, or "total" (the sum of the passes of one run)
    double median_ms = 0, min_ms = 0, max_ms = 0;
};

// Runs `passes` once to warm up (lavapipe compiles shaders at their first dispatch), then `runs`
// timed times, and returns one entry per pass in pass order, then "total". `label` names the
// case in the progress line (stderr).
std::vector<StageStats> time_passes(Context& context, PassList& passes, uint32_t runs, const std::string& label);

// `text` as one CSV field (RFC 4180): in double quotes, a quote inside doubled, so that a device
// name or a scene path with a comma or quote stays one column.
std::string csv_field(std::string_view text);

// Writes `text` to `path` through a temporary file: a failure leaves no partial file.
// Throws vplkit::Error naming the path.
void write_csv(const std::string& path, const std::string& text);
// write_csv when `path` was given (--csv), and says so on stdout. Called at the end of a run, so
// that a failed run leaves no file.
void write_csv_if_asked(const std::optional<std::string>& path, const std::string& text);

// Declares --counts, the VPL counts of bench sort and bench tree, on `command`; `counts` (the
// command's options object's) keeps the text for vpl_counts.
void add_vpl_counts_option(CLI::App& command, std::optional<std::string>& counts);
// The VPL counts --counts gave, else 4096, 65536 and 1048576.
std::vector<uint32_t> vpl_counts(const std::optional<std::string>& counts);

}  // namespace vplkit::cli
