#version 460
#extension GL_GOOGLE_include_directive : require
// The firefly clamp's second pass: each covered pixel gathers the shares of radiance its covered
// 5 x 5 neighbours (itself left out) took off in firefly_clamp.comp, divided by its own albedo
// divisor (vplkit/denoise.glsl), so that remodulation gives back exactly the radiance shared. The
// neighbour sets are the clamp's, and symmetric, so every share lands exactly once: the frame
// keeps its light (the remodulated sum equals the input's up to float rounding), and accumulating
// frames converges to the unclamped mean.
// Output: rgb = clamped + the shares gathered (irradiance); a = clamped's a (the input's).

#include "vplkit/denoise.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D clamped;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D excess;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D position;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D spread;
layout(set = 0, binding = 4, rgba16f) uniform readonly image2D albedo;

layout(push_constant) uniform FireflySpreadPush {
    float albedo_floor;  // demodulation's (denoise_albedo_divisor)
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(spread);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec4 c = imageLoad(clamped, pixel);
    if (imageLoad(position, pixel).w <= 0.5) {
        imageStore(spread, pixel, vec4(0.0));
        return;
    }
    vec3 gathered = vec3(0.0);
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if ((dx == 0 && dy == 0) || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) {
                continue;
            }
            // A background pixel's excess is 0 (the clamp writes 0 there): no coverage test needed.
            gathered += imageLoad(excess, q).rgb;
        }
    }
    vec3 divisor = denoise_albedo_divisor(imageLoad(albedo, pixel).rgb, push.albedo_floor);
    imageStore(spread, pixel, vec4(c.rgb + gathered / divisor, c.a));
}
