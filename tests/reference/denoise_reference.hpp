#pragma once
// CPU reference for the denoising passes (shaders/denoise/), in double, written from the passes'
// definitions (SVGF, Schied et al. 2017; vplkit/denoise.glsl), not from the shaders' code paths:
// images are row-major vectors of RGBA texels of one width x height.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vplkit::reference {

using Texel4 = std::array<double, 4>;

struct DenoiseImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<Texel4> texels;

    DenoiseImage() = default;
    DenoiseImage(uint32_t w, uint32_t h) : width(w), height(h), texels(std::size_t(w) * h, Texel4{}) {}
    Texel4& at(int x, int y) { return texels[std::size_t(y) * width + x]; }
    const Texel4& at(int x, int y) const { return texels[std::size_t(y) * width + x]; }
    bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < int(width) && y < int(height); }
};

double luminance(const Texel4& c);

// The G-buffer of one frame as the passes read it: position (xyz, w = 1 covered) and normal.
struct DenoiseGeometry {
    DenoiseImage position;
    DenoiseImage normal;
    bool covered(int x, int y) const { return position.inside(x, y) && position.at(x, y)[3] > 0.5; }
};

DenoiseImage demodulate(const DenoiseImage& radiance, const DenoiseImage& albedo, const DenoiseImage& position,
                        double albedo_floor);
DenoiseImage remodulate(const DenoiseImage& irradiance, const DenoiseImage& albedo, double albedo_floor);

// The energy-conserving firefly clamp: a covered pixel with at least 4 covered 5 x 5 neighbours
// (itself left out) whose luminance is above their mean + k sigma is scaled to that limit, and
// the radiance taken off (irradiance x the albedo divisor) is shared equally among those
// neighbours, each dividing its share by its own divisor.
struct FireflyResult {
    DenoiseImage clamped;  // rgb scaled to the limit, a = the input's a
    DenoiseImage excess;   // rgb = the radiance taken off / the neighbour count, a = the luminance taken off
    DenoiseImage spread;   // rgb = clamped + the neighbours' shares / divisor, a = the input's a
};
// moments: m1, m2, n per pixel; where n >= min_history the limit is at least the pixel's
// luminance less k_sigma x sqrt((m2 - m1^2) / n) (its mean's standard error).
FireflyResult firefly_clamp(const DenoiseImage& irradiance, const DenoiseImage& moments, const DenoiseImage& albedo,
                            const DenoiseImage& position, double k_sigma, double albedo_floor, uint32_t min_history);

struct TemporalResult {
    DenoiseImage accumulated;  // rgb, a = variance
    DenoiseImage moments;      // m1, m2, n, 0
};

struct TemporalParameters {
    std::array<double, 16> previous_view_projection{};  // column-major, world -> clip
    double max_plane_distance = 0.0;
    double min_normal_cos = 0.9;
    uint32_t max_history = 32;
    bool has_history = false;
    // A pixel whose point reprojects within static_pixels of its own centre (per axis) reads that
    // pixel alone and is capped by static_max_history (0: no cap).
    uint32_t static_max_history = 0;
    double static_pixels = 0.01;
};

// The previous frame's continuous pixel coordinates of world point p (pixel centres at
// integers), false when p is behind the previous camera.
bool reproject(const std::array<double, 16>& view_projection, const std::array<double, 3>& p, uint32_t width,
               uint32_t height, double& x, double& y);

TemporalResult temporal_accumulate(const DenoiseImage& irradiance, const DenoiseGeometry& current,
                                   const DenoiseGeometry& previous, const DenoiseImage& previous_color,
                                   const DenoiseImage& previous_moments, const TemporalParameters& parameters);

struct FilterParameters {
    double sigma_plane = 0.01;
    double sigma_normal = 128.0;
    double sigma_luminance = 4.0;
    uint32_t min_history = 4;
};

DenoiseImage variance_estimate(const DenoiseImage& accumulated, const DenoiseImage& moments,
                               const DenoiseGeometry& geometry, const FilterParameters& parameters);

DenoiseImage atrous(const DenoiseImage& source, const DenoiseGeometry& geometry, int step,
                    const FilterParameters& parameters);

}  // namespace vplkit::reference
