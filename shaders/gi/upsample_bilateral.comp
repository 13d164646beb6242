#version 460
#extension GL_GOOGLE_include_directive : require
// Joint bilateral upsampling of half-resolution indirect light (the thesis ch. 6, "Upsampling",
// and 7.4): a bilinear filter over the four half-resolution samples around a full pixel, each
// weight multiplied by the geometric similarity S of eq. 5.3 (vplkit/geometric_similarity.glsl)
// between the full pixel and the sample, so light is never blended across creases or depth jumps:
//   L(x) = sum_s b_s S(x, s) L_s / sum_s b_s S(x, s)
// The half G-buffer is gbuffer_downsample.comp's: half sample i lies at full pixel 2i.
//
// full_indirect.rgb: the upsampled indirect light, 0 on background pixels; .a = 0.

#include "vplkit/geometric_similarity.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D full_position;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D full_normal;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D half_position;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D half_normal;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D half_indirect;
layout(set = 0, binding = 5, rgba32f) uniform writeonly image2D full_indirect;
// fallback_pixels: covered pixels no sample was similar to, given their nearest facing sample;
// empty_pixels: covered pixels without even that, left 0. The host clears both first.
layout(std430, set = 0, binding = 6) buffer UpsampleCounters {
    uint fallback_pixels;
    uint empty_pixels;
} counters;

layout(push_constant) uniform UpsampleBilateralPush {
    float min_cos;       // eq. 5.3: n_min
    float max_distance;  // eq. 5.3: d_max, world units
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(full_indirect)))) {
        return;
    }
    vec4 position = imageLoad(full_position, pixel);
    // Background: no surface to light, and nothing to count.
    if (position.w <= 0.5) {
        imageStore(full_indirect, pixel, vec4(0.0));
        return;
    }
    vec3 p_x = position.xyz;
    vec3 n_x = imageLoad(full_normal, pixel).xyz;
    ivec2 half_size = imageSize(half_position);
    // The samples left of / above the pixel, i0 = X / 2, and the next ones, clamped at the last
    // row and column (there both taps are one sample, and its two weights add up to one).
    ivec2 s0 = pixel / 2;
    ivec2 s1 = min(s0 + 1, half_size - 1);
    // Sample i sits at full pixel 2i, so the pixel is t = (X - 2 i0) / 2 (0 or 1/2) of the way
    // from sample i0 to sample i0 + 1.
    vec2 t = vec2(pixel - 2 * s0) * 0.5;
    ivec2 taps[4] = ivec2[4](ivec2(s0.x, s0.y), ivec2(s1.x, s0.y), ivec2(s0.x, s1.y), ivec2(s1.x, s1.y));
    float bilinear[4] = float[4]((1.0 - t.x) * (1.0 - t.y), t.x * (1.0 - t.y), (1.0 - t.x) * t.y, t.x * t.y);

    vec3 weighted = vec3(0.0);
    float weights = 0.0;
    // The fallback: the nearest covered sample (world distance) whose normal is on n_x's side.
    int nearest = -1;
    float nearest_distance2 = 0.0;
    for (int k = 0; k < 4; ++k) {
        vec4 p_s = imageLoad(half_position, taps[k]);
        // Only samples on a surface: a background sample has no light and no geometry.
        if (p_s.w <= 0.5) {
            continue;
        }
        vec3 n_s = imageLoad(half_normal, taps[k]).xyz;
        vec3 d = p_x - p_s.xyz;
        float distance2 = dot(d, d);
        // Candidates for the fallback are all four samples, bilinear weight 0 included (an even
        // pixel's right or lower neighbours), strict < so the first of equals wins.
        if (dot(n_x, n_s) > 0.0 && (nearest < 0 || distance2 < nearest_distance2)) {
            nearest = k;
            nearest_distance2 = distance2;
        }
        // A zero bilinear weight is skipped, not multiplied: an even pixel then copies its own
        // sample exactly (1 x L / 1), whatever its neighbours hold.
        if (bilinear[k] == 0.0 || !geometrically_similar(p_x, n_x, p_s.xyz, n_s, push.min_cos, push.max_distance)) {
            continue;
        }
        weighted += bilinear[k] * imageLoad(half_indirect, taps[k]).rgb;
        weights += bilinear[k];
    }
    vec3 result;
    if (weights > 0.0) {
        // Normalized over the similar samples only, so a constant field stays constant.
        result = weighted / weights;
    } else if (nearest >= 0) {
        // No sample is on the pixel's piece of surface (a thin feature, a silhouette half-res
        // sampling missed): the nearest facing sample is the best guess, and the pixel is counted
        // so that a caller can see how much of the image was guessed.
        result = imageLoad(half_indirect, taps[nearest]).rgb;
        atomicAdd(counters.fallback_pixels, 1u);
    } else {
        // Nothing usable around it (all background or facing away): no light, and counted.
        result = vec3(0.0);
        atomicAdd(counters.empty_pixels, 1u);
    }
    imageStore(full_indirect, pixel, vec4(result, 0.0));
}
