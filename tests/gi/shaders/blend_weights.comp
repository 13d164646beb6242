#version 460
#extension GL_GOOGLE_include_directive : require
// Test-only: cut blending's neighbours and weights (vplkit/cut_blending.glsl) for every pixel of
// an image, against blocks and pixel geometry the host writes, so the host can check that the
// bilinear weights and the normalized blend weights sum to 1 and match its own computation.

#include "vplkit/geometric_similarity.glsl"
#include "vplkit/cut_blending.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

struct BlendPixel {
    vec3 position;
    float pad0;
    vec3 normal;
    float pad1;
};

struct BlendResult {
    ivec4 block_x;   // the four neighbour blocks
    ivec4 block_y;
    vec4 bilinear;   // their bilinear weights
    vec4 weight;     // normalized blend weights (0 when not blended)
    uint blended;    // 0: mock cut
    uint pad0, pad1, pad2;
};

layout(std430, set = 0, binding = 0) readonly buffer BlendBlocks { HybridBlock items[]; } blocks;
layout(std430, set = 0, binding = 1) readonly buffer BlendPixels { BlendPixel items[]; } pixels;
layout(std430, set = 0, binding = 2) writeonly buffer BlendResults { BlendResult items[]; } results;

layout(push_constant) uniform BlendWeightsPush {
    uint width;
    uint height;
    uint block_size;
    uint blocks_x;
    uint blocks_y;
    float min_cos;
    float max_distance;
} push;

void main() {
    uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= push.width || p.y >= push.height) {
        return;
    }
    uint index = p.y * push.width + p.x;
    ivec2 block[4];
    float bilinear[4];
    cut_blend_neighbours(ivec2(p), push.block_size, ivec2(push.blocks_x, push.blocks_y), block, bilinear);
    HybridBlock neighbour[4];
    for (int k = 0; k < 4; ++k) {
        neighbour[k] = blocks.items[uint(block[k].y) * push.blocks_x + uint(block[k].x)];
    }
    float weight[4];
    bool blended = cut_blend_weights(pixels.items[index].position, pixels.items[index].normal, neighbour, bilinear,
                                     push.min_cos, push.max_distance, weight);
    BlendResult r;
    r.block_x = ivec4(block[0].x, block[1].x, block[2].x, block[3].x);
    r.block_y = ivec4(block[0].y, block[1].y, block[2].y, block[3].y);
    r.bilinear = vec4(bilinear[0], bilinear[1], bilinear[2], bilinear[3]);
    r.weight = blended ? vec4(weight[0], weight[1], weight[2], weight[3]) : vec4(0.0);
    r.blended = blended ? 1u : 0u;
    r.pad0 = 0u;
    r.pad1 = 0u;
    r.pad2 = 0u;
    results.items[index] = r;
}
