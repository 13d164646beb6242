#version 460
#extension GL_GOOGLE_include_directive : require
// Linear HDR radiance -> display 8-bit sRGB: exposure, the ACES filmic curve, the sRGB transfer
// function. A pixel that is not finite is written magenta (never silently black) and counted, so
// the renderer can report it.

#include "vplkit/tonemap.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D hdr;
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D ldr;
layout(std430, set = 0, binding = 2) buffer TonemapStatsBuffer { uint non_finite_pixels; } stats;

layout(push_constant) uniform TonemapPush {
    float exposure;  // linear scale applied before the curve
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(hdr)))) {
        return;
    }
    vec3 radiance = imageLoad(hdr, pixel).rgb;
    vec3 display;
    if (any(isnan(radiance)) || any(isinf(radiance))) {
        atomicAdd(stats.non_finite_pixels, 1u);
        display = vec3(1.0, 0.0, 1.0);
    } else {
        display = linear_to_srgb(aces_filmic(max(radiance, vec3(0.0)) * push.exposure));
    }
    imageStore(ldr, pixel, vec4(display, 1.0));
}
