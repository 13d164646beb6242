#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// SMC, Alg. 1 lines 8 and 19 (the SMC paper sec. 3.2.4): the density of VPLs on the surfaces by
// k-nearest-neighbour estimation, as in photon mapping (the k nearest in 3D assumed to lie on
// the query's plane):
//     p(y) = k / (I pi r_k(y)^2)                                           (eq. 7)
// with I = |Y| and r_k the distance to the k-th nearest VPL of Y (the query itself left out when
// it is one of them). Candidates use k = 1 (so those near a VPL are unlikely to be chosen), the
// VPLs for rendering k = max(1, floor(sqrt(I / 32))) (eq. 8). Brute force over Y: I is a few
// thousand, so the O(I^2) scan is cheap next to the ray casting; the k best distances live in
// registers, inserted by an unrolled network (no inner loop for lavapipe's loop limit to count).
//
// out[q] = (p, I(y) = lum(B) / p (eq. 6, B: the estimate that chose y, see smc.glsl), the area one point stands for = 1 / (I p), r_k): a
// VPL's flux is B / (I p) (smc_vpls.comp). For the VPLs, k + 1/2 points share the disc (see main).
//
// The VPLs' discs where surfaces end (surface_samples > 0). Eq. 7 takes the whole disc of radius
// r_k for surface: at an open edge (the Cornell box's front, a block's rim) part of it is air, so
// the area came out too large and the light too bright (the box's floor 1.2-1.3x the reference
// at 512 VPLs, all of it 1.05-1.08x); in a corner the k nearest include the other wall's VPLs,
// so it came out too small. Here a VPL counts only neighbours on its own plane (normals within
// ~25 degrees, within ~14 degrees of its tangent plane), and its area is its cell (cell_area):
// of `surface_samples` points spread evenly over the disc on the tangent plane, those nearer to
// it than to any neighbour, with a surface of the VPL's orientation just below them (a short ray
// down the normal) and nothing between them and the VPL (a ray at the same height). The disc's
// share over k + 1/2 (before the cells) left the animated box 1.07x bright at rest and its turning
// block's VPLs at 0.67x of their light after five frames; the cells: |E| 0.0102 -> 0.0077 (IR's).

#define VPLKIT_BVH_NODES_BINDING 4
#define VPLKIT_BVH_TRIANGLES_BINDING 5
#define VPLKIT_BVH_ALPHA_BINDING 6
#include "vplkit/bvh.glsl"
#include "vplkit/rng.glsl"
#include "../vpl/vpl_sampling.glsl"
#include "smc.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer SmcStateBuffer { SmcVpl items[]; } state;
layout(std430, set = 0, binding = 1) readonly buffer SmcQueryBuffer { SmcVpl items[]; } queries;
layout(std430, set = 0, binding = 2) writeonly buffer SmcDensityBuffer { vec4 items[]; } density;
layout(std430, set = 0, binding = 3) readonly buffer SmcCounterBuffer { SmcCounters c; } counters;

layout(push_constant) uniform SmcDensityPush {
    uint budget;
    uint k;             // 1..kSmcMaxNeighbours
    uint queries_are_vpls;  // 1: the queries are Y itself (count |Y|, each leaves itself out); 0: the candidates
    float min_distance2;    // floor of r_k^2, so coincident points give a finite density
    float fallback_area;    // the area a lone VPL stands for (no neighbour to measure by)
    uint surface_samples;   // VPL queries: points measuring how much of the disc is surface (0: all of it)
} push;

const uint kSmcMaxNeighbours = 32u;
// A neighbour on the query's plane: normals within ~25 degrees, its offset within ~14 degrees of
// the tangent plane (a sphere's 1024 VPLs, k = 5, stay within ~9 and ~4).
const float kSmcPlaneNormalCos = 0.9;
const float kSmcPlaneOffsetSin = 0.25;
const float kGoldenAngle = 2.39996322972865332;

