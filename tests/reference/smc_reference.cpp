#include "smc_reference.hpp"

#include "brsm_reference.hpp"

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace vplkit::reference {

namespace {

Double3 a3(const glm::dvec3& v) {
    return {v.x, v.y, v.z};
}

// No triangle strictly between a and b (the end points' own surfaces do not count: a relative
// margin of 1e-6 at both ends, far below the tests' clearances).
bool segment_clear(const glm::dvec3& a, const glm::dvec3& b, std::span<const Triangle> triangles) {
    const Ray ray{a3(a), a3(b - a), 1e-6, 1.0 - 1e-6};
    return !occluded(triangles, ray);
}

}  // namespace

SmcCameraDraw smc_camera_draw(uint32_t seed, uint32_t iteration, uint32_t ray, uint32_t width, uint32_t height) {
    Pcg32 rng(pcg_hash(seed ^ pcg_hash(iteration)), ray);
    SmcCameraDraw d;
    const double px = rng.next_float(), py = rng.next_float();
    // The pixel is floor(u x size) in float (as the shader computes it), clamped to the image.
    d.x = std::min(uint32_t(float(px) * float(width)), width - 1);
    d.y = std::min(uint32_t(float(py) * float(height)), height - 1);
    d.u0 = rng.next_float();
    d.u1 = rng.next_float();
    d.exp1 = -std::log(1.0 - rng.next_float());
    return d;
}

glm::dvec3 cosine_direction(const glm::dvec3& n, double u0, double u1) {
    const double r = std::sqrt(u0), phi = 2.0 * std::numbers::pi * u1;
    const glm::dvec3 local{r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u0))};
    // Duff et al. 2017, listing 3.
    const double s = n.z >= 0.0 ? 1.0 : -1.0;
    const double a = -1.0 / (s + n.z);
    const double c = n.x * n.y * a;
    const glm::dvec3 t{1.0 + s * n.x * n.x * a, s * c, -s * n.x};
    const glm::dvec3 b{c, s + n.y * n.y * a, -n.y};
    return local.x * t + local.y * b + local.z * n;
}

double smc_area_pdf(const glm::dvec3& x, const glm::dvec3& nx, const glm::dvec3& y, const glm::dvec3& ny,
                    double min_cosine, double min_distance) {
    const glm::dvec3 d = y - x;
    const double d2 = std::max(glm::dot(d, d), min_distance * min_distance);
    const glm::dvec3 w = glm::normalize(d);
    const double cos_x = std::max(glm::dot(nx, w), min_cosine);
    const double cos_y = std::max(-glm::dot(ny, w), min_cosine);
    return cos_x / std::numbers::pi * cos_y / d2;
}

bool smc_anchor_seen(const glm::dmat4& view_projection, const glm::dvec3& camera, const glm::dvec3& anchor,
                     const glm::dvec3& anchor_normal, std::span<const Triangle> triangles) {
    const glm::dvec4 clip = view_projection * glm::dvec4(anchor, 1.0);
    const bool in_frustum =
        clip.w > 0.0 && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w && clip.z >= 0.0 && clip.z <= clip.w;
    if (!in_frustum || glm::dot(anchor_normal, camera - anchor) <= 0.0) return false;
    return segment_clear(anchor, camera, triangles);
}

bool smc_mutually_visible(const glm::dvec3& a, const glm::dvec3& na, const glm::dvec3& b, const glm::dvec3& nb,
                          std::span<const Triangle> triangles) {
    const glm::dvec3 d = b - a;
    if (glm::dot(na, d) <= 0.0 || glm::dot(nb, -d) <= 0.0) return false;
    return segment_clear(a, b, triangles);
}

