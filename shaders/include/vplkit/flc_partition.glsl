#ifndef VPLKIT_FLC_PARTITION_GLSL
#define VPLKIT_FLC_PARTITION_GLSL

// Forward light cuts (the FLC paper, Laurent et al. 2016): each triangle t of area A becomes at most one
// VPL, in one level k of N + 1 levels or discarded, and a VPL of level k stands for area
// S_k f^k(t, x) at a receiver x. The levels' areas grow geometrically, S_k = S_0 mu^k (eq. 17).
//
// Decimation and partition (sec. 4, Alg. 1, eq. 3): with u uniform in [0, 1), t goes to the first
// k with u < A (1/S_0 + ... + 1/S_k), so P(t in L_k) = A / S_k, and t is discarded with the rest,
// 1 - A / S~_N, where S~_N = 1 / (1/S_0 + ... + 1/S_N). (Eq. 2 writes P(kept) = A / S_0: that is
// the one-level case; with N + 1 levels Alg. 1 keeps A / S~_N.) A triangle larger than S~_N would
// need probabilities above one: it is "divergent" and must be subdivided first (sec. 6).
//
// Partition of unity (eqs. 10-16): F^k = S_k f^k makes the estimator unbiased when
// sum_k f^k(t, x) = 1 (eq. 11), since E[sum_k F^k 1[t in L_k]] = sum_k S_k f^k A / S_k = A f.
// f^k(t, x) = f~^k(d(t, x)) with d = |x - y| / <n, (x - y)/|x - y|>_+ (eq. 14): its level sets are
// spheres through the VPL's position y centred on its normal line, so a support is a ball in front
// of the triangle and nothing behind it. f~^k are hat functions on the influence distances
// D_k = D_0 mu^(k/2) (eq. 18: each level reaches about as many VPLs per point, area D_k^2 / S_k
// constant): f~^0 is 1 up to D_0 and falls to 0 at D_1; f~^k (0 < k < N) rises on ]D_{k-1}, D_k]
// and falls on ]D_k, D_{k+1}]; f~^N rises on ]D_{N-1}, D_N] and stays 1 beyond, so the sum is 1
// at every distance in front of the triangle. (Eq. 16 as printed gives f~^0 the value 1 up to
// D_1, which overlaps f~^1's rise; the hats above are the partition its Fig. 6 draws.) Eq. 18's
// D_{N+1} = D_N would end f~^N at D_N, and a receiver farther than D_N from every VPL would get
// no light at all: with mu 1.5 and 8 levels D_N is 0.41 x the scene radius, and a closed sphere
// (every support distance there is its diameter) went black. So the last level reaches
// everything in front of its triangle: sum_k f~^k = 1 everywhere, eq. 11 holds at any distance
// for any mu and level count, and the cost is that the last level's few VPLs (scene area / S_N
// expected) are splatted over the whole screen. With one level (N = 0), f~^0 is 1 everywhere.

// Level codes beside k = 0..N (stages/include/vplkit/stages/flc.hpp mirrors them, and the flc tests
// check that they agree).
const int kFlcDiscarded = -1;
const int kFlcDivergent = -2;

// S_k = S_0 mu^k (eq. 17).
float flc_level_area(int k, float s0, float mu) {
    return s0 * pow(mu, float(k));
}

// S_k fitted to the scene (flc_stratify.comp): the scene's area over the whole number of VPLs
// floor(scene_area / S_k), so that the stratified level keeps exactly that many every frame and
// its VPLs stand for exactly the scene's area together. Rounding down keeps S_k' >= S_k, so a
// triangle regular for S~_N stays regular. A level expected to keep less than one VPL, and
// scene_area 0, keep S_k.
float flc_fitted_level_area(int k, float s0, float mu, float scene_area) {
    float nominal = flc_level_area(k, s0, mu);
    float count = floor(scene_area / nominal);
    return count >= 1.0 ? scene_area / count : nominal;
}

// 1 / S~_k = 1/S_0 + ... + 1/S_k (Alg. 1).
float flc_inverse_cumulative_area(int k, float s0, float mu) {
    float sum = 0.0;
    for (int j = 0; j <= k; ++j) {
        sum += 1.0 / flc_level_area(j, s0, mu);
    }
    return sum;
}

// S~_N: a triangle larger than this is divergent.
float flc_divergence_area(int level_count, float s0, float mu) {
    return 1.0 / flc_inverse_cumulative_area(level_count - 1, s0, mu);
}

// Alg. 1: the level of a regular triangle of `area` for the uniform `u`, or kFlcDiscarded.
int flc_level(float u, float area, int level_count, float s0, float mu) {
    float cumulative = 0.0;
    for (int k = 0; k < level_count; ++k) {
        cumulative += area / flc_level_area(k, s0, mu);
        if (u < cumulative) {
            return k;
        }
    }
    return kFlcDiscarded;
}

// flc_level's pmf (eq. 3): A / S_k for a level, the rest for kFlcDiscarded.
float flc_level_pmf(int level, float area, int level_count, float s0, float mu) {
    if (level == kFlcDiscarded) {
        return max(0.0, 1.0 - area * flc_inverse_cumulative_area(level_count - 1, s0, mu));
    }
    return area / flc_level_area(level, s0, mu);
}

// D_k = D_0 mu^(k/2) (eq. 18).
float flc_influence_distance(int k, float d0, float mu) {
    return d0 * pow(mu, 0.5 * float(k));
}

// Eq. 14: |x - y| / <n, (x - y)/|x - y|>_+ = |x - y|^2 / <n, x - y>; +inf behind the triangle's
// plane (no support there), 0 at y itself.
float flc_support_distance(vec3 x, vec3 y, vec3 n) {
    vec3 v = x - y;
    float squared = dot(v, v);
    if (squared == 0.0) {
        return 0.0;
    }
    float along = dot(n, v);
    return along > 0.0 ? squared / along : uintBitsToFloat(0x7f800000u);
}

// f~^k(d) (eq. 16, as the hats above; the last level's reaches every finite d).
float flc_partition_weight(int k, float d, int level_count, float d0, float mu) {
    if (isinf(d)) {
        return 0.0;  // behind the triangle's plane: no support
    }
    int last = level_count - 1;
    float here = flc_influence_distance(k, d0, mu);
    if (k > 0) {
        float below = flc_influence_distance(k - 1, d0, mu);
        if (d <= below) {
            return 0.0;
        }
        if (d <= here) {
            return (d - below) / (here - below);
        }
    } else if (d <= here) {
        return 1.0;
    }
    if (k == last) {
        return 1.0;
    }
    float above = flc_influence_distance(k + 1, d0, mu);
    return d < above ? (above - d) / (above - here) : 0.0;
}

// F^k = S_k f~^k(d) (eq. 10): the area a VPL of level k stands for at support distance d.
float flc_vpl_area_weight(int k, float d, int level_count, float s0, float d0, float mu) {
    return flc_level_area(k, s0, mu) * flc_partition_weight(k, d, level_count, d0, mu);
}

#endif
