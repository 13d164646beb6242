#pragma once
// --budget-ms for render, sequence and view: the option, the knobs the command line fixed beside
// it (--method, --spp, --gi-resolution, --denoise, --vpls, --block: kept, the rest chosen), the
// plan with its printout, and the stats file's "budget" object (runtime/include/vplkit/budget.hpp).

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "vplkit/budget.hpp"

#include <optional>
#include <string>

namespace vplkit::cli {

// Declares --budget-ms B on `command`, in `group`; `more` ends the help (what the command does on drift).
CLI::Option* add_budget_option(CLI::App& command, std::optional<double>& budget_ms, const std::string& more);

// The knobs given on `command`'s line, read from `settings` (the parsed request's).
BudgetFixed budget_fixed_by_options(const CLI::App& command, const RenderSettings& settings);

// plan_for_budget with the calibration's progress on stderr; prints where the model came from,
// what was kept, and the choice's line.
BudgetPlan plan_budget(Renderer& renderer, const DeviceInfo& device, const scene::Scene& scene,
                       const scene::Camera& camera, const RenderSettings& settings, double budget_ms,
                       const std::string& scene_id, const BudgetFixed& fixed);

// The stats file's "budget": method, spp, gi_resolution, denoise, vpls, block_size, predicted_ms,
// predicted_rmse, budget_ms, over_budget.
nlohmann::ordered_json budget_stats_json(const BudgetChoice& choice);

}  // namespace vplkit::cli
