#include "render_stats.hpp"

#include "setting_flags.hpp"
#include "stats_json.hpp"

#include "vplkit/gi_methods.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace vplkit::cli {

namespace {

const char* vpl_source_name(VplSource source) {
    switch (source) {
        case VplSource::ir:
            return "ir";
        case VplSource::brsm:
            return "brsm";
        case VplSource::smc:
            return "smc";
        case VplSource::automatic:
            return "auto";
    }
    return "?";
}

double median(std::vector<double> values) {
    if (values.empty()) return NAN;
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

nlohmann::ordered_json gi_counts_stats(const stages::GiCounts& c) {
    return {{"traversals", c.traversals},           {"levels_per_traversal", json_number(c.levels_per_traversal())},
            {"dead_branches", c.dead_branches},     {"mock_cut_pixels", c.mock_cut_pixels},
            {"dropped_samples", c.dropped_samples}, {"dropped_pixels", c.dropped_pixels}};
}

}  // namespace

nlohmann::ordered_json stats_header(const std::string& command) {
    return {{"format", "vplkit stats 1"},
            {"command", command},
            {"null_means", "a number that is not finite (NaN or infinity), or one this run did not measure"}};
}

nlohmann::ordered_json device_stats(const DeviceInfo& device) {
    const bool lavapipe = device.driver_name == "llvmpipe" || device.name.find("llvmpipe") != std::string::npos;
    return {{"name", device.name},
            {"type", device.type_name},
            {"driver", device.driver_name},
            {"driver_info", device.driver_info},
            {"api_version", device.api_version_string},
            {"lavapipe", lavapipe},
            {"reason", device.reason}};
}

void PlanLog::add(uint32_t frame_index, const FramePlan& plan) {
    const std::string described = plan.describe();
    if (!plans_.empty() && described == last_) {
        plans_.back()["frame_indices"][1] = frame_index;
        return;
    }
    last_ = described;
    nlohmann::ordered_json stages = nlohmann::ordered_json::array();
    for (const PlannedStage& s : plan.stages) {
        stages.push_back({{"stage", stage_name(s.stage)}, {"runs", s.runs}, {"reason", with_flags(s.reason)}});
    }
    nlohmann::ordered_json notes = nlohmann::ordered_json::array();
    for (const std::string& note : plan.notes) notes.push_back(with_flags(note));
    plans_.push_back({{"frame_indices", {frame_index, frame_index}},
                      {"summary", plan.summary()},
                      {"vpl_source", vpl_source_name(plan.vpl_source)},
                      {"direct_sampler", direct_sampler_name(plan.direct_sampler)},
                      {"reuse_vpls", plan.reuse_vpls},
                      {"reuse_trees", plan.reuse_trees},
                      {"glossy_branch", plan.glossy_branch},
                      {"glossy_reason", with_flags(plan.glossy_reason)},
                      {"notes", notes},
                      {"stages", stages}});
}

nlohmann::ordered_json timing_stats(const std::vector<std::vector<PassTiming>>& frames) {
    const size_t first = frames.size() > 1 ? 1 : 0;
    nlohmann::ordered_json every = nlohmann::ordered_json::array();
    std::vector<double> totals;
    // Per stage and per pass name: the timed frames' values, in first-seen order over the timed
    // frames (a stage a later frame alone ran, e.g. a VPL set remade, is kept too).
    std::vector<std::string> stage_order, pass_order;
    std::map<std::string, std::vector<double>> stage_ms, pass_ms;
    std::map<std::string, size_t> pass_count;
    std::map<std::string, double> first_stage_sum, first_pass_sum;  // frame 0's, when it is not timed
    std::vector<std::string> first_stage_order, first_pass_order;
    const auto note = [](std::vector<std::string>& order, const std::string& name) {
        if (std::find(order.begin(), order.end(), name) == order.end()) order.push_back(name);
    };
    for (size_t f = 0; f < frames.size(); ++f) {
        double total = 0.0;
        std::map<std::string, double> stage_sum, pass_sum;
        std::map<std::string, size_t> passes_here;
        for (const PassTiming& t : frames[f]) {
            total += t.gpu_ms;
            const std::string stage = t.tag == 0 ? "untagged" : stage_name(FrameStage(t.tag - 1));
            stage_sum[stage] += t.gpu_ms;
            pass_sum[t.name] += t.gpu_ms;
            ++passes_here[t.name];
            note(f < first ? first_stage_order : stage_order, stage);
            note(f < first ? first_pass_order : pass_order, t.name);
        }
        every.push_back(json_number(total));
        if (f < first) {
            first_stage_sum = stage_sum, first_pass_sum = pass_sum;
            continue;
        }
        totals.push_back(total);
        for (const auto& [name, ms] : stage_sum) stage_ms[name].push_back(ms);
        for (const auto& [name, ms] : pass_sum) pass_ms[name].push_back(ms);
        for (const auto& [name, n] : passes_here) pass_count[name] = std::max(pass_count[name], n);
    }
    nlohmann::ordered_json stages = nlohmann::ordered_json::array(), passes = nlohmann::ordered_json::array();
    for (const std::string& name : stage_order) {
        stages.push_back({{"stage", name}, {"ms", json_number(median(stage_ms[name]))}});
    }
    for (const std::string& name : pass_order) {
        passes.push_back({{"pass", name}, {"ms", json_number(median(pass_ms[name]))}, {"passes", pass_count[name]}});
    }
    // What only the untimed first frame ran (the VPLs and trees the later frames reuse): its cost
    // is paid once, so it is not in the medians; frame 0's time, shader compiles included.
    nlohmann::ordered_json first_stages = nlohmann::ordered_json::array();
    nlohmann::ordered_json first_passes = nlohmann::ordered_json::array();
    for (const std::string& name : first_stage_order) {
        if (!stage_ms.count(name))
            first_stages.push_back({{"stage", name}, {"ms", json_number(first_stage_sum[name])}});
    }
    for (const std::string& name : first_pass_order) {
        if (!pass_ms.count(name)) first_passes.push_back({{"pass", name}, {"ms", json_number(first_pass_sum[name])}});
    }
    return {{"frame_ms", json_number(median(totals))},
            {"timed_frame_indices", {first, frames.size() - 1}},
            {"frame_gpu_ms", every},
            {"stage_ms", stages},
            {"pass_ms", passes},
            {"first_frame_only_stage_ms", first_stages},
            {"first_frame_only_pass_ms", first_passes}};
}

nlohmann::ordered_json counters_stats(const RenderedImage& image, const RenderSettings& settings) {
    const GiMethodInfo& method = gi_method(settings.method);
    nlohmann::ordered_json c = {{"vpls", image.vpl_count},
                                {"vpl_source", vpl_source_name(image.vpl_source)},
                                {"reused_vpls", image.reused_vpls},
                                {"reused_trees", image.reused_trees},
                                {"gi_size", {image.gi_width, image.gi_height}},
                                {"non_finite_pixels", image.non_finite_pixels}};
    if (method.ground_truth) {
        c["exact_dropped_pixels"] = image.dropped_pixels;
        c["exact_gi_wall_ms"] = json_number(image.exact_gi_wall_ms);
    }
    if (method.samples) c["gi"] = gi_counts_stats(image.gi_counts);
    if (method.reads_sst) c["sst_sigma_max"] = json_number(image.sst_sigma_max);
    if (image.direct_sampler == DirectSampler::tree || image.direct_sampler == DirectSampler::tree2) {
        c["direct_tree"] = gi_counts_stats(image.direct_counts);
    }
    if (image.smc) {
        const vplkit::SmcCounts& s = *image.smc;
        c["smc"] = {{"vpls", s.vpls},
                    {"hits", s.hits},
                    {"invalid", s.invalid},
                    {"revalidated", s.revalidated},
                    {"candidates", s.candidates},
                    {"strong", s.strong},
                    {"min_moves", s.min_moves},
                    {"still_invalid", s.still_invalid},
                    {"removed", s.removed},
                    {"moved", s.moved},
                    {"cut_short", s.cut_short}};
    }
    if (settings.half_resolution_gi) {
        c["upsample"] = {{"fallback_pixels", image.upsample_counts.fallback_pixels},
                         {"empty_pixels", image.upsample_counts.empty_pixels}};
    }
    return c;
}

}  // namespace vplkit::cli
