#version 460
#extension GL_GOOGLE_include_directive : require
// One iteration of the edge-avoiding a-trous wavelet filter (Dammertz et al. 2010, as SVGF sec.
// 4.3 guides it): a 5 x 5 B3-spline kernel h = (1, 4, 6, 4, 1) / 16 with taps `step` pixels apart
// (1, 2, 4, ... per iteration), each tap weighted by
//   w(p, q) = h(q) x plane(p, q) x normal(p, q) x exp(-|l_p - l_q| / (sigma_luminance sqrt(g(var_p)) + eps))
// where g is a 3 x 3 Gaussian blur of the variance (SVGF eq. 5). Colour is the weighted mean;
// the variance is filtered with the squared weights (SVGF eq. 3's variance propagation), so
// the next iteration's luminance test tightens as noise falls.
// Input and output: rgb = irradiance, a = variance. Background pixels get 0.

#include "vplkit/denoise.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D source;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D position;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D normal;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D filtered;

layout(push_constant) uniform AtrousPush {
    int step;               // tap spacing in pixels: 2^iteration
    float sigma_plane;      // world units (denoise_plane_weight)
    float sigma_normal;     // exponent (denoise_normal_weight)
    float sigma_luminance;  // SVGF's sigma_l (4)
} push;

// Avoids 0 / 0 where the variance is 0 (a noiseless or constant image): then only equal
// luminances pass, and a constant image stays constant.
const float kLuminanceEpsilon = 1e-10;

bool covered(ivec2 q, ivec2 size) {
    return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size)) && imageLoad(position, q).w > 0.5;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(filtered);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec4 p = imageLoad(position, pixel);
    if (p.w <= 0.5) {
        imageStore(filtered, pixel, vec4(0.0));
        return;
    }
    vec3 n = imageLoad(normal, pixel).xyz;
    vec4 center = imageLoad(source, pixel);
    float l_p = denoise_luminance(center.rgb);

    // The 3 x 3 Gaussian (1, 2, 1)^2 / 16 of the variance over covered pixels, renormalized.
    float variance_sum = 0.0;
    float variance_weights = 0.0;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (covered(q, size)) {
                float g = float((2 - abs(dx)) * (2 - abs(dy)));
                variance_sum += g * imageLoad(source, q).a;
                variance_weights += g;
            }
        }
    }
    float luminance_scale = push.sigma_luminance * sqrt(max(variance_sum / variance_weights, 0.0)) + kLuminanceEpsilon;

    const float h[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    vec3 color_sum = vec3(0.0);
    float variance_out = 0.0;
    float weights = 0.0;
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            ivec2 q = pixel + push.step * ivec2(dx, dy);
            if (!covered(q, size)) {
                continue;
            }
            vec4 s = (dx == 0 && dy == 0) ? center : imageLoad(source, q);
            float w = h[abs(dx)] * h[abs(dy)];
            if (dx != 0 || dy != 0) {
                w *= denoise_plane_weight(p.xyz, n, imageLoad(position, q).xyz, push.sigma_plane) *
                     denoise_normal_weight(n, imageLoad(normal, q).xyz, push.sigma_normal) *
                     exp(-abs(l_p - denoise_luminance(s.rgb)) / luminance_scale);
            }
            color_sum += w * s.rgb;
            variance_out += w * w * s.a;
            weights += w;
        }
    }
    // The centre's own weight (9/64) keeps weights > 0.
    imageStore(filtered, pixel, vec4(color_sum / weights, variance_out / (weights * weights)));
}
