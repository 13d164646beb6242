#pragma once
// CPU reference for tonemap.comp in double precision: exposure, ACES filmic (Narkowicz 2015),
// sRGB transfer function, then the UNORM8 conversion Vulkan specifies (round to nearest).

#include <array>
#include <cstdint>

namespace vplkit::reference {

// Returns the RGBA8 texel for linear radiance `rgb`; non-finite input gives magenta.
std::array<uint8_t, 4> tonemap(const std::array<float, 3>& rgb, double exposure);

// The encoded value before quantization (for tests that need the distance to a rounding border).
double tonemap_channel(double linear, double exposure);

}  // namespace vplkit::reference
