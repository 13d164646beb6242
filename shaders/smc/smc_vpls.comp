#version 460
#extension GL_GOOGLE_include_directive : require
// SMC, Alg. 1 line 19 and the hand-over to rendering: each VPL of Y keeps its new density and
// intensity (for the next update's lines 9-17) and becomes a Vpl with flux
//     B(y) / (I p(y)) = B(y) pi r_k^2 / k
// (eq. 5 with eq. 7: a Lambertian emitter of radiosity B over the area one VPL stands for), the
// form every gather (vpl_eval.glsl) reads.

#include "vplkit/vpl.glsl"
#include "smc.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) buffer SmcStateBuffer { SmcVpl items[]; } state;
layout(std430, set = 0, binding = 1) readonly buffer SmcDensityBuffer { vec4 items[]; } density;
layout(std430, set = 0, binding = 2) writeonly buffer VplBuffer { Vpl items[]; } vpls;
layout(std430, set = 0, binding = 3) readonly buffer SmcCounterBuffer { SmcCounters c; } counters;

layout(push_constant) uniform SmcVplsPush {
    uint budget;
} push;

void main() {
    uint i = linear_thread_index();
    if (i >= push.budget || i >= counters.c.vpl_count) {
        return;
    }
    vec4 d = density.items[i];
    state.items[i].pdf = d.x;
    state.items[i].intensity = d.y;
    SmcVpl v = state.items[i];
    Vpl out_vpl;
    out_vpl.position = v.position;
    out_vpl.normal = v.normal;
    out_vpl.flux = v.radiosity * d.z;
    vpls.items[i] = out_vpl;
}
