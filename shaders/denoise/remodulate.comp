#version 460
#extension GL_GOOGLE_include_directive : require
// Remodulation: indirect radiance = (filtered) indirect irradiance x max(albedo, albedo_floor), per
// channel (the divisor demodulate.comp divided by; vplkit/denoise.glsl), at full
// resolution, so texture detail comes from the G-buffer and not from the filtered light.

#include "vplkit/denoise.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D irradiance;
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D albedo;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D radiance;

layout(push_constant) uniform RemodulatePush {
    float albedo_floor;
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(radiance)))) {
        return;
    }
    vec3 factor = denoise_albedo_divisor(imageLoad(albedo, pixel).rgb, push.albedo_floor);
    imageStore(radiance, pixel, vec4(imageLoad(irradiance, pixel).rgb * factor, 0.0));
}
