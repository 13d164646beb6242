#include "render_report.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <utility>

namespace vplkit::cli {

namespace {

using StageTimes = std::vector<std::pair<std::string, double>>;

// Passes of one name (e.g. the importance mip levels) summed into one line, in first-seen order.
StageTimes by_stage(const std::vector<PassTiming>& timings) {
    StageTimes stages;
    std::map<std::string, size_t> index;
    std::map<std::string, int> passes;
    for (const PassTiming& t : timings) {
        auto [it, added] = index.try_emplace(t.name, stages.size());
        if (added) stages.push_back({t.name, 0.0});
        stages[it->second].second += t.gpu_ms;
        ++passes[t.name];
    }
    for (auto& [name, ms] : stages) {
        if (passes[name] > 1) name += " (" + std::to_string(passes[name]) + " passes)";
    }
    return stages;
}

// Each stage's median over the frames that ran it, in the order the frames first ran them.
StageTimes median_stages(const std::vector<StageTimes>& frames) {
    std::vector<std::string> names;
    for (const StageTimes& frame : frames) {
        for (const auto& [name, ms] : frame) {
            if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
        }
    }
    StageTimes out;
    for (const std::string& name : names) {
        std::vector<double> values;
        for (const StageTimes& frame : frames) {
            for (const auto& [n, v] : frame) {
                if (n == name) values.push_back(v);
            }
        }
        std::sort(values.begin(), values.end());
        const size_t n = values.size();
        out.push_back({name, n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2])});
    }
    return out;
}

std::string frames_text(uint32_t first, uint32_t last) {
    return first == last ? "frame " + std::to_string(first + 1)
                         : "frames " + std::to_string(first + 1) + ".." + std::to_string(last + 1);
}

std::string line(const char* format, const std::string& name, double ms) {
    char text[160];
    std::snprintf(text, sizeof text, format, name.c_str(), ms);
    return text;
}

}  // namespace

std::vector<std::string> plan_lines(const std::vector<FramePlan>& plans) {
    struct Run {
        uint32_t first, last;
        const FramePlan* plan;
    };
    std::vector<Run> runs;
    for (uint32_t i = 0; i < plans.size(); ++i) {
        if (!runs.empty() && plans[i].summary() == runs.back().plan->summary()) {
            runs.back().last = i;
        } else {
            runs.push_back({i, i, &plans[i]});
        }
    }
    std::vector<std::string> lines;
    if (runs.size() == 1) return {runs.front().plan->summary()};
    const FramePlan& first = *runs.front().plan;
    for (const Run& run : runs) {
        // A later run's line puts the stages frame 1 made and this run reuses under "reused", not
        // under "left out": their work is in this frame's image.
        const bool reuses = run.first > runs.front().last && (run.plan->reuse_vpls || run.plan->reuse_trees);
        std::string kept, out, reused;
        for (const PlannedStage& s : run.plan->stages) {
            std::string& list = s.runs ? kept : (reuses && first.runs(s.stage) ? reused : out);
            list += (list.empty() ? "" : ", ") + std::string(stage_name(s.stage));
        }
        std::string text = "plan, " + frames_text(run.first, run.last) + ": " + kept;
        if (!out.empty()) text += "; left out: " + out;
        if (!reused.empty())
            text += "; reused from " + frames_text(runs.front().first, runs.front().last) + ": " + reused;
        if (run.plan->glossy_branch) text += "; glossy branch on";
        lines.push_back(text);
    }
    return lines;
}

std::string stage_table(const std::vector<std::vector<PassTiming>>& frames, uint32_t width, uint32_t height) {
    const uint32_t count = uint32_t(frames.size());
    std::vector<StageTimes> timed;
    for (uint32_t f = count > 1 ? 1 : 0; f < count; ++f) timed.push_back(by_stage(frames[f]));
    std::string text = std::to_string(width) + "x" + std::to_string(height) + ", GPU time per stage" +
                       (count > 1 ? " (median of frames 2.." + std::to_string(count) + "):\n" : ":\n");
    double total = 0.0;
    const StageTimes medians = median_stages(timed);
    for (const auto& [name, ms] : medians) {
        text += line("  %-30s %9.3f ms\n", name, ms);
        total += ms;
    }
    text += line("  %-30s %9.3f ms\n", "total", total);
    if (count > 1) {
        // What frame 1 made and the later frames reused: its cost is paid once, not per frame.
        std::string made;
        double made_total = 0.0;
        for (const auto& [name, ms] : by_stage(frames.front())) {
            const bool timed_later =
                std::any_of(medians.begin(), medians.end(), [&](const auto& stage) { return stage.first == name; });
            if (timed_later) continue;
            made += line("  %-30s %9.3f ms\n", name, ms);
            made_total += ms;
        }
        if (!made.empty()) {
            text += "made on frame 1 only and reused after (frame 1's time, which includes its shader compiles):\n" +
                    made + line("  %-30s %9.3f ms\n", "total", made_total);
        }
    }
    return text;
}

}  // namespace vplkit::cli