bool on_query_plane(SmcVpl query, SmcVpl other, vec3 d, float d2) {
    return dot(other.normal, query.normal) >= kSmcPlaneNormalCos &&
           abs(dot(d, query.normal)) <= kSmcPlaneOffsetSin * sqrt(d2);
}

// The VPL's cell: the part of the surface nearer to it than to any other VPL on its plane (its
// Voronoi cell), measured in the disc of radius r about it on its tangent plane by
// `surface_samples` points spread evenly over the disc (a Vogel spiral turned by the VPL's own
// seed, so the area stays from frame to frame). Point s, at r * u_s, is nearer to neighbour j
// (offset d_j) than to the query where |r u_s - d_j|^2 < r^2 |u_s|^2, i.e. r > |d_j|^2 / (2 u_s . d_j):
// main's scan keeps each point's smallest such radius (claim[s]), so one pass over Y serves any r.
// A point counts when it is the query's (r <= claim[s]) and open surface reachable from it: a ray
// a height h above the plane reaches the point above it unblocked and a ray from there down the
// normal meets a surface of the query's orientation within 2h. h = r / 4 clears a curved
// surface's rise over the disc (r^2 / 2R for radius of curvature R, up to r / 14 on the
// 1024-VPL sphere). The cells tile the surface, so their areas add up to it wherever VPLs are,
// however they lie: eq. 7's disc took k + 1/2 points for every VPL, right for the even sets SMC
// keeps at rest but not where the set is denser on one side (a lit spot's rim, a light that moved:
// the animated box's light 1.07-1.14x the reference).
const uint kSmcCellSamples = 32u;  // kSmcMaxSurfaceSamples

vec2 cell_sample(uint s, float turn) {
    float rho = sqrt((float(s) + 0.5) / float(push.surface_samples));
    float phi = float(s) * kGoldenAngle + turn;
    return rho * vec2(cos(phi), sin(phi));
}

float cell_area(SmcVpl query, float r, float claim[kSmcCellSamples], float turn, float scale) {
    vec3 n = query.normal;
    vec3 t, b;
    orthonormal_basis(n, t, b);
    float h = 0.25 * r;
    vec3 above = offset_ray_origin(query.position, n, scale) + n * h;
    float lift = length(above - query.position);
    uint reached = 0u;
    [[unroll]] for (uint s = 0u; s < kSmcCellSamples; ++s) {
        if (s >= push.surface_samples || r > claim[s]) {
            continue;
        }
        vec2 u = cell_sample(s, turn);
        vec3 offset = r * (u.x * t + u.y * b);
        if (bvh_occluded(above, offset, 0.0, 1.0)) {
            continue;
        }
        BvhHit hit = bvh_closest_hit(above + offset, -n, 0.0, 2.0 * lift);
        if (hit.id == kBvhNoHit) {
            continue;
        }
        vec3 hit_normal = normalize(bvh_triangle_normal(hit.triangle));
        if (abs(dot(hit_normal, n)) >= kSmcPlaneNormalCos) {
            ++reached;
        }
    }
    // The VPL stands on surface itself: half a point at least, so its area never comes out 0.
    return 3.14159265358979 * r * r * max(float(reached), 0.5) / float(max(push.surface_samples, 1u));
}

