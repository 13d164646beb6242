#pragma once
// What every `vplkit bench` run shares: timing a pass list over many runs (median, min, max of the
// GPU timestamps per pass, with progress on the terminal), and writing the CSV whole.

#include <cstdint>
#include <string>
#include <vector>

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

// Writes `text` to `path` through a temporary file: a failure leaves no partial file.
// Throws vplkit::Error naming the path.
void write_csv(const std::string& path, const std::string& text);

}  // namespace vplkit::cli
