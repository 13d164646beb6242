#include "vplkit/stages/svgf.hpp"

#include "vplkit/error.hpp"

#include <string>

namespace vplkit::stages {

void add_svgf_passes(Device& device, StepList& passes, const GbufferViews& gbuffer, const ImageView& radiance,
                     std::span<const ImageView> images, const SvgfFrame& frame, const DenoiseOptions& options) {
    if (images.size() != kSvgfImageCount) {
        throw Error("svgf: " + std::to_string(images.size()) + " images given, the chain works in " +
                    std::to_string(kSvgfImageCount));
    }
    validate(options);
    const ImageView &irradiance = images[0], &accumulated_image = images[1], &clamped = images[2], &excess = images[3],
                    &spread = images[4], &estimated = images[5], &ping = images[6], &pong = images[7];
    const DenoiseHistory halves[2] = {{images[8], images[9], images[10], images[11]},
                                      {images[12], images[13], images[14], images[15]}};
    const DenoiseHistory& next = halves[frame.index % 2];
    const DenoiseHistory& previous = halves[(frame.index + 1) % 2];

    add_demodulate_pass(device, passes, radiance, gbuffer.albedo, gbuffer.position, irradiance, options);
    // SVGF's history is the first a-trous iteration's output, so a static view goes through the
    // filter once more every frame: the cap on its history stays. Temporal accumulation alone
    // (history = the running mean itself) keeps options.static_max_history.
    const bool spatial = options.atrous_iterations > 0;
    DenoiseOptions temporal_options = options;
    if (spatial) temporal_options.static_max_history = options.max_history;
    const ImageView& accumulated = spatial ? accumulated_image : next.color;
    add_temporal_accumulate_pass(device, passes, irradiance, gbuffer.position, gbuffer.normal, previous, next,
                                 accumulated, next.moments, frame.previous_view_projection, frame.index > 0,
                                 temporal_options, gbuffer.motion);
    // The clamp shapes what is filtered and shown; the history keeps the unclamped mean.
    ImageView result = accumulated;
    if (options.firefly_k_sigma > 0.0f) {
        add_firefly_clamp_passes(device, passes, accumulated, next.moments, gbuffer.albedo, gbuffer.position, clamped,
                                 excess, spread, options);
        result = spread;
    }
    if (spatial) {
        add_variance_estimate_pass(device, passes, result, next.moments, gbuffer.position, gbuffer.normal, estimated,
                                   options);
        result = estimated;
        // The demodulated frame and the accumulated image are read by nothing after the variance
        // estimate: the a-trous iterations work in them.
        const AtrousScratch scratch{irradiance, accumulated_image};
        for (uint32_t i = 0; i < options.atrous_iterations; ++i) {
            const ImageView& target = i == 0 ? next.color : (i % 2 == 1 ? ping : pong);
            add_atrous_passes(device, passes, result, gbuffer.position, gbuffer.normal, scratch, target, 1 << i,
                              options);
            result = target;
        }
    }
    add_remodulate_pass(device, passes, result, gbuffer.albedo, radiance, options);
}

}  // namespace vplkit::stages
