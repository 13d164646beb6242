#version 460
#extension GL_GOOGLE_include_directive : require
// The half-resolution G-buffer that GI at half resolution shades (the thesis ch. 6, "Upsampling":
// indirect light is rendered at half the resolution and joint-bilaterally upsampled). Half pixel
// (i, j) is a copy of full pixel (2i, 2j) of every image but depth; the half size is
// ((W + 1) / 2, (H + 1) / 2), so (2i, 2j) is always inside the full image, odd sizes included.
//
// A copy, not an average: an average of positions across a depth jump lies on no surface, and an
// average of normals is not unit; the GI stages and the upsampler's similarity test need a real
// surface point with its own normal. upsample_bilateral.comp places sample i at full pixel 2i.
// Depth is a depth attachment, not a storage image, and no compute stage reads it: not copied.

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D full_position;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D full_normal;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D full_geometric_normal;
layout(set = 0, binding = 3, rgba16f) uniform readonly image2D full_albedo;
layout(set = 0, binding = 4, rgba16f) uniform readonly image2D full_emission;
layout(set = 0, binding = 5, rgba32f) uniform writeonly image2D half_position;
layout(set = 0, binding = 6, rgba32f) uniform writeonly image2D half_normal;
layout(set = 0, binding = 7, rgba32f) uniform writeonly image2D half_geometric_normal;
layout(set = 0, binding = 8, rgba16f) uniform writeonly image2D half_albedo;
layout(set = 0, binding = 9, rgba16f) uniform writeonly image2D half_emission;

void main() {
    ivec2 half_pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(half_pixel, imageSize(half_position)))) {
        return;
    }
    ivec2 full_pixel = 2 * half_pixel;
    // Every channel as stored (w: coverage, roughness, metallic): the half G-buffer decodes like
    // the full one (vplkit/gbuffer.glsl). RGBA16F to RGBA16F through float is exact.
    imageStore(half_position, half_pixel, imageLoad(full_position, full_pixel));
    imageStore(half_normal, half_pixel, imageLoad(full_normal, full_pixel));
    imageStore(half_geometric_normal, half_pixel, imageLoad(full_geometric_normal, full_pixel));
    imageStore(half_albedo, half_pixel, imageLoad(full_albedo, full_pixel));
    imageStore(half_emission, half_pixel, imageLoad(full_emission, full_pixel));
}
