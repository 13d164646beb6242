#include "brsm_reference.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vplkit::reference {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr uint32_t kMultiplier = 747796405u;
constexpr uint32_t kIncrement = 2891336453u;

uint32_t rxs_m_xs(uint32_t state) {
    const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A projected coordinate this close to a pixel edge may land on either side in float.
constexpr double kPixelEdgeMargin = 0.02;

// The pixel indices a coordinate may fall in: one, or two near an edge; -1 = off the image.
std::vector<int> pixel_candidates(double p, uint32_t size) {
    std::vector<int> out;
    const double nearest_edge = std::round(p);
    if (std::abs(p - nearest_edge) < kPixelEdgeMargin) {
        for (int k : {int(nearest_edge) - 1, int(nearest_edge)}) out.push_back(k >= 0 && k < int(size) ? k : -1);
    } else {
        const double f = std::floor(p);
        out.push_back(f >= 0 && f < double(size) ? int(f) : -1);
    }
    return out;
}

glm::dvec3 xyz(const glm::vec4& v) {
    return glm::dvec3(v.x, v.y, v.z);
}

// The diffuse light of a pVPL (y, n_y, flux luminance) at G-buffer pixel (x, y), vplkit/brsm.glsl.
double diffuse_at(const Gbuffer& g, int px, int py, const glm::dvec3& y, const glm::dvec3& n_y, double flux,
                  double min_distance) {
    const glm::vec4& position = g.position.at(px, py);
    if (position.w <= 0.5f) return 0.0;
    const glm::dvec3 to_vpl = y - xyz(position);
    const double d2 = glm::dot(to_vpl, to_vpl);
    if (d2 == 0.0) return 0.0;
    const glm::dvec3 wi = to_vpl / std::sqrt(d2);
    const double cos_x = glm::dot(xyz(g.normal.at(px, py)), wi);
    const double cos_g = glm::dot(xyz(g.geometric_normal.at(px, py)), wi);
    const double cos_y = -glm::dot(n_y, wi);
    if (cos_x <= 0 || cos_g <= 0 || cos_y <= 0) return 0.0;
    const double metallic = g.geometric_normal.at(px, py).w;
    const double rho = luminance(xyz(g.albedo.at(px, py))) * (1.0 - metallic);
    return rho / kPi * flux * cos_y / kPi * cos_x / std::max(d2, min_distance * min_distance);
}

}  // namespace

uint32_t pcg_hash(uint32_t v) {
    return rxs_m_xs(v * kMultiplier + kIncrement);
}

Pcg32::Pcg32(uint32_t seed, uint32_t index) : state_(pcg_hash(seed ^ pcg_hash(index))), increment_(2u * index + 1u) {}

uint32_t Pcg32::next_uint() {
    const uint32_t state = state_;
    state_ = state * kMultiplier + increment_;
    return rxs_m_xs(state);
}

double Pcg32::next_float() {
    return double(next_uint() >> 8u) / 16777216.0;
}

double luminance(const glm::dvec3& rgb) {
    return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z;
}

std::vector<double> brsm_flux_luminance(const Rsm& rsm, uint32_t map_size) {
    std::vector<double> out(size_t(map_size) * map_size, 0.0);
    for (uint32_t y = 0; y < rsm.position.height; ++y) {
        for (uint32_t x = 0; x < rsm.position.width; ++x) {
            if (rsm.position.at(x, y).w > 0.5f)
                out[size_t(y) * map_size + x] = std::max(0.0, luminance(xyz(rsm.flux.at(x, y))));
        }
    }
    return out;
}

