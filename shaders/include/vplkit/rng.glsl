#ifndef VPLKIT_RNG_GLSL
#define VPLKIT_RNG_GLSL

// Seeded random numbers for stochastic stages: one independent stream per invocation, from an
// explicit seed, so the same seed gives the same numbers on every device and every run.
//
// Generator: PCG32 with the RXS-M-XS output permutation (O'Neill 2014, "PCG: A Family of Simple
// Fast Space-Efficient Statistically Good Algorithms for Random Number Generation", sec. 6.3.4),
// 32-bit state, one stream per invocation chosen by the LCG increment (sec. 4.3.2): streams with
// different increments are different sequences, not shifted copies of one sequence, so two
// invocations never replay each other's numbers however many they draw.
// Seeding: the stream's start comes from pcg_hash, the same permutation used as a hash, which
// Jarzynski and Olano ("Hash Functions for GPU Rendering", JCGT 9(3), 2020) rank best among
// 32-bit hashes for quality per cost.

const uint kPcgMultiplier = 747796405u;
const uint kPcgIncrement = 2891336453u;

// One LCG step then the RXS-M-XS permutation (Jarzynski and Olano 2020, "pcg").
uint pcg_hash(uint v) {
    uint state = v * kPcgMultiplier + kPcgIncrement;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

struct Rng {
    uint state;
    uint increment;  // odd: the stream
};

// The stream of invocation `index` (a path, a pixel...) under `seed`.
Rng rng_create(uint seed, uint index) {
    Rng rng;
    // The increment must be odd for a full-period LCG (Hull-Dobell); 2 * index + 1 gives every
    // index below 2^31 its own stream.
    rng.increment = 2u * index + 1u;
    rng.state = pcg_hash(seed ^ pcg_hash(index));
    return rng;
}

uint rng_next_uint(inout Rng rng) {
    uint state = rng.state;
    rng.state = state * kPcgMultiplier + rng.increment;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Uniform in [0, 1): the top 24 bits, so every value is exact in float and 1.0 never occurs.
float rng_next_float(inout Rng rng) {
    return float(rng_next_uint(rng) >> 8u) * 5.9604644775390625e-8;  // 2^-24
}

vec2 rng_next_vec2(inout Rng rng) {
    float u = rng_next_float(rng);
    return vec2(u, rng_next_float(rng));
}

#endif
