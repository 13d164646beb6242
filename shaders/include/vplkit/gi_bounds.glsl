#ifndef VPLKIT_GI_BOUNDS_GLSL
#define VPLKIT_GI_BOUNDS_GLSL

// What every tree sampler (rtslc, sst, hybrid) knows about a cluster of VPLs before it picks
// one: its box's distance and cosine bounds at a shading point, and the material term. They
// weigh tree children with these; the evaluation itself is vpl_eval.glsl's, for every method.
//
// Needs vplkit/brdf.glsl included first.

const float kGiBigFloat = 3.402823466e+38;

// The most samples per pixel (cut nodes) any sampler takes: bounds the cut shaders' local arrays.
// kMaxGiSamplesPerPixel on the host (stages/gi_counters.hpp).
const uint kGiMaxSamplesPerPixel = 64u;  // FLT_MAX: finite, unlike an Inf sentinel (light_tree.glsl)

// Smallest squared distance from x to the box [lo, hi]: 0 inside (the RTSLC paper eq. 1, d_min).
float gi_box_distance2_min(vec3 x, vec3 lo, vec3 hi) {
    vec3 d = max(max(lo - x, x - hi), vec3(0.0));
    return dot(d, d);
}

// Largest squared distance from x to the box: to its farthest corner (the RTSLC paper eq. 1, d_max).
float gi_box_distance2_max(vec3 x, vec3 lo, vec3 hi) {
    vec3 d = max(abs(lo - x), abs(hi - x));
    return dot(d, d);
}

// An upper bound of max(<n, (p - x) / |p - x|>, 0) over the points p of the box (the lightcuts
// cosine bound, Walter et al. 2005 sec. 4.1): the box's corners in a frame whose z is n give a
// box [a, b] around it there, and z / sqrt(x^2 + y^2 + z^2) grows with z and shrinks with x^2 + y^2,
// so b.z over the smallest x^2 + y^2 of [a, b] bounds it. 0 when the whole box lies behind the
// surface (b.z <= 0): no VPL in it can light x. x inside [a, b] (and b.z > 0) gives 1.
float gi_box_cosine_bound(vec3 x, vec3 n, vec3 lo, vec3 hi) {
    // Any orthonormal frame with z = n will do (the bound holds in all of them).
    vec3 helper = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    vec3 t = normalize(cross(helper, n));
    vec3 b = cross(n, t);
    vec3 a_lo = vec3(kGiBigFloat), a_hi = vec3(-kGiBigFloat);
    for (int corner = 0; corner < 8; ++corner) {
        vec3 c = vec3((corner & 1) != 0 ? hi.x : lo.x, (corner & 2) != 0 ? hi.y : lo.y, (corner & 4) != 0 ? hi.z : lo.z) - x;
        vec3 local = vec3(dot(c, t), dot(c, b), dot(c, n));
        a_lo = min(a_lo, local);
        a_hi = max(a_hi, local);
    }
    if (a_hi.z <= 0.0) {
        return 0.0;
    }
    vec2 closest = max(max(a_lo.xy, -a_hi.xy), vec2(0.0));  // 0 on an axis the box straddles
    float r2 = dot(closest, closest);
    return r2 == 0.0 ? 1.0 : a_hi.z * inversesqrt(r2 + a_hi.z * a_hi.z);
}

// the thesis eq. 5.2: the clamped cosine between n and the directions from x to the box's eight
// corners, averaged: the expected-contribution cosine of shallow cuts and hybrid traversal. 0 when
// every corner lies behind the surface ("children whose box lies fully behind the surface left
// out"). A corner at x itself (no direction) counts 0.
float gi_average_corner_cosine(vec3 x, vec3 n, vec3 lo, vec3 hi) {
    float sum = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        vec3 c = vec3((corner & 1) != 0 ? hi.x : lo.x, (corner & 2) != 0 ? hi.y : lo.y, (corner & 4) != 0 ? hi.z : lo.z) - x;
        float len2 = dot(c, c);
        if (len2 > 0.0) {
            sum += max(dot(n, c) * inversesqrt(len2), 0.0);
        }
    }
    return sum * 0.125;
}

// The material term of a cluster seen from x in direction wi (unit): the BRDF's luminance
// there (the SST paper sec. 4.1: the BRDF at the cluster; the cosine is the geometric term's). For
// the diffuse lobe it is the same for every child and cancels; for a glossy lobe it favours
// clusters near the reflection direction. A direction at or below the surface (a box centre
// or mean behind it while part of the box is in front) is lifted just above it first: the BRDF
// is 0 below the surface, and a 0 here would exclude a child that can still light x. So the
// term is never 0 for a non-black base colour (GGX's D > 0 everywhere).
float gi_material_weight(vec3 n, vec3 wo, vec3 wi, vec3 base_color, float roughness, float metallic) {
    vec3 above = normalize(wi - n * (min(dot(n, wi), 0.0) - 1e-2));
    vec3 f = brdf_evaluate(n, wo, above, base_color, roughness, metallic);
    return dot(f, vec3(0.2126, 0.7152, 0.0722));
}

// The child weights a traversal can use besides the lobes of brdf.glsl: the glossy lobe's BRDF
// towards the cluster's mean or centre, as the whole BRDF's weights look (the defensive half of
// the glossy traversal, gi_lobe.glsl). kBrdfLobeGlossy's weights look in gi_glossy_direction's.
const uint kGiWeightGlossyAtMean = 3u;

