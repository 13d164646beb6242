#version 460
#extension GL_GOOGLE_include_directive : require
// BRSM, step 3: the importance the VPLs are drawn from, a defensive mixture (Hesterberg 1995,
// "Weighted average importance sampling and defensive mixture distributions") of the filtered
// camera contribution and the flux:
//   importance_i = (1 - a) c_i / sum(c) + a f_i / sum(f)
// with a = defensive_fraction. The flux term keeps every texel that reflects light at a
// probability of at least a f_i / sum(f), so the VPL set estimates the RSM's whole reflected flux
// without bias (also off screen, where light arrives after a second bounce) and no VPL's flux,
// f_i / (N pmf_i) <= sum(f) / (a N) in luminance, can blow up. a = 0 is pure BRSM: unbiased only
// over the texels the camera sees light from. When the camera sees none of the light's light
// (sum(c) = 0) the importance is the flux alone; when no texel has flux (sum(f) = 0) it is 0
// everywhere and the warp yields no VPL. The sums are the 1x1 tops of the two mip chains.
// Writes level 0 of the importance mip chain.

#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) readonly buffer ContributionMipBuffer { float values[]; } contribution;
layout(std430, set = 0, binding = 1) readonly buffer FluxMipBuffer { float values[]; } flux;
layout(std430, set = 0, binding = 2) writeonly buffer ImportanceBuffer { float values[]; } importance;

layout(push_constant) uniform BrsmImportancePush {
    uint texel_count;          // map_size^2
    uint top_offset;           // the 1x1 level's float in both mip chains
    float defensive_fraction;  // a, in [0, 1]
} push;

bool usable_total(float total) {
    return total > 0.0 && !isinf(total);
}

void main() {
    uint i = linear_thread_index();
    if (i >= push.texel_count) {
        return;
    }
    float flux_total = flux.values[push.top_offset];
    float contribution_total = contribution.values[push.top_offset];
    float value = 0.0;
    if (usable_total(flux_total)) {
        float flux_share = flux.values[i] / flux_total;
        value = usable_total(contribution_total)
                    ? mix(contribution.values[i] / contribution_total, flux_share, push.defensive_fraction)
                    : flux_share;
    }
    importance.values[i] = value;
}
