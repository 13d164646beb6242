#pragma once
// The budget's measurements on this device and scene: a calibration renders a few frames per
// method and setting (budget_cost.hpp's samples, budget_error.hpp's noise), fits the cost model,
// and caches both on disk by device, driver, scene, size, camera and the calibration frames'
// plans, so a changed plan (other stages, other settings) or view calibrates again. budget_candidates() then predicts
// every configuration of a space for choose_for_budget (budget_chooser.hpp).

#include "vplkit/budget_chooser.hpp"
#include "vplkit/budget_config.hpp"
#include "vplkit/budget_cost.hpp"
#include "vplkit/budget_error.hpp"
#include "vplkit/device_info.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/render_settings.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace vplkit {

class Renderer;
namespace scene {
struct Scene;
struct Camera;
}  // namespace scene

// The configurations the chooser weighs: every combination (block sizes only for the methods with
// blocks, rtslc and hybrid).
struct BudgetSpace {
    std::vector<GiMethod> methods = gi_methods_with(&GiMethodInfo::budget);  // sst, rtslc, hybrid
    std::vector<uint32_t> spp{1, 2, 4, 8, 16, 32, 64};
    std::vector<bool> half_resolution{false, true};
    std::vector<DenoiseMode> denoise{DenoiseMode::off, DenoiseMode::svgf};
    std::vector<uint32_t> vpls;         // the VPL source's budget (vpl_count_knob)
    std::vector<uint32_t> block_sizes;  // rtslc, hybrid
};
// The default space over `base`: VPL budgets a quarter of, and equal to, the base's; its block size.
BudgetSpace default_budget_space(const RenderSettings& base, VplSource source);
// Throws vplkit::Error naming the first bad entry: an empty list, a method that does not sample
// the VPL trees (only sst, rtslc and hybrid have a noise to measure and an spp to trade), spp
// outside 1..64, block sizes outside 1..32, zero VPLs, the temporal filter alone (not modelled).
void validate_budget_space(const BudgetSpace& space);

struct BudgetModel {
    CostModel cost;
    ErrorModel error;
};

struct BudgetCalibrationOptions {
    std::filesystem::path cache_dir = "out/budget-cache";  // empty: neither read nor written
    std::string scene_id;                                  // names the scene in the cache key (a set-up name, a path)
    uint32_t calibration_spp = 4;                          // spp0 of the noise frames
    uint32_t second_spp = 16;                              // a second spp for the cost per sample
    std::function<void(uint32_t done, uint32_t total)> progress;  // frames rendered of all
};

struct BudgetCalibration {
    BudgetModel model;
    std::string key;  // device, driver, scene, size; a hash of the camera and the calibration frames' plans
    std::filesystem::path cache_file;  // empty without a cache
    bool from_cache = false;
    uint32_t frames = 0;  // frames rendered (0 when read from the cache)
    double wall_ms = 0.0;
};

// Calibrates on `renderer` (whose scene is `scene`) for frames of `base`'s size from `camera`,
// or reads the cache when it holds this key. Renders with nothing reused between frames.
// Throws vplkit::Error for a bad space or a cache file that cannot be written.
BudgetCalibration calibrate_budget(Renderer& renderer, const DeviceInfo& device, const scene::Scene& scene,
                                   const scene::Camera& camera, const RenderSettings& base, const BudgetSpace& space,
                                   const BudgetCalibrationOptions& options);

// Every configuration of `space` the model can predict (its plan's stages were all timed and its
// noise measured, and the settings' check takes it), with its predicted time and error.
std::vector<BudgetCandidate> budget_candidates(const BudgetModel& model, const BudgetSpace& space,
                                               const scene::Scene& scene, const RenderSettings& base);

}  // namespace vplkit