void main() {
    uint q = linear_thread_index();
    uint n = counters.c.vpl_count;
    uint query_count = push.queries_are_vpls != 0u ? n : counters.c.candidate_count;
    if (q >= push.budget || q >= query_count) {
        return;
    }
    SmcVpl query = queries.items[q];
    bool vpl_query = push.queries_are_vpls != 0u;
    bool measure_surface = vpl_query && push.surface_samples > 0u;
    uint others = vpl_query ? n - 1u : n;
    uint k = min(push.k, others);
    float area;
    float best_distance2 = 0.0;
    if (k == 0u) {
        area = push.fallback_area;
    } else {
        float best[kSmcMaxNeighbours];
        [[unroll]] for (uint b = 0u; b < kSmcMaxNeighbours; ++b) {
            best[b] = 3.4028234663852886e38;
        }
        // The cell's sample points in the query's tangent frame, and the radius past which a
        // neighbour claims each (cell_area).
        vec3 tangent, bitangent;
        orthonormal_basis(query.normal, tangent, bitangent);
        float turn = float(pcg_hash(query.seed)) * (6.28318530717958648 / 4294967296.0);
        float claim[kSmcCellSamples];
        vec2 cell_points[kSmcCellSamples];
        [[unroll]] for (uint s = 0u; s < kSmcCellSamples; ++s) {
            claim[s] = 3.4028234663852886e38;
            cell_points[s] = cell_sample(s, turn);
        }
        uint found = 0u;  // neighbours taken, up to k
        for (uint j = 0u; j < n; ++j) {
            if (vpl_query && j == q) {
                continue;
            }
            SmcVpl other = state.items[j];
            if ((other.flags & kSmcDead) != 0u) {
                continue;  // no surface under it: it stands for none
            }
            vec3 d = other.position - query.position;
            float d2 = dot(d, d);
            if (measure_surface) {
                if (!on_query_plane(query, other, d, d2)) {
                    continue;
                }
                vec2 dp = vec2(dot(d, tangent), dot(d, bitangent));
                [[unroll]] for (uint s = 0u; s < kSmcCellSamples; ++s) {
                    float along = 2.0 * dot(cell_points[s], dp);
                    if (along > 0.0) {
                        claim[s] = min(claim[s], d2 / along);
                    }
                }
            }
            if (!(d2 < best[k - 1u])) {
                continue;
            }
            found = min(found + 1u, k);
            // Insert into the sorted list best[0..k): from the top, shift what is larger.
            [[unroll]] for (int b = int(kSmcMaxNeighbours) - 1; b >= 0; --b) {
                if (uint(b) < k && d2 < best[b]) {
                    best[b] = (b > 0 && d2 < best[b - 1]) ? best[b - 1] : d2;
                }
            }
        }
        // Points sharing the disc of radius r_k: k for a candidate (the k-th on its rim); for a VPL
        // of Y itself and k neighbours. With the rim's point counted half: k - 1/2 and k + 1/2.
        // Eq. 7 counts k for both; on the blue-noise sets SMC keeps (candidates near VPLs are
        // rarely chosen) that overstates each VPL's area: in a closed sphere of known radiosity
        // the flux of a 1024-VPL set came out 13% high with k = 5 and 8% with k = 8 (k + 1/2:
        // within 2%). Candidates keep the paper's k = 1 (their densities only rank them).
        float points = vpl_query ? float(k) + 0.5 : float(k);
        float radius2 = best[k - 1u];
        if (found < k) {
            // Fewer than k VPLs on its plane in all: they and it share the disc of the scene's size
            // (eq. 7), or the cell is measured within twice the farthest of them (cell_area: a disc
            // of the scene's size would leave the cell a sample or none).
            radius2 = push.fallback_area / 3.14159265358979;
            points = float(found) + 1.0;
            if (measure_surface && found > 0u) {
                radius2 = min(radius2, 4.0 * best[found - 1u]);
            }
        }
        best_distance2 = radius2;
        area = 3.14159265358979 * max(radius2, push.min_distance2) / points;
        if (measure_surface) {
            area = cell_area(query, sqrt(max(radius2, push.min_distance2)), claim, turn, bvh_scene_scale());
        }
    }
    float pdf = 1.0 / (float(max(n, 1u)) * area);
    float intensity = smc_luminance(query.choice_radiosity) / pdf;  // ranks: the choosing estimate
    density.items[q] = vec4(pdf, (!isnan(intensity) && !isinf(intensity)) ? intensity : 0.0, area,
                            k == 0u ? 0.0 : sqrt(max(best_distance2, 0.0)));
}
