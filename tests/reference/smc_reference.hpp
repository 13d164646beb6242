#pragma once
// Plain double-precision references for the SMC stages (shaders/smc/, the SMC paper Alg. 1), written
// from the paper and the shaders' headers (what each stage is meant to do), not from their code
// paths. Random numbers come from the same PCG32 streams as vplkit/rng.glsl (brsm_reference.hpp's
// Pcg32), so a test can replay a shader's draws and compare ray by ray.

#include "ray_reference.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace vplkit::reference {

// ---- Camera rays (smc_camera_rays.comp, sec. 3.2.1) ----

// What camera ray `ray` of update `iteration` draws: a pixel of the width x height G-buffer, the
// two uniforms of its cosine direction and its Exp(1) variate for the resampling key.
struct SmcCameraDraw {
    uint32_t x = 0, y = 0;
    double u0 = 0, u1 = 0;
    double exp1 = 0;
};
SmcCameraDraw smc_camera_draw(uint32_t seed, uint32_t iteration, uint32_t ray, uint32_t width, uint32_t height);

// The cosine-distributed direction about unit n for uniforms (u0, u1): Malley's method (a
// uniform disc point lifted to the hemisphere) in the frame of Duff et al. 2017.
glm::dvec3 cosine_direction(const glm::dvec3& n, double u0, double u1);

// The area density p_A(y | x) = cos_x / pi * cos_y / d^2 of a ray from x (normal nx) hitting y
// (normal ny facing the ray), cosines floored at min_cosine and d at min_distance.
double smc_area_pdf(const glm::dvec3& x, const glm::dvec3& nx, const glm::dvec3& y, const glm::dvec3& ny,
                    double min_cosine, double min_distance);

// ---- Mailbox test (smc_validate.comp, sec. 3.2.2) ----

// Whether the camera still sees an anchor: inside the view frustum of `view_projection` (Vulkan
// clip space, depth 0..w), on the camera's side of its normal, and no triangle between the two.
bool smc_anchor_seen(const glm::dmat4& view_projection, const glm::dvec3& camera, const glm::dvec3& anchor,
                     const glm::dvec3& anchor_normal, std::span<const Triangle> triangles);

// Whether two surface points (each with its normal) see each other: each in front of the
// other's surface and no triangle between them.
bool smc_mutually_visible(const glm::dvec3& a, const glm::dvec3& na, const glm::dvec3& b, const glm::dvec3& nb,
                          std::span<const Triangle> triangles);

// ---- Revalidation (smc_revalidate.comp, sec. 3.2.2) ----

struct SmcPoint {
    glm::dvec3 position{0.0}, normal{0.0, 0.0, 1.0};
    bool covered = false;  // a camera point (else it casts nothing)
};

// One round: camera point j draws `tries` entries of `invalid_list` (uniform, from its own
// stream); a drawn VPL that j sees becomes valid. Returns, per VPL index, the camera points that
// drew and saw it (empty: it stays as it was), in pool index order: the first of them is the one
// whose claim wins (smc_revalidate.comp).
std::vector<std::vector<uint32_t>> smc_revalidation_seers(std::span<const SmcPoint> points,
                                                          std::span<const SmcPoint> vpls,
                                                          std::span<const uint32_t> invalid_list, uint32_t tries,
                                                          uint32_t seed, uint32_t iteration, uint32_t round,
                                                          std::span<const Triangle> triangles);

// ---- Selection (smc_selection_keys.comp, smc_select.comp: Alg. 1 lines 9-17, eq. 9) ----

struct SmcSelection {
    uint32_t candidates = 0;  // candidates with some intensity (> 0, finite)
    uint32_t strong = 0;      // M_strong: candidates stronger than the quantile of Y
    uint32_t min_moves = 0;   // M_min = min(M_max, M_strong)
    uint32_t still_invalid = 0;
    uint32_t removed = 0;
    uint32_t vpl_count = 0;                            // |Y| after
    std::vector<std::pair<uint32_t, uint32_t>> moves;  // (slot of Y, candidate index)
};

// Y has vpl_intensity.size() VPLs (their last intensities), valid[i] != 0 for the valid ones;
// candidate c has candidate_intensity[c]. Intensities must be distinct (no ties to break).
// Rules (the SMC paper sec. 3.2.5): invalid VPLs leave first, weakest first, at most M_max; then weak
// valid ones until M_min have left; no more leave than candidates can replace; the strongest
// candidates fill the freed slots first, then the empty ones up to the budget.
SmcSelection smc_select(std::span<const double> vpl_intensity, std::span<const uint32_t> valid,
                        std::span<const double> candidate_intensity, uint32_t budget, uint32_t max_moves,
                        double quantile);

// ---- Radiosity (smc_radiosity.comp, sec. 3.2.3) ----

// B(y) = rho E(y) of a point y (normal n) lit by a point light of intensity I (W/sr, RGB) at
// `light`: rho I cos / d^2, zero when the light is behind or the segment is blocked.
glm::dvec3 smc_point_light_radiosity(const glm::dvec3& y, const glm::dvec3& n, const glm::dvec3& rho,
                                     const glm::dvec3& light, const glm::dvec3& intensity,
                                     std::span<const Triangle> triangles);

}  // namespace vplkit::reference
