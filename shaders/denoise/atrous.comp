#version 460
#extension GL_GOOGLE_include_directive : require
// One iteration of the edge-avoiding a-trous wavelet filter (Dammertz et al. 2010, as SVGF sec.
// 4.3 guides it), the last of its three passes: a 5 x 5 B3-spline kernel h = (1, 4, 6, 4, 1) / 16
// with taps `step` pixels apart (1, 2, 4, ... per iteration), each tap q != p weighted by
//   a(p, q) = h(q) w(p, q) / max(W_p, W_q),   a(p, p) = 1 - sum over q != p of a(p, q)
// where w is the symmetric edge weight of denoise_atrous_edge_weight (plane x normal x luminance,
// the luminance scaled by the larger of the two pixels' 3 x 3 blurred variances, SVGF eq. 5) and
// W the pixel's weight sum (atrous_weights.comp). a is symmetric and its rows sum to 1, so its
// columns do too: a constant image stays constant AND every pixel hands out exactly its own light,
// so the image's sum is kept whatever the noise. SVGF divides by W_p alone: a bright outlier's small
// W_p pulls it far down while its neighbours (W ~ 1) take little of it, and heavy-tailed noise
// (rare bright samples) loses light (14% in samples/dropin). a(p, p) >= h(p)^2 / W_p > 0.
// The variance is filtered with the squared weights (SVGF eq. 3's variance propagation), so the
// next iteration's luminance test tightens as noise falls.
// Input and output: rgb = irradiance, a = variance. Background pixels get 0.

#include "vplkit/denoise.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D source;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D position;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D normal;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D weights;  // r: blurred variance, g: W
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D filtered;

layout(push_constant) uniform AtrousPush {
    int step;               // tap spacing in pixels: 2^iteration
    float sigma_plane;      // world units (denoise_plane_weight)
    float sigma_normal;     // exponent (denoise_normal_weight)
    float sigma_luminance;  // SVGF's sigma_l (4)
} push;

bool covered(ivec2 q, ivec2 size) {
    return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size)) && imageLoad(position, q).w > 0.5;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(filtered);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    if (!covered(pixel, size)) {
        imageStore(filtered, pixel, vec4(0.0));
        return;
    }
    vec3 p = imageLoad(position, pixel).xyz;
    vec3 n = imageLoad(normal, pixel).xyz;
    vec4 center = imageLoad(source, pixel);
    float l_p = denoise_luminance(center.rgb);
    vec2 variance_and_sum_p = imageLoad(weights, pixel).rg;

    const float h[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    vec3 color_sum = vec3(0.0);
    float variance_out = 0.0;
    float given = 0.0;  // sum of a(p, q) over q != p
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            ivec2 q = pixel + push.step * ivec2(dx, dy);
            if ((dx == 0 && dy == 0) || !covered(q, size)) {
                continue;
            }
            vec4 s = imageLoad(source, q);
            vec2 variance_and_sum_q = imageLoad(weights, q).rg;
            float a = h[abs(dx)] * h[abs(dy)] *
                      denoise_atrous_edge_weight(p, n, l_p, variance_and_sum_p.x, imageLoad(position, q).xyz,
                                                 imageLoad(normal, q).xyz, denoise_luminance(s.rgb),
                                                 variance_and_sum_q.x, push.sigma_plane, push.sigma_normal,
                                                 push.sigma_luminance) /
                      max(variance_and_sum_p.y, variance_and_sum_q.y);
            color_sum += a * s.rgb;
            variance_out += a * a * s.a;
            given += a;
        }
    }
    float kept = max(1.0 - given, 0.0);
    imageStore(filtered, pixel, vec4(color_sum + kept * center.rgb, variance_out + kept * kept * center.a));
}
