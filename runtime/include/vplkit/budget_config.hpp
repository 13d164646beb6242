#pragma once
// One configuration the budget chooser weighs (budget_chooser.hpp): the indirect-light method and
// the knobs that trade its error for time, and the settings of a frame with it.

#include "vplkit/render_settings.hpp"

#include <cstdint>
#include <string>

namespace vplkit {

struct BudgetConfig {
    GiMethod method = GiMethod::hybrid;  // sst, rtslc or hybrid
    uint32_t spp = 8;                    // samples_per_pixel
    bool half_resolution = false;        // half_resolution_gi
    DenoiseMode denoise = DenoiseMode::off;
    uint32_t vpls = 4096;  // the VPL source's budget (vpl_count_knob)
    uint32_t block_size = 8;
};

// "full" or "half".
const char* gi_resolution_name(bool half_resolution);

// "method hybrid, spp 8, resolution half, denoise svgf, vpls 4096, block 8".
std::string describe_budget_config(const BudgetConfig& config);

// The VPL source's budget in `settings`: `vpl_paths` for ir (light paths; the VPLs are a few per
// path), `brsm.vpl_count` for brsm, `smc.budget` for smc. `source` is resolved (not automatic).
uint32_t vpl_count_knob(const RenderSettings& settings, VplSource source);
void set_vpl_count_knob(RenderSettings& settings, VplSource source, uint32_t vpls);

// `base` with the configuration's method, spp, resolution, denoiser, VPL budget and block size.
RenderSettings apply_budget_config(RenderSettings base, const BudgetConfig& config, VplSource source);

}  // namespace vplkit
