#include "render_report.hpp"

#include <algorithm>
#include <cstdio>
#include <initializer_list>
#include <map>
#include <utility>

namespace vplkit::cli {

namespace {

// One line of the table: a pass name, its time summed over its passes, and how many it had.
struct StageTime {
    std::string name;
    double ms = 0.0;
    size_t passes = 0;
};
using StageTimes = std::vector<StageTime>;

// Passes of one name (e.g. the importance mip levels) summed into one line, in first-seen order.
StageTimes by_stage(const std::vector<PassTiming>& timings) {
    StageTimes stages;
    std::map<std::string, size_t> index;
    for (const PassTiming& t : timings) {
        auto [it, added] = index.try_emplace(t.name, stages.size());
        if (added) stages.push_back({t.name, 0.0, 0});
        stages[it->second].ms += t.gpu_ms;
        ++stages[it->second].passes;
    }
    return stages;
}

// Each stage's median over the frames that ran it, in the order the frames first ran them, with
// the most passes a frame gave it (a frame that ran more passes of a name is still that stage).
StageTimes median_stages(const std::vector<StageTimes>& frames) {
    StageTimes out;
    for (const StageTimes& frame : frames) {
        for (const StageTime& stage : frame) {
            if (std::none_of(out.begin(), out.end(), [&](const StageTime& o) { return o.name == stage.name; })) {
                out.push_back({stage.name, 0.0, 0});
            }
        }
    }
    for (StageTime& stage : out) {
        std::vector<double> values;
        for (const StageTimes& frame : frames) {
            for (const StageTime& s : frame) {
                if (s.name != stage.name) continue;
                values.push_back(s.ms);
                stage.passes = std::max(stage.passes, s.passes);
            }
        }
        std::sort(values.begin(), values.end());
        const size_t n = values.size();
        stage.ms = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    }
    return out;
}

std::string label(const StageTime& stage) {
    return stage.passes > 1 ? stage.name + " (" + std::to_string(stage.passes) + " passes)" : stage.name;
}

std::string frames_text(uint32_t first, uint32_t last) {
    return first == last ? "frame " + std::to_string(first + 1)
                         : "frames " + std::to_string(first + 1) + ".." + std::to_string(last + 1);
}

// "  name ....... 1.234 ms": the name column as wide as the longest name of the table.
std::string line(const std::string& name, double ms, int width) {
    char text[48];
    std::snprintf(text, sizeof text, " %9.3f ms\n", ms);
    return "  " + name + std::string(size_t(std::max(0, width - int(name.size()))), ' ') + text;
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
    const StageTimes medians = median_stages(timed);
    // What frame 1 made and the later frames reused (by name: frame 1 may run more passes of a
    // stage every frame runs, e.g. SMC's warm-up updates): its cost is paid once, not per frame.
    StageTimes made;
    if (count > 1) {
        for (const StageTime& stage : by_stage(frames.front())) {
            const auto same = [&](const StageTime& m) { return m.name == stage.name; };
            if (std::none_of(medians.begin(), medians.end(), same)) made.push_back(stage);
        }
    }
    int column = 30;
    for (const StageTimes* list : std::initializer_list<const StageTimes*>{&medians, &made}) {
        for (const StageTime& stage : *list) column = std::max(column, int(label(stage).size()));
    }
    std::string text = std::to_string(width) + "x" + std::to_string(height) + ", GPU time per stage" +
                       (count > 1 ? " (median of frames 2.." + std::to_string(count) + "):\n" : ":\n");
    double total = 0.0;
    for (const StageTime& stage : medians) {
        text += line(label(stage), stage.ms, column);
        total += stage.ms;
    }
    text += line("total", total, column);
    if (!made.empty()) {
        double made_total = 0.0;
        text += "made on frame 1 only and reused after (frame 1's time, which includes its shader compiles):\n";
        for (const StageTime& stage : made) {
            text += line(label(stage), stage.ms, column);
            made_total += stage.ms;
        }
        text += line("total", made_total, column);
    }
    return text;
}

}  // namespace vplkit::cli
