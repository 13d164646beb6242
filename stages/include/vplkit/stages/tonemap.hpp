#pragma once
// Display output (tonemap.comp): exposure, ACES filmic curve, sRGB encoding into an RGBA8 image;
// non-finite pixels become magenta and are counted.

#include "vplkit/stages/device.hpp"
#include "vplkit/steps.hpp"
#include "vplkit/views.hpp"

#include <cstdint>

namespace vplkit::stages {

// Bytes of the stats buffer: one uint32 count of non-finite pixels.
inline constexpr uint32_t kTonemapStatsBytes = 4;

// Adds "tonemap stats clear" and "tonemap". `hdr` (read) is RGBA32F with storage usage, `ldr`
// (written) is RGBA8_UNORM with storage usage and the same size, both used in GENERAL layout;
// `stats` (cleared, then written; kTonemapStatsBytes from its offset) gets the non-finite pixel count.
void add_tonemap_passes(Device& device, StepList& passes, const ImageView& hdr, const ImageView& ldr,
                        const BufferView& stats, float exposure);

}  // namespace vplkit::stages
