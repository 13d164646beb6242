#pragma once
// GI at half resolution (the thesis ch. 6, "Upsampling", and 7.4): the G-buffer is downsampled to
// half size (shaders/gi/gbuffer_downsample.comp), indirect light is shaded on that half
// G-buffer by any GI stage, and joint bilateral upsampling (shaders/gi/upsample_bilateral.comp)
// brings it back to full size: bilinear weights times the geometric similarity of eq. 5.3, so
// light does not bleed across creases or depth jumps.
//
//   half: a G-buffer of half_resolution(w) x half_resolution(h) (the runtime: GbufferImages::create)
//   add_gbuffer_downsample_pass(device, passes, gbuffer, half);
//   ... GI stage on `half` into half_indirect (RGBA32F, half size) ...
//   add_upsample_passes(device, passes, gbuffer, half, half_indirect, indirect, counters,
//                     upsample_options_for_scene(bvh.scene_scale));

#include "vplkit/stages/device.hpp"
#include "vplkit/stages/gbuffer_views.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <cstdint>

namespace vplkit::stages {

// The half-resolution size of a full-resolution side: (full + 1) / 2, so half pixel i copies
// full pixel 2i and the last full column or row (odd sizes) still has a sample on it.
uint32_t half_resolution(uint32_t full);

// Adds "gbuffer downsample": half pixel (i, j) = full pixel (2i, 2j) of position, normal,
// geometric normal, albedo and emission (a copy, so positions stay on real surfaces and normals
// unit; half.depth is not written; the half images need storage usage). Throws vplkit::Error
// unless half is half_resolution(full's width) x half_resolution(full's height).
void add_gbuffer_downsample_pass(Device& device, StepList& passes, const GbufferViews& full, const GbufferViews& half);

struct UpsampleOptions {
    // Eq. 5.3's n_min: a sample is similar when the dot product of its shading normal with the
    // pixel's is above this, in [-1, 1) (at 1 no pair passes and every pixel falls back). 0.9
    // splits surfaces at creases of ~25 degrees, as the BRSM filter's default does.
    float min_cos = 0.9f;
    // Eq. 5.3's d_max, in world units (absolute, > 0): a sample farther from the pixel is on
    // another surface. No default fits every scene, so it must be set: the caller passes a
    // scene-relative value, e.g. upsample_options_for_scene(bvh.scene_scale). It must exceed the
    // world distance between neighbouring half-resolution samples on one surface (two full
    // pixels' footprint, more at grazing angles), or smooth surfaces fall back to nearest.
    float max_distance = 0.0f;
};

// The fraction of the scene scale upsample_options_for_scene uses for max_distance (the BRSM
// filter's similarity_max_distance default).
inline constexpr float kUpsampleMaxDistanceFraction = 0.02f;

// min_cos 0.9 and max_distance kUpsampleMaxDistanceFraction x scene_scale (GpuBvh::scene_scale).
// Throws vplkit::Error for a scene_scale that is not a positive finite number.
UpsampleOptions upsample_options_for_scene(float scene_scale);

// Bytes of the counters buffer: one UpsampleCounters record (two uint32; upsample.cpp checks it
// against the generated struct). The runtime's create_upsample_counters
// (vplkit/upsample_counters.hpp) allocates it.
inline constexpr uint64_t kUpsampleCountersBytes = 2 * sizeof(uint32_t);

// The counters upsample_bilateral.comp increments (UpsampleCounters).
struct UpsampleCounts {
    // Covered pixels that no sample was similar to: they took the nearest covered sample whose
    // normal faces their hemisphere (a guess; many of them mean max_distance is too small).
    uint32_t fallback_pixels = 0;
    // Covered pixels without even such a sample: left 0.
    uint32_t empty_pixels = 0;
};

// Adds "upsample clear" (zeroes `counters`) and "upsample": full_indirect (RGBA32F, full's size,
// storage usage) from half_indirect (RGBA32F, half's size): for each covered full pixel the
// four half samples around it, bilinear weights times eq. 5.3's similarity, normalized; when
// every weight is 0 the nearest facing sample (counted in fallback_pixels), or 0 (counted in
// empty_pixels). Background pixels get 0; alpha is 0 everywhere. `half` is the G-buffer
// half_indirect was shaded on (add_gbuffer_downsample_pass's output). `counters` holds
// kUpsampleCountersBytes. Throws vplkit::Error for bad options (not finite, min_cos outside
// [-1, 1), max_distance not > 0), a half G-buffer that is not half of full, an image of the
// wrong format or size, naming it, or a counters buffer too small.
void add_upsample_passes(Device& device, StepList& passes, const GbufferViews& full, const GbufferViews& half,
                         const ImageView& half_indirect, const ImageView& full_indirect, const BufferView& counters,
                         const UpsampleOptions& options);

}  // namespace vplkit::stages
