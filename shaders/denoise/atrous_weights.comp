#version 460
#extension GL_GOOGLE_include_directive : require
// The second of an a-trous iteration's three passes: each pixel's weight sum
//   W_p = sum over its 5 x 5 taps q of h(q) x w(p, q)
// (w: denoise_atrous_edge_weight, h(p, p) w(p, p) = (3/8)^2), which atrous.comp divides by.
// Output: r = the blurred variance (atrous_variance.comp's, passed on), g = W_p, ba = 0.
// Background pixels get 0.

#include "vplkit/denoise.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D source;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D position;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D normal;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D blurred_variance;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D weights;

layout(push_constant) uniform AtrousWeightsPush {
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
    ivec2 size = imageSize(weights);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    if (!covered(pixel, size)) {
        imageStore(weights, pixel, vec4(0.0));
        return;
    }
    vec3 p = imageLoad(position, pixel).xyz;
    vec3 n = imageLoad(normal, pixel).xyz;
    float l_p = denoise_luminance(imageLoad(source, pixel).rgb);
    float variance_p = imageLoad(blurred_variance, pixel).r;
    const float h[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    float sum = h[0] * h[0];
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            ivec2 q = pixel + push.step * ivec2(dx, dy);
            if ((dx == 0 && dy == 0) || !covered(q, size)) {
                continue;
            }
            sum += h[abs(dx)] * h[abs(dy)] *
                   denoise_atrous_edge_weight(p, n, l_p, variance_p, imageLoad(position, q).xyz,
                                              imageLoad(normal, q).xyz, denoise_luminance(imageLoad(source, q).rgb),
                                              imageLoad(blurred_variance, q).r, push.sigma_plane, push.sigma_normal,
                                              push.sigma_luminance);
        }
    }
    imageStore(weights, pixel, vec4(variance_p, sum, 0.0, 0.0));
}
