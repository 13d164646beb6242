// The knobs the user fixed beside the budget (budget_fixed.hpp).

#include "vplkit/budget_fixed.hpp"

#include "vplkit/gi_methods.hpp"

namespace vplkit {

std::string describe_budget_fixed(const BudgetFixed& f) {
    std::string text;
    const auto add = [&text](const std::string& part) { text += (text.empty() ? "" : ", ") + part; };
    if (f.method) add(std::string("method ") + gi_method_name(*f.method));
    if (f.spp) add("spp " + std::to_string(*f.spp));
    if (f.half_resolution) add(std::string("resolution ") + gi_resolution_name(*f.half_resolution));
    if (f.denoise) add(std::string("denoise ") + denoise_mode_name(*f.denoise));
    if (f.vpls) add("vpls " + std::to_string(*f.vpls));
    if (f.block_size) add("block " + std::to_string(*f.block_size));
    return text;
}

BudgetSpace narrow_budget_space(BudgetSpace space, const BudgetFixed& f) {
    if (f.method) space.methods = {*f.method};
    if (f.spp) space.spp = {*f.spp};
    if (f.half_resolution) space.half_resolution = {*f.half_resolution};
    if (f.denoise) space.denoise = {*f.denoise};
    if (f.vpls) space.vpls = {*f.vpls};
    if (f.block_size) space.block_sizes = {*f.block_size};
    return space;
}

bool keeps_fixed(const BudgetConfig& c, const BudgetFixed& f) {
    return (!f.method || c.method == *f.method) && (!f.spp || c.spp == *f.spp) &&
           (!f.half_resolution || c.half_resolution == *f.half_resolution) && (!f.denoise || c.denoise == *f.denoise) &&
           (!f.vpls || c.vpls == *f.vpls) &&
           // A method without blocks (sst) builds no cuts: its block size is no knob
           // (budget_candidates gives it the first).
           (!f.block_size || !gi_method(c.method).blocks || c.block_size == *f.block_size);
}

std::vector<BudgetCandidate> candidates_keeping(std::span<const BudgetCandidate> candidates, const BudgetFixed& fixed) {
    std::vector<BudgetCandidate> out;
    for (const BudgetCandidate& c : candidates) {
        if (keeps_fixed(c.config, fixed)) out.push_back(c);
    }
    return out;
}

}  // namespace vplkit
