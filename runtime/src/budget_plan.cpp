// plan_for_budget and replan_for_budget (budget.hpp).

#include "vplkit/budget.hpp"

#include "vplkit/error.hpp"
#include "vplkit/planner.hpp"

#include <cmath>

namespace vplkit {

BudgetPlan plan_for_budget(Renderer& renderer, const DeviceInfo& device, const scene::Scene& scene,
                           const scene::Camera& camera, const RenderSettings& base, double budget_ms,
                           const BudgetCalibrationOptions& options, std::optional<BudgetSpace> space,
                           const BudgetFixed& fixed) {
    // The budget is checked before the calibration's frames are spent.
    if (!std::isfinite(budget_ms) || budget_ms <= 0.0) {
        throw Error("budget: the frame time budget must be a number of milliseconds > 0");
    }
    BudgetPlan plan;
    plan.base = base;
    plan.vpl_source = plan_frame(scene, base, "budget").vpl_source;
    plan.fixed = fixed;
    plan.space = narrow_budget_space(space ? *space : default_budget_space(base, plan.vpl_source), fixed);
    plan.calibration = calibrate_budget(renderer, device, scene, camera, base, plan.space, options);
    plan.candidates = budget_candidates(plan.calibration.model, plan.space, scene, base);
    if (plan.candidates.empty()) {
        throw Error("budget: the calibration predicts no configuration of the space (none of its plans was timed)");
    }
    plan.choice = choose_for_budget(plan.candidates, budget_ms);
    plan.settings = apply_budget_config(base, plan.choice.chosen.config, plan.vpl_source);
    plan.drift.start(plan.choice.chosen.predicted_ms);
    return plan;
}

void replan_for_budget(BudgetPlan& plan) {
    plan.choice = choose_for_budget(scaled_candidates(plan.candidates, plan.drift.scale()), plan.choice.budget_ms);
    plan.settings = apply_budget_config(plan.base, plan.choice.chosen.config, plan.vpl_source);
    plan.drift.start(plan.choice.chosen.predicted_ms);
}

}  // namespace vplkit