// The lobe of brdf.glsl a weight kind evaluates.
uint gi_weight_lobe(uint weight) {
    return weight == kGiWeightGlossyAtMean ? kBrdfLobeGlossy : weight;
}

// The material term of a cluster for one lobe of the BRDF (brdf_evaluate_lobe; `weight` a lobe
// or kGiWeightGlossyAtMean), from x in direction wi; kBrdfLobeBoth is gi_material_weight itself.
// A direction below the surface (or within 1e-2 of it) is lifted as gi_material_weight does, one
// above it is kept: a glossy lobe of roughness 0.05 is a few 1e-3 rad wide, and gi_material_weight's
// lift of every direction by 1e-2 would move its peak off the reflection direction.
float gi_lobe_material_weight(vec3 n, vec3 wo, vec3 wi, vec3 base_color, float roughness, float metallic,
                              uint weight) {
    if (weight == kBrdfLobeBoth) {
        return gi_material_weight(n, wo, wi, base_color, roughness, metallic);
    }
    float along = dot(n, wi);
    vec3 above = along >= 1e-2 ? wi : normalize(wi - n * (min(along, 0.0) - 1e-2));
    vec3 f = brdf_evaluate_lobe(n, wo, above, base_color, roughness, metallic, gi_weight_lobe(weight));
    return dot(f, vec3(0.2126, 0.7152, 0.0722));
}

// the SST paper sec. 4.1's heuristic for the glossy lobe's material term: the perfect reflection
// R of the view vector about n; if the ray x + t R (t >= 0) meets the box, the BRDF is evaluated
// in direction R, otherwise in the direction of the box's point nearest the ray (the paper's R',
// "the direction that does intersect the box and differs least from R"). That point is found
// approximately: the ray's point nearest the box centre, clamped into the box, then the ray's
// point nearest that, clamped again. Any direction into the box keeps the estimator unbiased
// (it only steers the choice); this one is near the BRDF's largest value over the box, so the
// weight stays close to a bound and rare children are not hugely over-weighted.
vec3 gi_glossy_direction(vec3 x, vec3 n, vec3 wo, vec3 lo, vec3 hi) {
    vec3 r = reflect(-wo, n);
    // Slab test; an axis the ray runs along gets a tiny slope instead of a division by 0.
    vec3 safe = vec3(abs(r.x) > 1e-30 ? r.x : 1e-30, abs(r.y) > 1e-30 ? r.y : 1e-30, abs(r.z) > 1e-30 ? r.z : 1e-30);
    vec3 t0 = (lo - x) / safe, t1 = (hi - x) / safe;
    vec3 near = min(t0, t1), far = max(t0, t1);
    float t_enter = max(max(near.x, near.y), max(near.z, 0.0));
    float t_exit = min(min(far.x, far.y), far.z);
    if (t_exit >= t_enter) {
        return r;
    }
    vec3 q = clamp(x + r * max(dot(0.5 * (lo + hi) - x, r), 0.0), lo, hi);
    q = clamp(x + r * max(dot(q - x, r), 0.0), lo, hi);
    vec3 d = q - x;
    float len2 = dot(d, d);
    return len2 > 0.0 ? d * inversesqrt(len2) : r;
}

// The probability of the left child when the weights are w = a / d2 (a: material x cosine x
// intensity, d2: a squared distance clamped away from 0), in the cross-multiplied form
// a_l d2_r / (a_l d2_r + a_r d2_l): no 1/d2 is formed, so no inf/inf. Returns a negative value
// for a dead branch (both a are 0): the caller stops there and returns no light. A child with
// a = 0 gets probability exactly 0 and is never chosen.
float gi_left_probability(float a_left, float d2_left, float a_right, float d2_right) {
    float left = a_left * d2_right;
    float right = a_right * d2_left;
    float sum = left + right;
    if (!(sum > 0.0)) {
        return -1.0;
    }
    return left / sum;
}

// rng_next_float's resolution: it returns k 2^-24 for a uniform k in [0, 2^24).
const float kGiProbabilityStep = 5.9604644775390625e-8;

// A child probability p in [0, 1] of a choice between two children that both weigh more than 0,
// rounded up to a multiple of 2^-24 and kept in [2^-24, 1 - 2^-24]: the traversal compares it
// with rng_next_float's k 2^-24 (u < p), so the child is taken with exactly the probability the
// estimator divides by. Unrounded, a p below 2^-24 is taken with probability 2^-24 and weighed
// by 1 / p (over-weighted), and a p that rounds to 1 never takes its sibling (its light is lost).
// A NaN is passed on as it is (the sample is dropped and counted).
float gi_grid_probability(float p) {
    if (!(p >= 0.0 && p <= 1.0)) {
        return p;
    }
    return clamp(ceil(p * 16777216.0) * kGiProbabilityStep, kGiProbabilityStep, 1.0 - kGiProbabilityStep);
}

// The left child's probability for a traversal that compares it with rng_next_float (u < p):
// gi_left_probability, on u's grid when both children weigh more than 0 (gi_grid_probability),
// exactly 0 or 1 when one weighs 0, negative for a dead branch.
float gi_child_probability(float a_left, float d2_left, float a_right, float d2_right) {
    float p = gi_left_probability(a_left, d2_left, a_right, d2_right);
    return a_left > 0.0 && a_right > 0.0 ? gi_grid_probability(p) : p;
}

#endif
