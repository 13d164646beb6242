#pragma once
// Denoising indirect light (shaders/denoise/): SVGF's shape (Schied et al. 2017) as separate
// passes a renderer can take one by one. A frame, with the runtime's Denoiser doing the
// bookkeeping (vplkit/denoiser.hpp):
//
//   add_demodulate_pass(...)            radiance / albedo -> irradiance (before any upsampling)
//   ... upsample the irradiance to full size if GI ran at half ...
//   add_temporal_accumulate_pass(...)   reprojected history, running mean, moments -> variance
//   add_firefly_clamp_passes(...)         on the accumulated image (the history keeps the unclamped
//                                       mean): luminance above the neighbours' mean + k sigma
//                                       spread over them
//   add_variance_estimate_pass(...)     spatial variance where the history is short
//   add_atrous_passes(..., step 1, 2, 4, 8, ...)   the first iteration's output is the next history;
//                                       symmetric, mass-preserving weights: the light is kept
//   add_remodulate_pass(...)            irradiance x albedo -> radiance, then compose as before
//
// Every image is RGBA32F except the albedo (the G-buffer's RGBA16F), all of one size, storage
// usage, GENERAL layout. Errors: vplkit::Error naming the image or option.

#include "vplkit/stages/device.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <glm/mat4x4.hpp>

#include <cstdint>

