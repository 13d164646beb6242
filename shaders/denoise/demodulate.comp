#version 460
#extension GL_GOOGLE_include_directive : require
// Demodulation: indirect irradiance = indirect radiance / max(albedo, albedo_floor), per channel
// (vplkit/denoise.glsl says why a floor). Every filter after it (upsampling, temporal
// accumulation, a-trous) blurs light, not texture; remodulate.comp multiplies the albedo back.
// Background pixels (position.w = 0) get 0.

#include "vplkit/denoise.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D radiance;
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D albedo;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D position;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D irradiance;

layout(push_constant) uniform DemodulatePush {
    float albedo_floor;
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(irradiance)))) {
        return;
    }
    if (imageLoad(position, pixel).w <= 0.5) {
        imageStore(irradiance, pixel, vec4(0.0));
        return;
    }
    vec3 divisor = denoise_albedo_divisor(imageLoad(albedo, pixel).rgb, push.albedo_floor);
    imageStore(irradiance, pixel, vec4(imageLoad(radiance, pixel).rgb / divisor, 0.0));
}