std::vector<Interval> brsm_contribution(const Rsm& rsm, const Gbuffer& gbuffer, const ContributionParams& p) {
    const std::vector<double> flux = brsm_flux_luminance(rsm, p.map_size);
    std::vector<Interval> out(flux.size());
    const double mass = 2.0 * p.core_radius - p.core_radius * p.core_radius / p.max_radius;
    for (uint32_t ty = 0; ty < rsm.position.height; ++ty) {
        for (uint32_t tx = 0; tx < rsm.position.width; ++tx) {
            const uint32_t index = ty * p.map_size + tx;
            if (flux[index] <= 0.0) continue;
            const glm::dvec3 y = xyz(rsm.position.at(tx, ty)), n_y = xyz(rsm.normal.at(tx, ty));
            Pcg32 rng(p.seed, index);
            Interval sum;
            for (uint32_t s = 0; s < p.sample_count; ++s) {
                // A uniform direction (z = 1 - 2u, phi = 2 pi v) and a radius from the capped
                // 1/r^2 density, inverted from its CDF.
                const double u0 = rng.next_float(), u1 = rng.next_float(), u2 = rng.next_float();
                const double z = 1.0 - 2.0 * u0, r_xy = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * kPi * u1;
                const glm::dvec3 direction(r_xy * std::cos(phi), r_xy * std::sin(phi), z);
                const double t = u2 * mass;
                const double r = t <= p.core_radius ? t : p.core_radius * p.core_radius / (2.0 * p.core_radius - t);
                const glm::dvec4 clip = p.camera_view_projection * glm::dvec4(y + r * direction, 1.0);
                if (clip.w <= 1e-9) continue;  // behind the camera (or too near its plane to tell)
                const double px = (clip.x / clip.w * 0.5 + 0.5) * gbuffer.position.width;
                const double py = (clip.y / clip.w * 0.5 + 0.5) * gbuffer.position.height;
                double lo = INFINITY, hi = -INFINITY;
                for (int cx : pixel_candidates(px, gbuffer.position.width)) {
                    for (int cy : pixel_candidates(py, gbuffer.position.height)) {
                        const double c =
                            cx < 0 || cy < 0 ? 0.0 : diffuse_at(gbuffer, cx, cy, y, n_y, flux[index], p.min_distance);
                        lo = std::min(lo, c);
                        hi = std::max(hi, c);
                    }
                }
                sum.lo += lo;
                sum.hi += hi;
            }
            out[index] = {sum.lo / p.sample_count, sum.hi / p.sample_count};
        }
    }
    return out;
}

std::vector<Interval> brsm_filter(const Rsm& rsm, const std::vector<float>& contribution,
                                  const std::vector<float>& flux_luminance, const FilterParams& p) {
    const uint32_t size = p.map_size;
    std::vector<Interval> out(size_t(size) * size);
    for (uint32_t ty = 0; ty < size; ++ty) {
        for (uint32_t tx = 0; tx < size; ++tx) {
            const size_t index = size_t(ty) * size + tx;
            if (!(flux_luminance[index] > 0.0f)) continue;
            const glm::dvec3 p_i = xyz(rsm.position.at(tx, ty)), n_i = xyz(rsm.normal.at(tx, ty));
            double weighted = 0, weights = 0;
            std::vector<std::pair<double, double>> undecided;  // (w, w c) of neighbours at d_max
            for (int dy = -p.radius; dy <= p.radius; ++dy) {
                for (int dx = -p.radius; dx <= p.radius; ++dx) {
                    const int jx = int(tx) + dx, jy = int(ty) + dy;
                    if (jx < 0 || jy < 0 || jx >= int(rsm.position.width) || jy >= int(rsm.position.height)) continue;
                    const glm::vec4& p_j = rsm.position.at(jx, jy);
                    if (p_j.w <= 0.5f) continue;
                    if (glm::dot(n_i, xyz(rsm.normal.at(jx, jy))) <= p.min_cos) continue;
                    const double d = glm::length(p_i - xyz(p_j));
                    const double w = std::exp(-double(dx * dx + dy * dy) / (2.0 * p.sigma * p.sigma));
                    const double wc = w * contribution[size_t(jy) * size + jx];
                    if (std::abs(d - p.max_distance) <= 1e-5 * p.max_distance) {
                        undecided.push_back({w, wc});
                    } else if (d < p.max_distance) {
                        weighted += wc;
                        weights += w;
                    }
                }
            }
            // Every subset of the undecided neighbours (rarely more than one).
            Interval range{INFINITY, -INFINITY};
            const size_t subsets = size_t(1) << std::min<size_t>(undecided.size(), 10);
            for (size_t mask = 0; mask < subsets; ++mask) {
                double a = weighted, b = weights;
                for (size_t k = 0; k < undecided.size() && k < 10; ++k) {
                    if (mask & (size_t(1) << k)) {
                        b += undecided[k].first;
                        a += undecided[k].second;
                    }
                }
                const double v = b > 0 ? a / b : 0.0;
                range.lo = std::min(range.lo, v);
                range.hi = std::max(range.hi, v);
            }
            out[index] = range;
        }
    }
    return out;
}

std::vector<double> brsm_importance(const std::vector<float>& filtered, const std::vector<float>& flux_luminance,
                                    double a) {
    double c_total = 0, f_total = 0;
    for (float v : filtered) c_total += v;
    for (float v : flux_luminance) f_total += v;
    std::vector<double> out(filtered.size(), 0.0);
    if (!(f_total > 0)) return out;
    for (size_t i = 0; i < out.size(); ++i) {
        const double flux_share = flux_luminance[i] / f_total;
        out[i] = c_total > 0 ? (1.0 - a) * filtered[i] / c_total + a * flux_share : flux_share;
    }
    return out;
}

}  // namespace vplkit::reference
