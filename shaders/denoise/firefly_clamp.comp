#version 460
#extension GL_GOOGLE_include_directive : require
// Firefly control, energy-conserving (the first of two passes; the second, firefly_spread.comp,
// gives the light back). A pixel whose luminance is above the mean + k sigma of its covered
// neighbours (5 x 5 without itself) is scaled down to that limit. A firefly is a rare sample of a
// real path: dropping its excess biases every frame dark, and an accumulation of such frames
// converges to a dark image (5% of Sponza's indirect light). So the excess is not
// dropped but handed, in equal shares, to the same covered neighbours the statistics came from:
// their set is symmetric (q is p's neighbour iff p is q's), so what p hands out is exactly what
// its neighbours gather. The shares travel as radiance (the excess irradiance times p's albedo
// divisor, vplkit/denoise.glsl), and each neighbour divides by its own divisor: after
// remodulation the image's radiance is the input's (up to float rounding), whatever the albedos.
// The runtime runs it on the accumulated image, after temporal accumulation, not on each frame:
// the history stays the unclamped running mean (on a static view it converges to the unbiased
// answer), and the clamp only shapes what is shown and filtered. Where the pixel's history holds
// at least min_history frames, its own statistics bound the clamp too: the pixel is pulled down
// by at most k standard errors of its mean (sqrt(variance / n), the moments' variance of one
// frame over the history length), so a highlight that is there in every frame, which the spatial
// test calls an outlier for ever, is moved less and less as its mean converges (the shown image
// converges to the unclamped mean like 1/sqrt(n)), while a firefly, whose frame inflates the
// pixel's variance, is still cut to the spatial limit.
// The neighbourhood leaves the pixel out, or one bright pixel would raise its own limit above
// itself. Fewer than 4 covered neighbours: left as it is (nothing to compare, nowhere to spread).
// Reads the input's history moments (m1, m2, n of luminance, temporal_accumulate.comp).
// Writes: clamped (rgb: the irradiance scaled to the limit; a: the input's a, e.g. the variance)
// and excess (rgb: the radiance taken off over the neighbour count, what each neighbour gathers;
// a: the luminance of irradiance taken off, for the caller's count of the share moved).

#include "vplkit/denoise.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D irradiance;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D position;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D clamped;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D excess;
layout(set = 0, binding = 4, rgba16f) uniform readonly image2D albedo;
layout(set = 0, binding = 5, rgba32f) uniform readonly image2D moments;  // m1, m2, n (temporal pass)

layout(push_constant) uniform FireflyClampPush {
    float k_sigma;       // the limit: neighbours' mean + k_sigma x their standard deviation
    float albedo_floor;  // demodulation's (denoise_albedo_divisor)
    uint min_history;    // from this history length on, the pixel's own standard error bounds the clamp
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(clamped);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec4 input_texel = imageLoad(irradiance, pixel);
    vec3 c = input_texel.rgb;
    if (imageLoad(position, pixel).w <= 0.5) {
        imageStore(clamped, pixel, vec4(0.0));
        imageStore(excess, pixel, vec4(0.0));
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
    vec3 divisor = denoise_albedo_divisor(imageLoad(albedo, pixel).rgb, push.albedo_floor);
    float removed = 0.0;
    vec3 share = vec3(0.0);
    if (count >= 4) {
        float mean = sum / float(count);
        float sigma = sqrt(max(sum2 / float(count) - mean * mean, 0.0));
        float limit = mean + push.k_sigma * sigma;
        vec4 m = imageLoad(moments, pixel);
        if (m.z >= float(push.min_history)) {
            float standard_error = sqrt(max(m.y - m.x * m.x, 0.0) / m.z);
            limit = max(limit, l - push.k_sigma * standard_error);
        }
        if (l > limit) {
            vec3 kept = c * (limit / l);
            share = (c - kept) * divisor / float(count);
            removed = l - limit;
            c = kept;
        }
    }
    imageStore(clamped, pixel, vec4(c, input_texel.a));
    imageStore(excess, pixel, vec4(share, removed));
}
