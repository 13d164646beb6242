#include "upsample_reference.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vplkit::reference {

namespace {

double dot(const UpsampleVec3& a, const UpsampleVec3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double distance(const UpsampleVec3& a, const UpsampleVec3& b) {
    const UpsampleVec3 d{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return std::sqrt(dot(d, d));
}

// Float rounds a dot product of unit vectors, or a distance, by a few 1e-7 relative; 1e-5 is a
// wide margin around that.
constexpr double kDecisionMargin = 1e-5;

bool near(double value, double threshold) {
    return std::abs(value - threshold) <= kDecisionMargin * std::max(1.0, std::abs(threshold));
}

struct Tap {
    uint32_t x = 0, y = 0;
    double bilinear = 0.0;
};

}  // namespace

uint32_t upsample_half_side(uint32_t full) {
    return uint32_t((uint64_t(full) + 1) / 2);
}

UpsampleResult upsample_reference(const Grid<UpsampleTexel>& full, const Grid<UpsampleTexel>& half,
                                  const Grid<UpsampleVec3>& half_radiance, double min_cos, double max_distance) {
    if (half.width != upsample_half_side(full.width) || half.height != upsample_half_side(full.height) ||
        half_radiance.width != half.width || half_radiance.height != half.height) {
        throw std::invalid_argument("upsample_reference: sizes do not match");
    }
    UpsampleResult result;
    for (uint32_t y = 0; y < full.height; ++y) {
        for (uint32_t x = 0; x < full.width; ++x) {
            UpsampledPixel out;
            const UpsampleTexel& p = full.at(x, y);
            if (!p.covered) {
                result.pixels.push_back(out);
                continue;
            }
            // Sample i lies at full pixel 2i: x is between samples x/2 and x/2 + 1 (the last
            // one clamped), a fraction (x - 2 (x/2)) / 2 of the way.
            const uint32_t i0 = x / 2, j0 = y / 2;
            const uint32_t i1 = std::min(i0 + 1, half.width - 1), j1 = std::min(j0 + 1, half.height - 1);
            const double tx = (double(x) - 2.0 * i0) / 2.0, ty = (double(y) - 2.0 * j0) / 2.0;
            const Tap taps[4] = {
                {i0, j0, (1 - tx) * (1 - ty)}, {i1, j0, tx * (1 - ty)}, {i0, j1, (1 - tx) * ty}, {i1, j1, tx * ty}};
            UpsampleVec3 sum{};
            double weight_sum = 0.0;
            int nearest = -1;
            double nearest_distance = 0.0;
            for (int k = 0; k < 4; ++k) {
                const UpsampleTexel& s = half.at(taps[k].x, taps[k].y);
                if (!s.covered) continue;
                const double cos_ns = dot(p.normal, s.normal);
                const double d = distance(p.position, s.position);
                if (near(cos_ns, 0.0)) out.near_decision = true;
                if (cos_ns > 0.0) {
                    if (nearest < 0 || d < nearest_distance) {
                        nearest = k;
                        nearest_distance = d;
                    }
                }
                if (taps[k].bilinear == 0.0) continue;
                if (near(cos_ns, min_cos) || near(d, max_distance)) out.near_decision = true;
                if (!(cos_ns > min_cos && d < max_distance)) continue;
                const UpsampleVec3& l = half_radiance.at(taps[k].x, taps[k].y);
                for (int c = 0; c < 3; ++c) sum[c] += taps[k].bilinear * l[c];
                weight_sum += taps[k].bilinear;
            }
            if (weight_sum > 0.0) {
                out.outcome = UpsampleOutcome::blended;
                for (int c = 0; c < 3; ++c) out.radiance[c] = sum[c] / weight_sum;
            } else if (nearest >= 0) {
                out.outcome = UpsampleOutcome::fallback;
                out.radiance = half_radiance.at(taps[nearest].x, taps[nearest].y);
                ++result.fallback_pixels;
                // A different sample at (nearly) the nearest distance: float may pick either.
                // The same sample twice (a clamped tap) is no ambiguity.
                for (int k = 0; k < 4; ++k) {
                    const UpsampleTexel& s = half.at(taps[k].x, taps[k].y);
                    if (k == nearest || !s.covered || dot(p.normal, s.normal) <= 0.0) continue;
                    if (taps[k].x == taps[nearest].x && taps[k].y == taps[nearest].y) continue;
                    if (near(distance(p.position, s.position), nearest_distance)) out.near_decision = true;
                }
            } else {
                out.outcome = UpsampleOutcome::empty;
                ++result.empty_pixels;
            }
            result.pixels.push_back(out);
        }
    }
    return result;
}

}  // namespace vplkit::reference
