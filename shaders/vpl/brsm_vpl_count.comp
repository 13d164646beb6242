#version 460
// BRSM, step 6: after a light's VPLs are written (brsm_vpls.comp), the running count moves past
// them, so the next light appends after them. A separate dispatch because every thread of
// brsm_vpls.comp reads the count the light started from. One thread.

layout(local_size_x = 1) in;

layout(std430, set = 0, binding = 0) readonly buffer WarpCountBuffer { uint count; } warp;
layout(std430, set = 0, binding = 1) buffer VplCountBuffer { uint count; uint cut_short; } vpl_count;

layout(push_constant) uniform BrsmVplCountPush {
    uint sample_count;  // this light's share: warp.count is this or 0
} push;

void main() {
    vpl_count.count += min(warp.count, push.sample_count);
}
