#version 460
#extension GL_GOOGLE_include_directive : require
// BRSM, step 2 (the thesis ch. 6, "BRSM Filtering"): the pVPL contributions, estimated from a few
// G-buffer samples each, are noisy; an edge-aware Gaussian smooths them within a surface and not
// across its edges. For texel i, over the texels j of the (2 radius + 1)^2 window that hold a
// surface and are geometrically similar to i (the thesis eq. 5.3, vplkit/geometric_similarity.glsl):
//   filtered_i = sum_j w_ij c_j / sum_j w_ij,   w_ij = exp(-|i - j|^2 / (2 sigma^2))  (texels)
// A texel without flux stays 0, so a VPL is never placed where there is no light to carry.
// Writes level 0 of the contribution's mip chain.

#include "vplkit/geometric_similarity.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// Half the window's side, in texels.
layout(constant_id = 0) const int kFilterRadius = 4;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D rsm_position;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D rsm_normal;
layout(std430, set = 0, binding = 2) readonly buffer ContributionBuffer { float values[]; } contribution;
layout(std430, set = 0, binding = 3) readonly buffer FluxLuminanceBuffer { float values[]; } flux_luminance;
layout(std430, set = 0, binding = 4) writeonly buffer FilteredContributionBuffer { float values[]; } filtered;

layout(push_constant) uniform BrsmFilterPush {
    uint map_size;
    float sigma;         // the Gaussian's standard deviation, texels (> 0)
    float min_cos;       // eq. 5.3: n_min
    float max_distance;  // eq. 5.3: d_max, world units
} push;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    int size = int(push.map_size);
    if (texel.x >= size || texel.y >= size) {
        return;
    }
    int index = texel.y * size + texel.x;
    if (!(flux_luminance.values[index] > 0.0)) {
        filtered.values[index] = 0.0;  // outside the RSM, no surface, or no flux
        return;
    }
    ivec2 rsm_size = imageSize(rsm_position);
    vec3 p_i = imageLoad(rsm_position, texel).xyz;
    vec3 n_i = imageLoad(rsm_normal, texel).xyz;
    float inv_two_sigma2 = 0.5 / (push.sigma * push.sigma);
    float weighted = 0.0;
    float weights = 0.0;
    for (int dy = -kFilterRadius; dy <= kFilterRadius; ++dy) {
        for (int dx = -kFilterRadius; dx <= kFilterRadius; ++dx) {
            ivec2 j = texel + ivec2(dx, dy);
            if (any(lessThan(j, ivec2(0))) || any(greaterThanEqual(j, rsm_size))) {
                continue;
            }
            vec4 p_j = imageLoad(rsm_position, j);
            if (p_j.w <= 0.5) {
                continue;  // no surface
            }
            vec3 n_j = imageLoad(rsm_normal, j).xyz;
            if (!geometrically_similar(p_i, n_i, p_j.xyz, n_j, push.min_cos, push.max_distance)) {
                continue;
            }
            float w = exp(-float(dx * dx + dy * dy) * inv_two_sigma2);
            weighted += w * contribution.values[j.y * size + j.x];
            weights += w;
        }
    }
    // weights >= 1: the texel itself is always similar to itself (n_min < 1, d_max > 0).
    filtered.values[index] = weighted / weights;
}
