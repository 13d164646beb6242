// The error model's sum of noise, bias and the denoiser's effect (budget_error.hpp).

#include "vplkit/budget_error.hpp"

#include "vplkit/budget_noise.hpp"

#include <cmath>

namespace vplkit {

double method_bias_floor(GiMethod method) {
    switch (method) {
        case GiMethod::sst:
            return kSstBiasFloor;
        case GiMethod::hybrid:
            return kHybridBiasFloor;
        default:
            return 0.0;
    }
}

const NoiseMeasurement* ErrorModel::find(GiMethod method, bool half_resolution, uint32_t block_size) const {
    for (const NoiseMeasurement& m : sampling) {
        // sst builds no cuts: its noise does not depend on the block size.
        const bool block_matches = m.block_size == block_size || method == GiMethod::sst;
        if (m.method == method && m.half_resolution == half_resolution && block_matches) return &m;
    }
    return nullptr;
}

std::optional<double> ErrorModel::predict_rmse(const BudgetConfig& config) const {
    const NoiseMeasurement* noise = find(config.method, config.half_resolution, config.block_size);
    // temporal alone: its effect depends on how long the camera stays still; not modelled.
    if (!noise || config.denoise == DenoiseMode::temporal) return std::nullopt;
    // 1/spp from spp0, not the measured exponent: extrapolated to 64 spp the exponent overrated
    // the raw frames' noise and the chooser took svgf at 64 spp with 1.5x the best measured
    // RMSE (docs/budget.md); the exponent is kept as a measurement of how far 1/spp is off.
    double sampling_mse = variance_at_samples(noise->variance, noise->spp, config.spp);
    // The denoiser filters each frame's new samples; the VPL set stays the same from frame to
    // frame, so its error is not averaged away (its blotches are larger than the a-trous kernel's
    // edge-stopped reach, assumed untouched).
    if (config.denoise == DenoiseMode::svgf) {
        sampling_mse = kSvgfBlurFloor * kSvgfBlurFloor + kSvgfNoiseShare * sampling_mse;
    }
    double vpl_mse = 0.0;
    if (vpl_measured > 0 && config.vpls > 0) {
        vpl_mse = vpl_variance * double(vpl_measured) / double(config.vpls);
    }
    double bias = method_bias_floor(config.method);
    double bias_mse = bias * bias;
    if (config.half_resolution) bias_mse += kHalfResolutionBiasFloor * kHalfResolutionBiasFloor;
    return std::sqrt(sampling_mse + vpl_mse + bias_mse);
}

}  // namespace vplkit
