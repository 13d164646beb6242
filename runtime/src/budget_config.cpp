// A budget configuration as words and as settings (budget_config.hpp).

#include "vplkit/budget_config.hpp"

#include "vplkit/error.hpp"

namespace vplkit {

const char* gi_resolution_name(bool half_resolution) {
    return half_resolution ? "half" : "full";
}

std::string describe_budget_config(const BudgetConfig& config) {
    return std::string("method ") + gi_method_name(config.method) + ", spp " + std::to_string(config.spp) +
           ", resolution " + gi_resolution_name(config.half_resolution) + ", denoise " +
           denoise_mode_name(config.denoise) + ", vpls " + std::to_string(config.vpls) + ", block " +
           std::to_string(config.block_size);
}

uint32_t vpl_count_knob(const RenderSettings& settings, VplSource source) {
    switch (source) {
        case VplSource::ir:
            return settings.vpl_paths;
        case VplSource::brsm:
            return settings.brsm.vpl_count;
        case VplSource::smc:
            return settings.smc.budget;
        case VplSource::automatic:
            break;
    }
    throw Error("budget: the VPL source must be resolved (ir, brsm or smc), not automatic");
}

void set_vpl_count_knob(RenderSettings& settings, VplSource source, uint32_t vpls) {
    switch (source) {
        case VplSource::ir:
            settings.vpl_paths = vpls;
            return;
        case VplSource::brsm:
            settings.brsm.vpl_count = vpls;
            return;
        case VplSource::smc:
            settings.smc.budget = vpls;
            return;
        case VplSource::automatic:
            break;
    }
    throw Error("budget: the VPL source must be resolved (ir, brsm or smc), not automatic");
}

RenderSettings apply_budget_config(RenderSettings base, const BudgetConfig& config, VplSource source) {
    base.method = config.method;
    base.samples_per_pixel = config.spp;
    base.half_resolution_gi = config.half_resolution;
    base.denoise = config.denoise;
    base.block_size = config.block_size;
    // The resolved source, so the VPL budget set is the one the frame uses.
    base.vpl_source = source;
    set_vpl_count_knob(base, source, config.vpls);
    return base;
}

}  // namespace vplkit
