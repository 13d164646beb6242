// Every configuration of a budget space, predicted (budget_calibration.hpp's budget_candidates).

#include "vplkit/budget_calibration.hpp"

#include "vplkit/error.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/planner.hpp"

namespace vplkit {

std::vector<BudgetCandidate> budget_candidates(const BudgetModel& model, const BudgetSpace& space,
                                               const scene::Scene& scene, const RenderSettings& base) {
    validate_budget_space(space);
    const VplSource source = plan_frame(scene, base, "budget").vpl_source;
    std::vector<BudgetCandidate> out;
    for (GiMethod method : space.methods) {
        // A method without blocks (sst) builds no cuts: one block size stands for all.
        const std::vector<uint32_t> blocks =
            gi_method(method).blocks ? space.block_sizes : std::vector<uint32_t>{space.block_sizes.front()};
        for (uint32_t spp : space.spp) {
            for (bool half : space.half_resolution) {
                for (DenoiseMode denoise : space.denoise) {
                    for (uint32_t vpls : space.vpls) {
                        for (uint32_t block : blocks) {
                            const BudgetConfig config{method, spp, half, denoise, vpls, block};
                            const RenderSettings s = apply_budget_config(base, config, source);
                            try {
                                validate_gi_settings(s);  // e.g. rtslc's interleave needs m^2 <= spp
                            } catch (const Error&) {
                                continue;
                            }
                            const auto ms =
                                model.cost.predict_frame(plan_frame(scene, s, "budget"), cost_point(s, source));
                            const auto rmse = model.error.predict_rmse(config);
                            if (ms && rmse) out.push_back({config, *ms, *rmse});
                        }
                    }
                }
            }
        }
    }
    return out;
}

}  // namespace vplkit
