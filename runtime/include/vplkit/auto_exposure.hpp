#pragma once
// The automatic exposure (RenderSettings::auto_exposure): a scale for the tone curve taken from
// the frame's own linear radiance.
//
// The 95th percentile of the luminance of the lit pixels (luminance > 0) is scaled to 2.0 before
// the ACES curve (display ~0.96 after the sRGB transfer). A percentile, not the mean-log key of
// Reinhard et al. 2002: in a sun-lit interior (Sponza: the sun patches are ~8% of the view, 100x
// the shadowed stone) the key exposes for the shadows and burns the sun patches to white, while
// the 95th percentile lands in them and keeps them just below white; the brightest 5% (emitters,
// highlights) may compress to white without deciding the exposure, and the black that no
// surface or light reaches is left out so it cannot push the exposure up. 2.0 keeps the default
// Cornell box as exposure 1 showed it (0.99 there).

#include <cstdint>
#include <span>

namespace vplkit {

inline constexpr double kAutoExposurePercentile = 0.95;
inline constexpr double kAutoExposureTarget = 2.0;  // the percentile's value before the tone curve
// The scale is kept within [1/kAutoExposureLimit, kAutoExposureLimit] (a nearly black frame is
// not amplified without end); 1 for a frame with no lit pixel.
inline constexpr double kAutoExposureLimit = 65536.0;

struct AutoExposure {
    float exposure = 1.0f;       // the scale the tone curve is given
    float key_luminance = 0.0f;  // the percentile's luminance (0: no lit pixel)
};

// `rgb`: linear RGB, 3 floats per pixel. Non-finite pixels are left out.
AutoExposure auto_exposure(std::span<const float> rgb);

}  // namespace vplkit
