#version 460
#extension GL_GOOGLE_include_directive : require
// The first of an a-trous iteration's three passes: the variance the luminance test scales by,
// a 3 x 3 Gaussian (1, 2, 1)^2 / 16 of the source's variance over covered pixels, renormalized
// (SVGF eq. 5's g). It has a pass of its own because the symmetric weight of atrous.comp needs it
// at every tap, not only at the centre.
// Output: r = blurred variance, gba = 0. Background pixels get 0.

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D source;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D position;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D blurred_variance;

bool covered(ivec2 q, ivec2 size) {
    return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size)) && imageLoad(position, q).w > 0.5;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(blurred_variance);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    if (!covered(pixel, size)) {
        imageStore(blurred_variance, pixel, vec4(0.0));
        return;
    }
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
    imageStore(blurred_variance, pixel, vec4(variance_sum / variance_weights, 0.0, 0.0, 0.0));
}
