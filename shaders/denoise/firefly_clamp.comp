#version 460
#extension GL_GOOGLE_include_directive : require
// Firefly control before accumulation: a pixel whose luminance is above the mean + k sigma of
// its covered neighbours (5 x 5 without itself) is scaled down to that limit. A firefly is a rare
// sample of a real (mostly caustic-like) path, so clamping biases the image dark: the luminance
// removed is written to .a so that the caller can measure that bias (sum of .a over the sum of
// the input's luminance). The neighbourhood leaves the pixel out, or one bright pixel would raise
// its own limit above itself. Fewer than 4 covered neighbours: left as it is (nothing to compare).

#include "vplkit/denoise.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D irradiance;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D position;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D clamped;

layout(push_constant) uniform FireflyClampPush {
    float k_sigma;  // the limit: neighbours' mean + k_sigma x their standard deviation
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(clamped);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec3 c = imageLoad(irradiance, pixel).rgb;
    if (imageLoad(position, pixel).w <= 0.5) {
        imageStore(clamped, pixel, vec4(0.0));
        return;
    }
    float sum = 0.0;
    float sum2 = 0.0;
    int count = 0;
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if ((dx == 0 && dy == 0) || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)) ||
                imageLoad(position, q).w <= 0.5) {
                continue;
            }
            float l = denoise_luminance(imageLoad(irradiance, q).rgb);
            sum += l;
            sum2 += l * l;
            ++count;
        }
    }
    float l = denoise_luminance(c);
    float removed = 0.0;
    if (count >= 4) {
        float mean = sum / float(count);
        float sigma = sqrt(max(sum2 / float(count) - mean * mean, 0.0));
        float limit = mean + push.k_sigma * sigma;
        if (l > limit) {
            removed = l - limit;
            c *= limit / l;
        }
    }
    imageStore(clamped, pixel, vec4(c, removed));
}
