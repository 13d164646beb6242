// The per-stage linear cost model (budget_cost.hpp).

#include "vplkit/budget_cost.hpp"

#include "vplkit/budget_config.hpp"
#include "vplkit/budget_fit.hpp"
#include "vplkit/error.hpp"

#include <algorithm>

namespace vplkit {

CostPoint cost_point(const RenderSettings& settings, VplSource source) {
    CostPoint p;
    p.pixels = double(settings.width) * double(settings.height);
    // Half resolution: every second pixel each way, rounded up.
    p.gi_pixels =
        settings.half_resolution_gi ? double((settings.width + 1) / 2) * double((settings.height + 1) / 2) : p.pixels;
    p.spp = double(settings.samples_per_pixel);
    p.block_size = double(settings.block_size);
    p.vpls = double(vpl_count_knob(settings, source));
    return p;
}

CostFeatures cost_features(uint32_t tag) {
    if (tag == 0) return CostFeatures::pixels;
    switch (FrameStage(tag - 1)) {
        case FrameStage::vpl_paths:
        case FrameStage::brsm_vpls:
        case FrameStage::smc_vpls:
        case FrameStage::flc_vpls:
        case FrameStage::vpl_sort:
        case FrameStage::light_tree:
        case FrameStage::sst:
            return CostFeatures::vpls;
        case FrameStage::gi_exact:
        case FrameStage::gi_sst:
        case FrameStage::gi_rtslc:
        case FrameStage::gi_hybrid:
        case FrameStage::gi_flc:
            return CostFeatures::gi_samples;
        default:
            return CostFeatures::pixels;
    }
}

std::vector<double> cost_feature_values(CostFeatures features, const CostPoint& p) {
    switch (features) {
        case CostFeatures::pixels:
            return {1.0, p.pixels};
        case CostFeatures::vpls:
            return {1.0, p.vpls};
        case CostFeatures::gi_samples: {
            const double samples = p.gi_pixels * p.spp;
            return {1.0, p.gi_pixels, samples, samples / (p.block_size * p.block_size)};
        }
    }
    return {1.0};
}

void CostModel::add_frame(const std::vector<PassTiming>& timings, const CostPoint& point) {
    std::map<uint32_t, double> by_tag;
    for (const PassTiming& t : timings) by_tag[t.tag] += t.gpu_ms;
    for (const auto& [tag, ms] : by_tag) add_sample(tag, point, ms);
}

void CostModel::add_sample(uint32_t tag, const CostPoint& point, double ms) {
    Samples& s = samples_[tag];
    const std::vector<double> f = cost_feature_values(cost_features(tag), point);
    s.features.insert(s.features.end(), f.begin(), f.end());
    s.ms.push_back(ms);
}

void CostModel::fit() {
    for (const auto& [tag, s] : samples_) {
        const size_t n = cost_feature_values(cost_features(tag), CostPoint{}).size();
        coefficients_[tag] = fit_linear_nonnegative_slopes(s.features, n, s.ms);
    }
}

void CostModel::set_coefficients(uint32_t tag, std::vector<double> coefficients) {
    const size_t n = cost_feature_values(cost_features(tag), CostPoint{}).size();
    if (coefficients.size() != n) {
        throw Error("budget cost model: stage tag " + std::to_string(tag) + " takes " + std::to_string(n) +
                    " coefficients, not " + std::to_string(coefficients.size()));
    }
    coefficients_[tag] = std::move(coefficients);
}

double CostModel::predict_stage(uint32_t tag, const CostPoint& point) const {
    auto it = coefficients_.find(tag);
    if (it == coefficients_.end()) throw Error("budget cost model: stage tag " + std::to_string(tag) + " not fitted");
    const std::vector<double> f = cost_feature_values(cost_features(tag), point);
    double ms = 0.0;
    for (size_t i = 0; i < f.size(); ++i) ms += it->second[i] * f[i];
    return std::max(ms, 0.0);
}

std::optional<double> CostModel::predict_frame(const FramePlan& plan, const CostPoint& point,
                                               std::string* missing) const {
    double ms = has_stage(0) ? predict_stage(0, point) : 0.0;
    for (const PlannedStage& s : plan.stages) {
        if (!s.runs) continue;
        const uint32_t tag = stage_tag(s.stage);
        if (!has_stage(tag)) {
            if (missing) *missing = stage_name(s.stage);
            return std::nullopt;
        }
        ms += predict_stage(tag, point);
    }
    return ms;
}

}  // namespace vplkit
