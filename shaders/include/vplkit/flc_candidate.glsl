#ifndef VPLKIT_FLC_CANDIDATE_GLSL
#define VPLKIT_FLC_CANDIDATE_GLSL

// One scene triangle as forward light cuts sees it (shaders/flc/flc_candidates.comp writes one per
// triangle; levels and codes in vplkit/flc_partition.glsl).
struct FlcCandidate {
    vec3 position;  // the triangle's centroid
    float area;
    vec3 normal;    // unit, front (counter-clockwise) side; zero for a triangle too thin for one
    int level;      // 0..N, kFlcDiscarded or kFlcDivergent
};

#endif
