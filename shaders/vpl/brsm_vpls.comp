#version 460
#extension GL_GOOGLE_include_directive : require
// BRSM, step 5 (the thesis sec. 4.1.2): every warped sample becomes a VPL at its RSM texel, with
// the texel's flux over (N x pmf): over the samples' random rotation, the N VPLs together
// estimate, without bias, the flux of the texels of positive importance. Appended after the VPLs
// already in the buffer (earlier lights): VPL i of this light goes to vpl_count.count + i;
// brsm_vpl_count.comp then advances the count. When the warp found no importance (count 0),
// nothing is written.

#include "vplkit/sampling.glsl"
#include "vplkit/vpl.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D rsm_position;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D rsm_normal;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D rsm_flux;
layout(std430, set = 0, binding = 3) readonly buffer WarpedSampleBuffer { WarpedSample items[]; } samples;
layout(std430, set = 0, binding = 4) readonly buffer WarpCountBuffer { uint count; } warp;
layout(std430, set = 0, binding = 5) readonly buffer VplCountBuffer { uint count; uint cut_short; } vpl_count;
layout(std430, set = 0, binding = 6) writeonly buffer VplBuffer { Vpl items[]; } vpls;

layout(push_constant) uniform BrsmVplsPush {
    uint sample_count;  // N, this light's share of the VPLs
    uint map_size;      // side of the importance map the texels index
    uint capacity;      // entries of `vpls`
} push;

void main() {
    uint i = linear_thread_index();
    if (i >= warp.count || i >= push.sample_count) {
        return;
    }
    uint slot = vpl_count.count + i;
    if (slot >= push.capacity) {
        return;  // the host sizes the buffer for every light's share; never reached
    }
    WarpedSample s = samples.items[i];
    ivec2 texel = ivec2(s.texel % push.map_size, s.texel / push.map_size);
    Vpl vpl;
    vpl.position = imageLoad(rsm_position, texel).xyz;
    vpl.normal = imageLoad(rsm_normal, texel).xyz;
    // A warped sample always lands on a texel of positive importance (pmf > 0); a pmf that is not
    // positive and finite (a corrupt importance map) would make an infinite or negative VPL that
    // poisons every tree node above it: such a VPL gets no flux.
    float n_pmf = float(push.sample_count) * s.pmf;
    bool valid_pmf = n_pmf > 0.0 && !isinf(n_pmf);
    vpl.flux = valid_pmf ? imageLoad(rsm_flux, texel).rgb / n_pmf : vec3(0.0);
    vpls.items[slot] = vpl;
}
