#version 460
#extension GL_GOOGLE_include_directive : require
// Real-time stochastic lightcuts, reconstruction after interleaved sampling (the RTSLC paper sec. 3.4):
// each pixel of an m x m sub-block sampled only its share of the block's cut nodes
// (rtslc_interleave_slots), so one pixel's estimate covers ~1/m^2 of the VPLs. Here each pixel
// x gets the sum of the estimates of the sub-block's pixels y whose geometry is similar to its
// own (the thesis eq. 5.3: geometrically_similar, normals within min_cos and positions within
// max_distance; x itself always), rescaled by c / (the cut nodes those pixels sampled), c = the
// nodes of the block's cut. When all m^2 pixels are similar they sample every node once and the
// scale is 1.
//
// This is an approximation, not an unbiased estimator: y's estimate is of y's light, evaluated
// at y's position, normal and material, and it stands in for x's light from the same nodes. That
// is close where the surface is smooth and the lighting varies slowly over the sub-block, and
// wrong at edges and shadow boundaries: a similar neighbour in another VPL's shadow, or on the
// far side of a crease the thresholds let through, lends x light x does not receive (or takes
// light away). Where few neighbours are similar, the rescale by c / covered extrapolates x's
// light from the nodes those pixels sampled, which assumes the uncovered nodes give as much per
// node. The seed pairs this with a geometry-aware denoiser; here the mean over frames (the
// rotation moves each pixel through every share) converges to the average of those estimates.
//
// indirect.rgb: the reconstruction; indirect.a: the dropped samples of the estimates summed.

#include "vplkit/geometric_similarity.glsl"
#include "vplkit/brdf.glsl"
#include "vplkit/light_tree.glsl"
#include "vplkit/gi_bounds.glsl"
#include "vplkit/rtslc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D gbuffer_normal;
layout(std430, set = 0, binding = 2) readonly buffer RtslcCutBuffer { uint items[]; } cuts;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D estimates;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D indirect;

layout(push_constant) uniform RtslcInterleavePush {
    uint block_size;  // k
    uint cut_size;    // n: slots per block in `cuts`
    uint blocks_x;
    uint interleave;  // m > 1, divides k
    uint frame;
    float similarity_min_cos;
    float similarity_max_distance;  // absolute (world units)
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(indirect);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec4 position = imageLoad(gbuffer_position, pixel);
    if (position.w <= 0.5) {
        imageStore(indirect, pixel, vec4(0.0));
        return;
    }
    vec3 normal = imageLoad(gbuffer_normal, pixel).xyz;
    uvec2 block_xy = uvec2(pixel) / push.block_size;
    uint base = (block_xy.y * push.blocks_x + block_xy.x) * push.cut_size;
    uint cut_nodes = 0u;
    while (cut_nodes < push.cut_size && cuts.items[base + cut_nodes] != kRtslcNoNode) {
        ++cut_nodes;
    }
    // m divides k, so the sub-block lies inside the pixel's block: its pixels share the cut. At
    // most m^2 <= 1024 iterations plus the cut count: far below lavapipe's loop limit.
    ivec2 lo = pixel - pixel % int(push.interleave);
    ivec2 hi = min(lo + ivec2(push.interleave), size);
    vec3 sum = vec3(0.0);
    float dropped = 0.0;
    uint covered_nodes = 0u;
    for (int y = lo.y; y < hi.y; ++y) {
        for (int x = lo.x; x < hi.x; ++x) {
            ivec2 other = ivec2(x, y);
            vec4 other_position = imageLoad(gbuffer_position, other);
            if (other_position.w <= 0.5) {
                continue;
            }
            if (other != pixel && !geometrically_similar(position.xyz, normal, other_position.xyz,
                                                         imageLoad(gbuffer_normal, other).xyz, push.similarity_min_cos,
                                                         push.similarity_max_distance)) {
                continue;
            }
            uvec2 share = rtslc_interleave_slots(uvec2(other), push.interleave, push.frame, cut_nodes);
            vec4 estimate = imageLoad(estimates, other);
            sum += estimate.rgb;
            dropped += estimate.a;
            covered_nodes += share.y - share.x;
        }
    }
    // x itself covers at least one node whenever the cut has one (rtslc_interleave_slots gives
    // every pixel a share once c >= m^2, and the whole cut below that), so covered_nodes > 0.
    vec3 result = covered_nodes == 0u ? vec3(0.0) : sum * (float(cut_nodes) / float(covered_nodes));
    imageStore(indirect, pixel, vec4(result, dropped));
}
