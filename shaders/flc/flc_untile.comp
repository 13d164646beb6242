#version 460
#extension GL_GOOGLE_include_directive : require
// Forward light cuts, interleaved sub-tiles (the FLC paper sec. 6): the splat's n x n sub-tiles put back
// in image order (untiling), and the blur that gives every pixel all the VPLs: image pixel p takes
// the mean of the n x n window around it (one pixel of each sub-tile, so each of the n^2 VPL
// subsets once) over the neighbours on p's surface: covered, normal within acos(min_cos) of p's,
// and within max_distance of p's tangent plane (the geometry-aware blur; a neighbour across an
// edge would bring light of another surface). p itself always counts, so a lone pixel keeps its
// own sub-tile's estimate. blur = 0: untiling only (what the tests compare pixel by pixel).

#include "vplkit/gbuffer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D tiled;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D gbuffer_geometric_normal;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D indirect;

layout(push_constant) uniform FlcUntilePush {
    uvec2 image_size;
    uvec2 subtile_size;
    uint subtiles;  // n >= 1
    uint blur;      // 0 or 1
    float max_distance;
    float min_cos;
} push;

vec4 tiled_at(ivec2 p) {
    uvec2 q = uvec2(p);
    return imageLoad(tiled, ivec2((q % push.subtiles) * push.subtile_size + q / push.subtiles));
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(p), push.image_size))) {
        return;
    }
    vec4 sum = tiled_at(p);
    vec4 x = imageLoad(gbuffer_position, p);
    if (push.blur == 0u || push.subtiles == 1u || x.w <= 0.5) {
        imageStore(indirect, p, sum);
        return;
    }
    vec3 n = imageLoad(gbuffer_geometric_normal, p).xyz;
    float count = 1.0;
    int first = -int(push.subtiles / 2u);
    for (int dy = first; dy < first + int(push.subtiles); ++dy) {
        for (int dx = first; dx < first + int(push.subtiles); ++dx) {
            ivec2 q = p + ivec2(dx, dy);
            if ((dx == 0 && dy == 0) || any(lessThan(q, ivec2(0))) ||
                any(greaterThanEqual(uvec2(q), push.image_size))) {
                continue;
            }
            vec4 y = imageLoad(gbuffer_position, q);
            vec3 m = imageLoad(gbuffer_geometric_normal, q).xyz;
            if (y.w <= 0.5 || dot(n, m) < push.min_cos || abs(dot(n, y.xyz - x.xyz)) > push.max_distance) {
                continue;
            }
            sum += tiled_at(q);
            count += 1.0;
        }
    }
    imageStore(indirect, p, sum / count);
}
