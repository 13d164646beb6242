#pragma once
// Plain double-precision references for GI at half resolution: the G-buffer downsample
// (shaders/gi/gbuffer_downsample.comp) and the joint bilateral upsampling
// (shaders/gi/upsample_bilateral.comp), written from the rules in their headers (the thesis
// ch. 6 "Upsampling", eq. 5.3), not from their code.
//
// Where float and double may decide a comparison differently (a normal dot product or a
// distance within a hair of its threshold, two fallback candidates at nearly equal distances),
// the pixel is flagged near_decision and a test leaves it out.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vplkit::reference {

using UpsampleVec3 = std::array<double, 3>;

// The part of a G-buffer texel the upsampler reads.
struct UpsampleTexel {
    bool covered = false;
    UpsampleVec3 position{};
    UpsampleVec3 normal{};  // the shading normal
};

// Row-major `width` x `height` texels of any type.
template <class T>
struct Grid {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<T> texels;
    const T& at(uint32_t x, uint32_t y) const { return texels[std::size_t(y) * width + x]; }
};

// (n + 1) / 2: the half-resolution side.
uint32_t upsample_half_side(uint32_t full);

// Half texel (i, j) = full texel (2i, 2j).
template <class T>
Grid<T> downsample_grid(const Grid<T>& full) {
    Grid<T> half;
    half.width = upsample_half_side(full.width);
    half.height = upsample_half_side(full.height);
    for (uint32_t j = 0; j < half.height; ++j) {
        for (uint32_t i = 0; i < half.width; ++i) half.texels.push_back(full.at(2 * i, 2 * j));
    }
    return half;
}

enum class UpsampleOutcome {
    background,  // the full pixel has no surface: 0
    blended,     // at least one similar sample with a bilinear weight > 0
    fallback,    // none: the nearest covered sample facing the pixel's hemisphere
    empty,       // not even that: 0
};

struct UpsampledPixel {
    UpsampleVec3 radiance{};
    UpsampleOutcome outcome = UpsampleOutcome::background;
    bool near_decision = false;
};

struct UpsampleResult {
    std::vector<UpsampledPixel> pixels;  // row-major, full size
    uint32_t fallback_pixels = 0;
    uint32_t empty_pixels = 0;
};

// L(x) = sum_s b_s S(x, s) L_s / sum_s b_s S(x, s) over the four samples around x (sample i at
// full pixel 2i, clamped at the last one), S = eq. 5.3 (dot of normals > min_cos, distance <
// max_distance), covered samples only; the fallback and empty rules as UpsampleOutcome says.
UpsampleResult upsample_reference(const Grid<UpsampleTexel>& full, const Grid<UpsampleTexel>& half,
                                  const Grid<UpsampleVec3>& half_radiance, double min_cos, double max_distance);

}  // namespace vplkit::reference
