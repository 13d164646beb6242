#pragma once
// Display output (tonemap.comp): exposure, ACES filmic curve, sRGB encoding into an RGBA8 image;
// non-finite pixels become magenta and are counted.

#include <cstdint>

namespace vplkit {
class Buffer;
class Context;
class Image;
class PassList;
}  // namespace vplkit

namespace vplkit::stages {

// Bytes of the stats buffer: one uint32 count of non-finite pixels.
inline constexpr uint32_t kTonemapStatsBytes = 4;

// Adds "tonemap stats clear" and "tonemap". `hdr` is RGBA32F with storage usage, `ldr` is
// RGBA8_UNORM with storage usage and the same size; `stats` gets the non-finite pixel count.
void add_tonemap_passes(Context& context, PassList& passes, Image& hdr, Image& ldr, Buffer& stats, float exposure);

}  // namespace vplkit::stages
