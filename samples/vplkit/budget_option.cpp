// --budget-ms's option, the knobs kept beside it, the plan's printout and its stats
// (budget_option.hpp).

#include "budget_option.hpp"

#include "cli_checks.hpp"
#include "stats_json.hpp"

#include <cstdio>

namespace vplkit::cli {

CLI::Option* add_budget_option(CLI::App& command, std::optional<double>& budget_ms, const std::string& more) {
    return number(command.add_option_function<double>(
                      "--budget-ms", [&budget_ms](double v) { budget_ms = v; },
                      "choose the method (sst, rtslc, hybrid), --spp, --gi-resolution, --denoise (off, svgf), --vpls "
                      "and --block with the least predicted error within B ms of GPU time per frame on this device; "
                      "those of them given beside it are kept and only the rest chosen (about 30 calibration "
                      "frames, cached in out/budget-cache by device, scene, size and camera; docs/budget.md)" +
                          more),
                  "B", NumberRange::above(0.0));
}

BudgetFixed budget_fixed_by_options(const CLI::App& command, const RenderSettings& settings) {
    BudgetFixed fixed;
    const auto given = [&command](const char* name) {
        const CLI::Option* option = command.get_option_no_throw(name);
        return option && option->count() > 0;
    };
    if (given("--method")) fixed.method = settings.method;
    if (given("--spp")) fixed.spp = settings.samples_per_pixel;
    if (given("--gi-resolution")) fixed.half_resolution = settings.half_resolution_gi;
    if (given("--denoise")) fixed.denoise = settings.denoise;
    // --vpls sets every source's budget (vpl_paths, brsm.vpl_count, smc.budget) alike.
    if (given("--vpls")) fixed.vpls = settings.vpl_paths;
    if (given("--block")) fixed.block_size = settings.block_size;
    return fixed;
}

BudgetPlan plan_budget(Renderer& renderer, const DeviceInfo& device, const scene::Scene& scene,
                       const scene::Camera& camera, const RenderSettings& settings, double budget_ms,
                       const std::string& scene_id, const BudgetFixed& fixed) {
    BudgetCalibrationOptions options;
    options.scene_id = scene_id;
    options.progress = [](uint32_t done, uint32_t total) {
        std::fprintf(stderr, "[budget] calibration frame %u/%u\n", done, total);
    };
    BudgetPlan plan =
        plan_for_budget(renderer, device, scene, camera, settings, budget_ms, options, std::nullopt, fixed);
    std::printf("budget: %s %s\n", plan.calibration.from_cache ? "model read from" : "calibrated, cached in",
                plan.calibration.cache_file.string().c_str());
    if (fixed.any()) std::printf("budget: kept as given: %s; the rest chosen\n", describe_budget_fixed(fixed).c_str());
    std::printf("%s\n", plan.choice.line().c_str());
    return plan;
}

nlohmann::ordered_json budget_stats_json(const BudgetChoice& choice) {
    const BudgetStatsFields f = budget_stats_fields(choice);
    return {{"method", f.method},
            {"spp", f.spp},
            {"gi_resolution", f.gi_resolution},
            {"denoise", f.denoise},
            {"vpls", f.vpls},
            {"block_size", f.block_size},
            {"predicted_ms", json_number(f.predicted_ms)},
            {"predicted_rmse", json_number(f.predicted_rmse)},
            {"budget_ms", json_number(f.budget_ms)},
            {"over_budget", f.over_budget}};
}

}  // namespace vplkit::cli