namespace vplkit::stages {

struct DenoiseOptions {
    // Demodulation divides each channel by max(albedo, albedo_floor) and remodulation multiplies
    // by the same (vplkit/denoise.glsl): a channel darker than the floor gets back at most
    // albedo_floor x its neighbours' irradiance, and light not proportional to the albedo is
    // amplified by at most 1 / albedo_floor. 0.04 is the glTF BRDF's specular reflectance at
    // normal incidence for dielectrics (F0): no channel of such a surface reflects less than
    // that, so its specular light is never divided by less than the reflectance it came from.
    // Must be > 0.
    float albedo_floor = 0.04f;
    // Firefly clamp: the limit is the neighbours' mean + firefly_k_sigma standard deviations; the
    // light above it is spread over those neighbours, not dropped (the frame's sum is kept). 0
    // turns the pass off in the runtime.
    float firefly_k_sigma = 4.0f;
    // History length cap: alpha = 1 / min(n, max_history) (a running mean for max_history frames,
    // then an exponential moving average).
    uint32_t max_history = 32;
    // The cap where a pixel reprojects onto itself (a static camera); 0: no cap, an exact running
    // mean that converges to the frames' mean.
    uint32_t static_max_history = 0;
    // The scene's size (GpuBvh::scene_scale): the lengths below are shares of it.
    float scene_scale = 1.0f;
    // Reprojection: a history tap farther than this share of scene_scale from the pixel's tangent
    // plane, or with normals below min_normal_cos, is another surface.
    float max_plane_distance_fraction = 0.01f;
    float min_normal_cos = 0.9f;
    // A-trous edge weights (SVGF's sigma_z, sigma_n, sigma_l; the plane one as a share of
    // scene_scale, see vplkit/denoise.glsl).
    float sigma_plane_fraction = 0.005f;
    float sigma_normal = 128.0f;
    float sigma_luminance = 4.0f;
    uint32_t atrous_iterations = 5;
    // Below this history length the a-trous filter's variance is estimated spatially (SVGF: 4).
    uint32_t min_temporal_history = 4;
};

// Throws vplkit::Error naming the first option that is out of range (not finite, negative, a
// cap of 0, more than 10 a-trous iterations).
void validate(const DenoiseOptions& options);

// One frame's history as temporal_accumulate.comp reads (previous) or writes (next) it.
struct DenoiseHistory {
    ImageView position;  // the G-buffer's position of that frame
    ImageView normal;    // its shading normal
    ImageView color;     // filtered irradiance (rgb), a: variance
    ImageView moments;   // m1, m2 of luminance, n (history length), 0
};

// "denoise demodulate": irradiance = radiance / albedo (rule in vplkit/denoise.glsl), 0 on the
// background (position.w = 0).
void add_demodulate_pass(Device& device, StepList& passes, const ImageView& radiance, const ImageView& albedo,
                         const ImageView& position, const ImageView& irradiance, const DenoiseOptions& options);

// "denoise remodulate": radiance = irradiance x albedo.
void add_remodulate_pass(Device& device, StepList& passes, const ImageView& irradiance, const ImageView& albedo,
                         const ImageView& radiance, const DenoiseOptions& options);

// "denoise firefly clamp" + "denoise firefly spread": a pixel's luminance above its 5 x 5
// neighbours' (covered, itself left out) mean + k sigma is taken off it and handed to those
// neighbours in equal shares of radiance (irradiance x the albedo divisor of vplkit/denoise.glsl),
// so the remodulated image keeps its light. clamped: rgb scaled to the limit, a = the input's a;
// excess: rgb = the radiance taken off over the neighbour count, a = the luminance taken off;
// spread: rgb = clamped + the shares gathered over the pixel's own divisor (the pass's result),
// a = the input's a. `moments` (m1, m2, n: the temporal pass's): where n >= min_temporal_history
// the pixel is pulled down by at most k_sigma standard errors of its own mean,
// sqrt((m2 - m1^2) / n), so the clamp fades as the mean converges.
void add_firefly_clamp_passes(Device& device, StepList& passes, const ImageView& irradiance, const ImageView& moments,
                              const ImageView& albedo, const ImageView& position, const ImageView& clamped,
                              const ImageView& excess, const ImageView& spread, const DenoiseOptions& options);

// "denoise temporal": accumulated (rgb, a = variance) and moments (m1, m2, n) from `irradiance`
// and the `previous` history reprojected with previous_view_projection; writes this frame's
// position and normal into next.position / next.normal (next.color and next.moments are not
// touched: the caller points `accumulated` / `moments` at them, or at the a-trous input).
// has_history false: every pixel starts over (n = 1), the previous images are not read. A pixel
// that reprojects onto its own centre reads that one pixel and is capped by static_max_history.
// `motion` (the G-buffer's, gbuffer_views.hpp; optional): each pixel is looked up where its point
// was (position + motion) and its history taps tested against that previous position, so a
// moving object keeps its own history and what it uncovers starts over; empty: nothing moved.
void add_temporal_accumulate_pass(Device& device, StepList& passes, const ImageView& irradiance,
                                  const ImageView& position, const ImageView& normal, const DenoiseHistory& previous,
                                  const DenoiseHistory& next, const ImageView& accumulated, const ImageView& moments,
                                  const glm::mat4& previous_view_projection, bool has_history,
                                  const DenoiseOptions& options, const ImageView& motion = {});

// "denoise variance": estimated = accumulated, with a = the 7 x 7 spatial variance where
// moments' n < min_temporal_history.
void add_variance_estimate_pass(Device& device, StepList& passes, const ImageView& accumulated,
                                const ImageView& moments, const ImageView& position, const ImageView& normal,
                                const ImageView& estimated, const DenoiseOptions& options);

// Two images an a-trous iteration works in besides its source and output (RGBA32F, their size):
// the blurred variance, then it with each pixel's weight sum. Nothing is kept in them after it.
struct AtrousScratch {
    ImageView variance;
    ImageView weights;
};

// One a-trous iteration with taps `step` pixels apart (step >= 1), three passes: "denoise a-trous
// variance <step>", "denoise a-trous weights <step>", "denoise a-trous <step>". Its weights are
// symmetric and normalized so that the filter keeps both a constant image and the image's sum
// (atrous.comp). `scratch`'s images must differ from `source` and `filtered`.
void add_atrous_passes(Device& device, StepList& passes, const ImageView& source, const ImageView& position,
                       const ImageView& normal, const AtrousScratch& scratch, const ImageView& filtered, int step,
                       const DenoiseOptions& options);

}  // namespace vplkit::stages
