// compose*.comp's body: composed = direct + indirect per pixel, a = 1. The including entry point
// defines VPLKIT_COMPOSE_FORMAT, the storage format qualifier of `direct` and `composed` (a
// storage image's format is part of the shader, so each output format is an entry point of its
// own rather than a branch). `indirect` is the kit's RGBA32F. `direct` and `composed` may be one
// image (add in place): each invocation reads its pixel before it writes it.

layout(local_size_x = 16, local_size_y = 16) in;

layout(set = 0, binding = 0, VPLKIT_COMPOSE_FORMAT) uniform readonly image2D direct;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D indirect;
layout(set = 0, binding = 2, VPLKIT_COMPOSE_FORMAT) uniform writeonly image2D composed;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(composed)))) {
        return;
    }
    imageStore(composed, pixel, vec4(imageLoad(direct, pixel).rgb + imageLoad(indirect, pixel).rgb, 1.0));
}
