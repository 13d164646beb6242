#pragma once
// The budget's cost model: each stage's GPU time as a linear function of what the frame asks,
// fitted with slopes >= 0 (budget_fit.hpp) to frames timed on this device (budget_calibration.hpp). The model of
// a stage, by the stage (planner.hpp's FrameStage, by the passes' tags):
//   VPL stages (vpl paths, brsm, smc, flc VPLs, sort, light tree, sst):  c0 + c1 * vpls
//   the sampling stages (gi sst, gi rtslc, gi hybrid, gi exact, gi flc):
//       c0 + c1 * gi_pixels + c2 * gi_pixels * spp + c3 * gi_pixels * spp / block^2
//     (per pixel, per sample, and per cut node of a block: the cuts are built per block)
//   every other stage, and the passes of no stage (tag 0):  c0 + c1 * pixels
// `vpls` is the VPL source's budget (vpl_count_knob), gi_pixels the pixels indirect light is
// computed at (a quarter of them at half resolution). A frame's time is the sum over the stages
// its plan runs, with nothing reused from an earlier frame (the first frame, or a moving camera
// with BRSM): a static camera that reuses its VPLs and trees takes less.

#include "vplkit/planner.hpp"
#include "vplkit/render_settings.hpp"

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace vplkit {

// What a frame's cost depends on.
struct CostPoint {
    double pixels = 0.0;
    double gi_pixels = 0.0;
    double spp = 0.0;
    double block_size = 8.0;
    double vpls = 0.0;
};
// The point of a frame with these settings, whose VPL source resolves to `source`.
CostPoint cost_point(const RenderSettings& settings, VplSource source);

enum class CostFeatures { pixels, vpls, gi_samples };
// The features a stage's time is modelled by; tag 0 (no stage) is `pixels`.
CostFeatures cost_features(uint32_t stage_tag);
// The feature values of `point` for that model, the constant 1 first.
std::vector<double> cost_feature_values(CostFeatures features, const CostPoint& point);

class CostModel {
public:
    // One timed frame: every pass's GPU time, summed by tag, is a sample of its stage's model.
    void add_frame(const std::vector<PassTiming>& timings, const CostPoint& point);
    // One stage's sample (ms) at `point`.
    void add_sample(uint32_t stage_tag, const CostPoint& point, double ms);
    // Fits every stage that has samples (replacing earlier fits).
    void fit();

    bool has_stage(uint32_t stage_tag) const { return coefficients_.count(stage_tag) != 0; }
    // The stage's fitted time at `point`, never below 0 (throws vplkit::Error for a stage not fitted).
    double predict_stage(uint32_t stage_tag, const CostPoint& point) const;
    // A frame with `plan`: the passes of no stage and each stage the plan runs. Nothing when a
    // stage it runs was never timed (a plan the calibration did not cover); `missing` names it.
    std::optional<double> predict_frame(const FramePlan& plan, const CostPoint& point,
                                        std::string* missing = nullptr) const;

    const std::map<uint32_t, std::vector<double>>& coefficients() const { return coefficients_; }
    void set_coefficients(uint32_t stage_tag, std::vector<double> coefficients);

private:
    struct Samples {
        std::vector<double> features;  // row by row
        std::vector<double> ms;
    };
    std::map<uint32_t, Samples> samples_;
    std::map<uint32_t, std::vector<double>> coefficients_;
};

}  // namespace vplkit
