#pragma once
// The budget's error model: a configuration's predicted RMSE of the tonemapped frame (sRGB / 255,
// the bench's metric) against the exact frame, without rendering the exact frame. Its squared
// error is the sum of
//   sampling noise:  sigma_s^2(method, resolution, block) x spp0 / spp, measured from two
//                    frames of this scene with other random numbers (budget_noise.hpp) at spp0
//                    (two more at spp1 measure how far from 1/spp it falls: `exponent`);
//   the VPL budget:  the error a budget V below the settings' V0 adds against the frame over V0's
//                    VPLs, measured at the space's smallest budget (two pairs of frames at 64 spp,
//                    low-passed: vpl_set_variance), in proportion to V0 / V - 1 between;
//   bias:            the method's floor (sst, hybrid: their substitutes) and half resolution's
//                    (the upsampling), squared, from the bench's tables (docs/budget.md);
// and svgf replaces sampling noise n^2 by F^2 + r n^2 (the filter's blur floor F and the share r
// of the noise it keeps, measured on this scene from filtered calibration frames: svgf_effect()).
// docs/budget.md says where it is wrong.

#include "vplkit/budget_config.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace vplkit {

// Bias floors, RMSE of tonemapped frames beyond rtslc's (which is unbiased), the median over the
// bench's three scenes at 320x180 (docs/measurements.md, "the four methods against exact":
// e^2 = b^2 + c / spp fitted to 8 and 32 spp; docs/budget.md has the per-scene values).
inline constexpr double kSstBiasFloor = 0.025;
inline constexpr double kHybridBiasFloor = 0.016;
inline constexpr double kHalfResolutionBiasFloor = 0.017;
// svgf over 3 frames (as the bench runs it): fitted to sst, rtslc and hybrid at 2, 8 and 32 spp,
// raw and filtered, against exact in the Cornell box at 160x90 (docs/budget.md), within 0.001 RMSE.
// Used only where the calibration measured no svgf frames (a space without svgf).
inline constexpr double kSvgfBlurFloor = 0.023;
inline constexpr double kSvgfNoiseShare = 0.081;

// svgf's effect on this scene: its filtered frame's error is F^2 + r n^2 where the raw frame's is n^2.
struct SvgfEffect {
    double floor_variance = kSvgfBlurFloor * kSvgfBlurFloor;  // F^2, per value
    double noise_share = kSvgfNoiseShare;                     // r
};

// svgf's effect through two measurements, at spp0 and a higher spp1, all per value on one scale:
// the raw frames' sampling noise n^2 (their half-difference) and the filtered frame's error e
// against the converged frame (its half-differences from two frames at many more spp with the
// same VPLs, less theirs from each other). e = F^2 + r n^2 through both points: r = (e0 - e1) /
// (n0^2 - n1^2) within [0, 1], F^2 = e1 - r n1^2 not below 0. Nothing when n0^2 <= n1^2.
std::optional<SvgfEffect> svgf_effect(double raw_noise0, double filtered_error0, double raw_noise1,
                                      double filtered_error1);

// The method's bias floor (the method table's: 0 for rtslc, the constants above for sst and hybrid).
double method_bias_floor(GiMethod method);

// Sampling noise measured for one method, resolution and block size.
struct NoiseMeasurement {
    GiMethod method = GiMethod::hybrid;
    bool half_resolution = false;
    uint32_t block_size = 8;
    uint32_t spp = 4;       // spp0
    double variance = 0.0;  // sigma_s^2 per value at spp0
    // a: sigma_s^2 fell as spp^-a from spp0 to spp1 (spp_exponent of the two pairs). Measured and
    // cached, not used by predict_rmse (docs/budget.md: extrapolated, it chose worse).
    double exponent = 1.0;
    // svgf's effect on this method's frames (measured at one resolution; the other's takes it).
    std::optional<SvgfEffect> svgf;
};

struct ErrorModel {
    std::vector<NoiseMeasurement> sampling;
    // The VPL budget's error against the frame over the settings' budget V0 (the bench's exact frame
    // is over those VPLs): measured at V_small, e^2 (V0 / V - 1) / (V0 / V_small - 1) at V < V0.
    uint32_t vpl_measured = 0;   // V0 (vpl_count_knob)
    uint32_t vpl_small = 0;      // V_small
    double vpl_small_mse = 0.0;  // e^2 at V_small

    // svgf's effect for a configuration: its method's measured one, else the Cornell constants.
    SvgfEffect svgf_for(const BudgetConfig& config) const;

    const NoiseMeasurement* find(GiMethod method, bool half_resolution, uint32_t block_size) const;
    // The predicted RMSE; nothing when its sampling noise was not measured, or for the temporal
    // filter alone (not modelled).
    std::optional<double> predict_rmse(const BudgetConfig& config) const;
};

}  // namespace vplkit