std::vector<std::vector<uint32_t>> smc_revalidation_seers(std::span<const SmcPoint> points,
                                                          std::span<const SmcPoint> vpls,
                                                          std::span<const uint32_t> invalid_list, uint32_t tries,
                                                          uint32_t seed, uint32_t iteration, uint32_t round,
                                                          std::span<const Triangle> triangles) {
    std::vector<std::vector<uint32_t>> seers(vpls.size());
    const uint32_t invalid = uint32_t(invalid_list.size());
    if (invalid == 0) return seers;
    const uint32_t stream = pcg_hash(seed ^ pcg_hash(iteration * 2u + round + 0x5bd1e995u));
    for (uint32_t j = 0; j < points.size(); ++j) {
        if (!points[j].covered) continue;
        Pcg32 rng(stream, j);
        for (uint32_t t = 0; t < tries; ++t) {
            // The entry is floor(u x count) in float, as the shader draws it.
            const float u = float(rng.next_float());
            const uint32_t i = invalid_list[std::min(uint32_t(u * float(invalid)), invalid - 1)];
            const SmcPoint& v = vpls[i];
            if (smc_mutually_visible(points[j].position, points[j].normal, v.position, v.normal, triangles) &&
                std::find(seers[i].begin(), seers[i].end(), j) == seers[i].end()) {
                seers[i].push_back(j);
            }
        }
    }
    return seers;
}

SmcSelection smc_select(std::span<const double> vpl_intensity, std::span<const uint32_t> valid,
                        std::span<const double> candidate_intensity, uint32_t budget, uint32_t max_moves,
                        double quantile) {
    SmcSelection s;
    const uint32_t n = uint32_t(vpl_intensity.size());
    // Y weakest first; the candidates with light, strongest first.
    std::vector<uint32_t> weakest(n);
    std::iota(weakest.begin(), weakest.end(), 0u);
    std::sort(weakest.begin(), weakest.end(),
              [&](uint32_t a, uint32_t b) { return vpl_intensity[a] < vpl_intensity[b]; });
    std::vector<uint32_t> strongest;
    for (uint32_t c = 0; c < std::min<size_t>(candidate_intensity.size(), budget); ++c) {
        if (candidate_intensity[c] > 0.0 && std::isfinite(candidate_intensity[c])) strongest.push_back(c);
    }
    std::sort(strongest.begin(), strongest.end(),
              [&](uint32_t a, uint32_t b) { return candidate_intensity[a] > candidate_intensity[b]; });
    s.candidates = uint32_t(strongest.size());

    // Eq. 9: candidates above the quantile of Y's intensities (all of them while Y is empty).
    s.strong = s.candidates;
    if (n > 0) {
        const uint32_t rank = std::min(n - 1, uint32_t(std::floor(quantile * n)));
        const double threshold = vpl_intensity[weakest[rank]];
        s.strong = uint32_t(std::count_if(strongest.begin(), strongest.end(),
                                          [&](uint32_t c) { return candidate_intensity[c] > threshold; }));
    }
    s.min_moves = std::min(max_moves, s.strong);

    std::vector<uint32_t> leaving;
    for (uint32_t i : weakest) {
        if (valid[i] != 0) continue;
        ++s.still_invalid;
        if (leaving.size() < max_moves) leaving.push_back(i);
    }
    for (uint32_t i : weakest) {
        if (leaving.size() >= s.min_moves) break;
        if (valid[i] != 0) leaving.push_back(i);
    }
    leaving.resize(std::min<size_t>(leaving.size(), s.candidates));  // no holes in Y
    s.removed = uint32_t(leaving.size());
    const uint32_t entering = std::min(budget - n + s.removed, s.candidates);
    for (uint32_t m = 0; m < entering; ++m) {
        const uint32_t slot = m < s.removed ? leaving[m] : n + (m - s.removed);
        s.moves.push_back({slot, strongest[m]});
    }
    s.vpl_count = n - s.removed + entering;
    return s;
}

glm::dvec3 smc_point_light_radiosity(const glm::dvec3& y, const glm::dvec3& n, const glm::dvec3& rho,
                                     const glm::dvec3& light, const glm::dvec3& intensity,
                                     std::span<const Triangle> triangles) {
    const glm::dvec3 to = light - y;
    const double d2 = glm::dot(to, to);
    const double cosine = glm::dot(n, to) / std::sqrt(d2);
    if (cosine <= 0.0 || !segment_clear(y, light, triangles)) return glm::dvec3(0.0);
    return rho * intensity * (cosine / d2);
}

}  // namespace vplkit::reference
