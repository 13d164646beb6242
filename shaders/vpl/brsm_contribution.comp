#version 460
#extension GL_GOOGLE_include_directive : require
// BRSM, step 1 (the thesis sec. 4.1.1 and ch. 6): the expected contribution of every pVPL (RSM
// texel) to the camera's image. Around the pVPL, `sample_count` points are drawn (a uniform
// direction, a radius from the capped 1/r^2 density of vplkit/brsm.glsl), projected into the
// camera's G-buffer, and the diffuse light the pVPL sends to the surface found there is summed,
// occlusion ignored. Written as the mean over the samples (the thesis sums; a constant factor
// changes no pdf). One thread per texel of the square importance map, which holds the RSM in
// its top-left corner: texels outside the RSM, without a surface or without flux get 0.
//
// Also writes each texel's flux luminance (the RSM-style importance the defensive mixture of
// brsm_importance.comp needs), into level 0 of its mip chain.

#include "vplkit/brsm.glsl"
#include "vplkit/rng.glsl"
#include "vpl_sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D rsm_position;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D rsm_normal;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D rsm_flux;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D gbuffer_normal;
layout(set = 0, binding = 5, rgba32f) uniform readonly image2D gbuffer_geometric_normal;
layout(set = 0, binding = 6, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(std430, set = 0, binding = 7) writeonly buffer ContributionBuffer { float values[]; } contribution;
layout(std430, set = 0, binding = 8) writeonly buffer FluxLuminanceBuffer { float values[]; } flux_luminance;

layout(push_constant) uniform BrsmContributionPush {
    mat4 camera_view_projection;  // world -> the G-buffer camera's Vulkan clip space
    uint map_size;                // side of the square importance map (>= the RSM's sides)
    uint sample_count;            // G-buffer samples per pVPL, >= 1
    uint seed;
    float core_radius;            // the radius density's flat core, world units (> 0)
    float max_radius;             // its end (> core_radius)
    float scene_scale;            // Bvh::scene_scale: the VPL falloff clamp is relative to it
} push;

void main() {
    uvec2 texel = gl_GlobalInvocationID.xy;
    if (texel.x >= push.map_size || texel.y >= push.map_size) {
        return;
    }
    uint index = texel.y * push.map_size + texel.x;
    ivec2 rsm_size = imageSize(rsm_position);
    float flux = 0.0;
    float sum = 0.0;
    if (all(lessThan(ivec2(texel), rsm_size))) {
        vec4 position = imageLoad(rsm_position, ivec2(texel));
        // A texel without a surface, or one that reflects nothing, is no pVPL.
        flux = position.w > 0.5 ? max(luminance(imageLoad(rsm_flux, ivec2(texel)).rgb), 0.0) : 0.0;
        if (flux > 0.0) {
            vec3 y = position.xyz;
            vec3 n_y = imageLoad(rsm_normal, ivec2(texel)).xyz;
            vec2 gbuffer_size = vec2(imageSize(gbuffer_position));
            // The falloff is clamped at the core radius, not at the VPLs' much smaller d_min: an
            // importance is a coarse average over a neighbourhood, and a clamp at d_min would
            // let the few samples that land next to a crease outweigh everything the pVPL
            // lights farther away (BRSM's VPLs then crowd into the room's corners).
            float min_distance = max(vpl_min_distance(push.scene_scale), push.core_radius);
            Rng rng = rng_create(push.seed, index);
            for (uint s = 0u; s < push.sample_count; ++s) {
                vec3 direction = sample_uniform_sphere(rng_next_vec2(rng));
                float r = sample_capped_inverse_square_radius(rng_next_float(rng), push.core_radius, push.max_radius);
                vec4 clip = push.camera_view_projection * vec4(y + r * direction, 1.0);
                if (!(clip.w > 0.0)) {
                    continue;  // behind the camera
                }
                vec2 pixel = (clip.xy / clip.w * 0.5 + 0.5) * gbuffer_size;
                if (!all(greaterThanEqual(pixel, vec2(0.0))) || !all(lessThan(pixel, gbuffer_size))) {
                    continue;  // off screen
                }
                ivec2 p = ivec2(pixel);
                vec4 g_position = imageLoad(gbuffer_position, p);
                if (g_position.w <= 0.5) {
                    continue;  // background
                }
                GbufferSample g = gbuffer_decode(g_position, imageLoad(gbuffer_normal, p),
                                                 imageLoad(gbuffer_geometric_normal, p), imageLoad(gbuffer_albedo, p),
                                                 vec4(0.0));
                sum += pvpl_diffuse_contribution(y, n_y, flux, g, min_distance);
            }
            sum /= float(push.sample_count);
        }
    }
    // An importance must be finite: an overflowing or non-finite estimate (HDR beyond float
    // range, NaN geometry) is dropped to 0 rather than poisoning the pdf; the defensive flux term
    // still covers the texel.
    contribution.values[index] = isinf(sum) || isnan(sum) ? 0.0 : sum;
    flux_luminance.values[index] = isinf(flux) || isnan(flux) ? 0.0 : flux;
}
