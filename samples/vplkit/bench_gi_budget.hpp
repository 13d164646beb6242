#pragma once
// `vplkit bench gi` checks the budget chooser (runtime/include/vplkit/budget.hpp): the model is
// calibrated (or read from the cache) for the bench's settings, and for budgets across the time
// range of the sweep's points that lie in the chooser's space (sst, rtslc, hybrid; any spp, full
// or half resolution, raw or svgf; block 8, the run's VPL budget), the choice is rendered and
// measured like a point and set against the best measured point within the budget.

#include "bench_gi.hpp"

#include "vplkit/render_settings.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace vplkit {
class Renderer;
struct DeviceInfo;
namespace scene {
struct Scene;
}
}  // namespace vplkit

namespace vplkit::cli {

struct BudgetCheckInputs {
    const RenderSettings* base = nullptr;  // the bench's settings (size, VPL source and budget, seed)
    uint32_t frames = 3;                   // per measured choice, as per point
    std::vector<double> fractions;         // of the time range
    const std::vector<float>* truth_rgb = nullptr;
    const std::vector<float>* truth_radiance = nullptr;
    std::filesystem::path out;        // the bench's folder (images/)
    std::filesystem::path cache_dir;  // the model's cache
    std::string scene_id;
};

// Fills run.budget_check and run.budget_note (a note alone when fewer than two points are comparable).
void check_budget_chooser(Renderer& renderer, const DeviceInfo& device, const scene::Scene& scene,
                          const BudgetCheckInputs& in, BenchRun& run);

// The sweep's points a choice can be compared with (in the chooser's space).
bool in_budget_space(const BenchPoint& p);

// The criteria for one budget: the choice's measured time within 1.15 B, its RMSE within
// 1.25x the best measured within B.
inline constexpr double kBudgetTimeSlack = 1.15;
inline constexpr double kBudgetRmseSlack = 1.25;
bool time_ok(const BudgetCheckRow& row);
bool rmse_ok(const BudgetCheckRow& row);

// The check on the terminal, as report.md's section (table and plots), and under "budget_check"
// in points.json (what scripts/plot.py draws budget_rmse.png and budget_time.png from).
void print_budget_check(const BenchRun& run);
std::string budget_check_markdown(const BenchRun& run);
nlohmann::ordered_json budget_check_json(const BenchRun& run);

}  // namespace vplkit::cli
