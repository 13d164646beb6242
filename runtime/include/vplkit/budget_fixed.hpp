#pragma once
// What the user fixed beside the budget: a method, an spp, a GI resolution, a denoiser, a VPL
// budget or a block size given explicitly is kept, and the chooser varies only the rest.
// narrow_budget_space replaces the space's list of each fixed knob by the one value (so the
// calibration renders no other), keeps_fixed says whether a configuration holds them all.

#include "vplkit/budget_calibration.hpp"
#include "vplkit/budget_chooser.hpp"
#include "vplkit/budget_config.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace vplkit {

struct BudgetFixed {
    std::optional<GiMethod> method;
    std::optional<uint32_t> spp;
    std::optional<bool> half_resolution;
    std::optional<DenoiseMode> denoise;
    std::optional<uint32_t> vpls;  // the VPL source's budget (vpl_count_knob)
    std::optional<uint32_t> block_size;

    bool any() const { return method || spp || half_resolution || denoise || vpls || block_size; }
};

// "method rtslc, spp 8" (the fixed knobs, in BudgetConfig's order); "" when none is.
std::string describe_budget_fixed(const BudgetFixed& fixed);

// `space` with each fixed knob's list replaced by its value.
BudgetSpace narrow_budget_space(BudgetSpace space, const BudgetFixed& fixed);

bool keeps_fixed(const BudgetConfig& config, const BudgetFixed& fixed);

// The candidates that keep every fixed knob.
std::vector<BudgetCandidate> candidates_keeping(std::span<const BudgetCandidate> candidates, const BudgetFixed& fixed);

}  // namespace vplkit
