#version 460
// Runtime tests only: dst[i] = src[i] * multiplier + addend for i < count; reads what another
// pass wrote, so a missing barrier shows up (as a wrong value or a sync-validation hazard).

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer ScaleInput { uint values[]; } src;
layout(std430, set = 0, binding = 1) writeonly buffer ScaleOutput { uint values[]; } dst;

layout(push_constant) uniform ScaleAddPush {
    uint count;
    uint multiplier;
    uint addend;
} push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < push.count) dst.values[i] = src.values[i] * push.multiplier + push.addend;
}
