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
} push;

const uint kSmcMaxNeighbours = 32u;

void main() {
    uint q = linear_thread_index();
    uint n = counters.c.vpl_count;
    uint query_count = push.queries_are_vpls != 0u ? n : counters.c.candidate_count;
    if (q >= push.budget || q >= query_count) {
        return;
    }
    SmcVpl query = queries.items[q];
    uint others = push.queries_are_vpls != 0u ? n - 1u : n;
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
        for (uint j = 0u; j < n; ++j) {
            if (push.queries_are_vpls != 0u && j == q) {
                continue;
            }
            vec3 d = state.items[j].position - query.position;
            float d2 = dot(d, d);
            if (!(d2 < best[k - 1u])) {
                continue;
            }
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
        best_distance2 = best[k - 1u];
        float points = push.queries_are_vpls != 0u ? float(k) + 0.5 : float(k);
        area = 3.14159265358979 * max(best[k - 1u], push.min_distance2) / points;
    }
    float pdf = 1.0 / (float(max(n, 1u)) * area);
    float intensity = smc_luminance(query.choice_radiosity) / pdf;  // ranks: the choosing estimate
    density.items[q] = vec4(pdf, (!isnan(intensity) && !isinf(intensity)) ? intensity : 0.0, area,
                            k == 0u ? 0.0 : sqrt(max(best_distance2, 0.0)));
}
