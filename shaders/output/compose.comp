#version 460
// The frame's radiance: direct plus indirect light, per pixel (both linear RGB, the same size).
// Kept apart until here so that each can be written out (and compared) on its own.

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D direct;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D indirect;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D composed;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(composed)))) {
        return;
    }
    imageStore(composed, pixel, vec4(imageLoad(direct, pixel).rgb + imageLoad(indirect, pixel).rgb, 1.0));
}
