#ifndef VPLKIT_SAMPLING_GLSL
#define VPLKIT_SAMPLING_GLSL

// Sample generation for importance-driven VPL placement (the thesis sec. 4.1 and ch. 6): a
// randomized Hammersley point set, warped hierarchically down a mip chain of texel importance.
// Every routine that produces samples has its pdf beside it (STYLE.md).

#include "vplkit/rng.glsl"

// One warped sample: a texel of the finest importance level and its probability of being picked.
struct WarpedSample {
    uint texel;  // y * size + x in the finest level
    float pmf;   // importance(texel) / total importance
};

// Van der Corput radical inverse in base 2: the bits of i mirrored about the binary point
// (the thesis ch. 6, "Hammersley Distribution").
float radical_inverse_base2(uint i) {
    return float(bitfieldReverse(i)) * 2.3283064365386963e-10;  // 2^-32
}

// The largest float below 1: rotated or rescaled coordinates are clamped to it so a coordinate
// never reaches 1, where "u < p" with p == 1 would fail and pick a half of zero importance.
const float kOneMinusUlp = 0.99999994;

// Point i of the n-point 2D Hammersley set ((i + 0.5) / n, radical inverse of i) (the thesis ch. 6),
// Cranley-Patterson rotated by `rotation` (toroidal shift, modulo 1): the rotated set keeps its
// stratification, and each point is uniform on [0,1)^2 over random rotations, which makes
// estimates built on it unbiased.
vec2 hammersley_2d(uint i, uint n, vec2 rotation) {
    vec2 u = vec2((float(i) + 0.5) / float(n), radical_inverse_base2(i));
    return min(fract(u + rotation), vec2(kOneMinusUlp));
}

// Density of one point of hammersley_2d over random rotations: uniform on the unit square.
float hammersley_2d_pdf() {
    return 1.0;
}

// The Cranley-Patterson rotation of a seed: one random offset shared by the whole point set.
vec2 hammersley_rotation(uint seed) {
    Rng rng = rng_create(seed, 0u);
    float x = float(rng_next_uint(rng) >> 8u) * 5.9604644775390625e-8;  // 24 bits * 2^-24
    float y = float(rng_next_uint(rng) >> 8u) * 5.9604644775390625e-8;
    return vec2(x, y);
}

// One step of the hierarchical warp (the thesis ch. 6, "Hierarchical warping"): picks the first of
// two parts, with sums `first` and `second`, with probability first / (first + second), and
// rescales `u` to [0,1) within the chosen part so the next step gets a fresh uniform coordinate.
// A part of zero sum is never picked. Returns true for the second part.
bool warp_select(inout float u, float first, float second) {
    float p_first = first / (first + second);
    bool pick_second = (!(u < p_first) && second > 0.0) || first <= 0.0;
    if (pick_second) {
        u = (u - p_first) / (1.0 - p_first);
    } else {
        u = u / p_first;
    }
    u = clamp(u, 0.0, kOneMinusUlp);
    return pick_second;
}

// Probability of a warped texel: its share of the total importance (a discrete pmf), the
// product of the warp_select probabilities along its path down the chain.
float warp_select_pmf(float importance, float total) {
    return importance / total;
}

#endif  // VPLKIT_SAMPLING_GLSL
