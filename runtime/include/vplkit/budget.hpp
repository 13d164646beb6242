#pragma once
// The budget in one call, for a front end (`--budget-ms`): calibrate or read the cache
// (budget_calibration.hpp), predict every configuration of the space, choose for B ms
// (budget_chooser.hpp), and the frame's settings with the choice applied; replan_for_budget
// chooses again when BudgetDrift (budget_drift.hpp) saw the measured times drift.
//
//   BudgetPlan plan = plan_for_budget(renderer, context.info(), scene, camera, settings, B, options);
//   print plan.choice.line(); render with plan.settings; stats "budget": budget_stats_fields(plan.choice)
//   per frame: if (plan.drift.record(frame_ms)) { replan_for_budget(plan); print plan.choice.line(); }
//
// docs/budget.md states the models and where they are wrong.

#include "vplkit/budget_calibration.hpp"
#include "vplkit/budget_chooser.hpp"
#include "vplkit/budget_config.hpp"
#include "vplkit/budget_drift.hpp"
#include "vplkit/budget_fixed.hpp"

#include <optional>
#include <vector>

namespace vplkit {

struct BudgetPlan {
    BudgetCalibration calibration;
    BudgetSpace space;  // narrowed to the fixed knobs
    BudgetFixed fixed;
    std::vector<BudgetCandidate> candidates;
    BudgetChoice choice;
    VplSource vpl_source = VplSource::ir;  // the base settings' source, resolved
    RenderSettings base;                   // the settings the plan started from
    RenderSettings settings;               // base with the choice applied
    BudgetDrift drift;                     // started with the choice's predicted time
};

// `space`: the configurations to weigh (none: default_budget_space of `base`), narrowed to
// `fixed` (the knobs the user gave: only the rest are chosen). Throws vplkit::Error for a bad
// budget or space, or when the model predicts no configuration of it.
BudgetPlan plan_for_budget(Renderer& renderer, const DeviceInfo& device, const scene::Scene& scene,
                           const scene::Camera& camera, const RenderSettings& base, double budget_ms,
                           const BudgetCalibrationOptions& options, std::optional<BudgetSpace> space = std::nullopt,
                           const BudgetFixed& fixed = {});

// Chooses again over the candidates' times scaled by plan.drift.scale(), updates the choice and
// the settings, and restarts the drift's window.
void replan_for_budget(BudgetPlan& plan);

}  // namespace vplkit
