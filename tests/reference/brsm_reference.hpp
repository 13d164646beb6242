#pragma once
// Plain double-precision references for the BRSM stages (shaders/vpl/brsm_*.comp), written from
// the formulas in vplkit/brsm.glsl and the shaders' headers, not from their code paths.
//
// Where float and double may round a comparison differently (a projected point on a pixel
// edge, a neighbour at exactly d_max), the reference gives an interval [lo, hi] over every way
// the decision could go, and the GPU value must lie in it (within the float tolerance).

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace vplkit::reference {

// PCG32 streams as vplkit/rng.glsl defines them (O'Neill 2014, RXS-M-XS; seeding by pcg_hash).
class Pcg32 {
public:
    Pcg32(uint32_t seed, uint32_t index);
    uint32_t next_uint();
    double next_float();  // the top 24 bits / 2^24, as rng_next_float
private:
    uint32_t state_ = 0;
    uint32_t increment_ = 0;
};
uint32_t pcg_hash(uint32_t v);

// An image read back as RGBA, row-major, `width` x `height`.
struct Rgba {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<glm::vec4> texels;
    const glm::vec4& at(uint32_t x, uint32_t y) const { return texels[size_t(y) * width + x]; }
};

struct Rsm {
    Rgba position, normal, flux;
};

struct Gbuffer {
    Rgba position, normal, geometric_normal, albedo;
};

struct ContributionParams {
    glm::dmat4 camera_view_projection{1.0};
    uint32_t map_size = 0;
    uint32_t sample_count = 0;
    uint32_t seed = 0;
    double core_radius = 0;
    double max_radius = 0;
    double min_distance = 0;  // the VPL falloff clamp
};

struct Interval {
    double lo = 0;
    double hi = 0;
};

// Rec. 709 luminance.
double luminance(const glm::dvec3& rgb);

// Per texel of the map_size^2 map: the mean diffuse contribution (brsm_contribution.comp).
std::vector<Interval> brsm_contribution(const Rsm& rsm, const Gbuffer& gbuffer, const ContributionParams& params);

// Per texel: flux luminance (0 outside the RSM or without a surface).
std::vector<double> brsm_flux_luminance(const Rsm& rsm, uint32_t map_size);

struct FilterParams {
    uint32_t map_size = 0;
    int radius = 0;
    double sigma = 0;
    double min_cos = 0;
    double max_distance = 0;
};

// The edge-aware Gaussian of `contribution` (brsm_filter.comp); texels with an undecidable
// neighbour (distance within 1e-5 relative of max_distance) get the interval over both choices.
std::vector<Interval> brsm_filter(const Rsm& rsm, const std::vector<float>& contribution,
                                  const std::vector<float>& flux_luminance, const FilterParams& params);

// The defensive mixture (brsm_importance.comp), normalized by double sums.
std::vector<double> brsm_importance(const std::vector<float>& filtered, const std::vector<float>& flux_luminance,
                                    double defensive_fraction);

}  // namespace vplkit::reference
