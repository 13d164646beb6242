// PassList::run: the StepList recorded into one of the context's command buffers, each step
// bracketed by a debug label and two timestamps.

#include "vplkit/pass_list.hpp"

#include "timestamps.hpp"
#include "vplkit/context.hpp"

#include <atomic>
#include <numeric>
#include <set>
#include <string>

namespace vplkit {

void PassList::clear() {
    StepList::clear();
    timings_.clear();
    barriers_.clear();
}

double PassList::total_gpu_ms() const {
    return std::accumulate(timings_.begin(), timings_.end(), 0.0,
                           [](double sum, const PassTiming& t) { return sum + t.gpu_ms; });
}

size_t PassList::pipeline_barrier_count() const {
    std::set<size_t> passes;
    for (const BarrierRecord& b : barriers_) passes.insert(b.pass);
    return passes.size();
}

std::string PassList::describe_barriers() const {
    std::vector<std::string> names;
    for (const Step& s : steps()) names.push_back(s.name);
    std::string out;
    for (const BarrierRecord& b : barriers_) out += b.describe(names) + "\n";
    return out;
}

void PassList::run(Context& context) {
    timings_.clear();
    barriers_.clear();
    if (empty()) return;

    detail::TimestampQueries queries(context, uint32_t(2 * size()));
    std::vector<BarrierRecord> barriers;
    Hooks hooks;
    hooks.before = [&](VkCommandBuffer cmd, size_t i) {
        context.begin_label(cmd, steps()[i].name);
        queries.write(cmd, uint32_t(2 * i));
    };
    hooks.after = [&](VkCommandBuffer cmd, size_t i) {
        queries.write(cmd, uint32_t(2 * i + 1));
        context.end_label(cmd);
    };
    context.one_shot([&](VkCommandBuffer cmd) {
        queries.reset(cmd);
        context.begin_label(cmd, name_);
        barriers = record(cmd, hooks);
        context.end_label(cmd);
    });

    barriers_ = std::move(barriers);
    const std::vector<double> durations = queries.pair_durations_ms();
    static std::atomic<uint64_t> submissions{0};
    const uint64_t submission = ++submissions;
    for (size_t i = 0; i < size(); ++i) {
        timings_.push_back({steps()[i].name, durations.at(i), steps()[i].tag, submission});
    }
}

}  // namespace vplkit
