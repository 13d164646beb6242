#version 460
#extension GL_GOOGLE_include_directive : require
// One level of the importance mip chain (the thesis sec. 4.1): each texel is the SUM of the 2x2
// texels below it, so every texel holds the total importance of its quadrant and the 1x1 top
// holds the total. All levels live in one flat buffer, finest first (layout in
// runtime/include/vplkit/stages/importance_warp.hpp); one dispatch per level, so a level is
// complete before the next one reads it.

#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) buffer ImportanceMipBuffer { float values[]; } mips;

layout(push_constant) uniform ImportanceMipsPush {
    uint src_offset;  // first float of the finer level
    uint dst_offset;  // first float of the level written
    uint dst_size;    // its width (= height); the finer level is twice as wide
} push;

void main() {
    uint i = linear_thread_index();
    if (i >= push.dst_size * push.dst_size) {
        return;
    }
    uint x = i % push.dst_size;
    uint y = i / push.dst_size;
    uint src_size = 2u * push.dst_size;
    uint base = push.src_offset + 2u * y * src_size + 2u * x;
    mips.values[push.dst_offset + i] = (mips.values[base] + mips.values[base + 1u]) +
                                       (mips.values[base + src_size] + mips.values[base + src_size + 1u]);
}
