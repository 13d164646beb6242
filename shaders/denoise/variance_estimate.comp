#version 460
#extension GL_GOOGLE_include_directive : require
// The variance the a-trous filter is guided by (SVGF sec. 4.2): where a pixel's history is short
// (n < min_history), its temporal moments say little (n = 1: variance 0, which would stop the
// filter dead right where it is needed, at disocclusions), so the variance comes from the moments
// of the 7 x 7 neighbourhood instead, each neighbour weighted by the geometric edge weights of
// vplkit/denoise.glsl. Elsewhere the temporal variance is kept.
// Output: rgb = accumulated rgb, a = variance.

#include "vplkit/denoise.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D accumulated;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D moments;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D position;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D normal;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D estimated;

layout(push_constant) uniform VarianceEstimatePush {
    float sigma_plane;   // world units (denoise_plane_weight)
    float sigma_normal;  // exponent (denoise_normal_weight)
    uint min_history;    // below this history length the variance is spatial
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(estimated);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec4 c = imageLoad(accumulated, pixel);
    vec4 m = imageLoad(moments, pixel);
    vec4 p = imageLoad(position, pixel);
    if (p.w <= 0.5 || m.z >= float(push.min_history)) {
        imageStore(estimated, pixel, c);
        return;
    }
    vec3 n = imageLoad(normal, pixel).xyz;
    vec2 sum = vec2(0.0);
    float weights = 0.0;
    for (int dy = -3; dy <= 3; ++dy) {
        for (int dx = -3; dx <= 3; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) {
                continue;
            }
            vec4 pq = imageLoad(position, q);
            if (pq.w <= 0.5) {
                continue;
            }
            float w = denoise_plane_weight(p.xyz, n, pq.xyz, push.sigma_plane) *
                      denoise_normal_weight(n, imageLoad(normal, q).xyz, push.sigma_normal);
            sum += w * imageLoad(moments, q).xy;
            weights += w;
        }
    }
    // The pixel itself has weight 1, so weights >= 1.
    sum /= weights;
    imageStore(estimated, pixel, vec4(c.rgb, max(sum.y - sum.x * sum.x, 0.0)));
}
