#version 460
#extension GL_GOOGLE_include_directive : require
// Direct light from emissive triangles, added to the radiance image: per pixel, `samples`
// points on the emitters, each chosen with probability pmf(triangle) / area (power-proportional
// triangle, uniform point on it), with a BVH shadow ray each. Monte Carlo estimate of
//   L(x, wo) = integral over emitters of f(x, wo, wi) L_e cos(theta_x) cos(theta_y) / d^2 dA(y)
// (the area form of the rendering equation's direct term: pbrt-v4 sec. 12.2 "area lights").

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 8
#define VPLKIT_EMITTERS_BINDING 6
#include "vplkit/bvh.glsl"
#include "vplkit/brdf.glsl"
#include "vplkit/gbuffer.glsl"
#include "vplkit/rng.glsl"
#include "vplkit/emitter_sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 2, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D gbuffer_normal;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D gbuffer_geometric_normal;
layout(set = 0, binding = 5, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(set = 0, binding = 7, rgba32f) uniform image2D radiance;

layout(push_constant) uniform DirectEmissivePush {
    vec3 camera_position;
    uint emitter_count;
    uint samples;  // per pixel
    uint seed;
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(radiance))) || push.emitter_count == 0u || push.samples == 0u) {
        return;
    }
    GbufferSample g = gbuffer_decode(imageLoad(gbuffer_position, pixel), imageLoad(gbuffer_normal, pixel),
                                     imageLoad(gbuffer_geometric_normal, pixel), imageLoad(gbuffer_albedo, pixel),
                                     vec4(0.0));
    if (!g.covered) {
        return;
    }
    vec3 wo = normalize(push.camera_position - g.position);
    float scale = bvh_scene_scale();
    Rng rng = rng_create(push.seed, uint(pixel.y) * uint(imageSize(radiance).x) + uint(pixel.x));  // a stream per pixel
    vec3 sum = vec3(0.0);
    for (uint s = 0u; s < push.samples; ++s) {
        EmitterSample e = emitter_sample(g.position, g.normal, g.geometric_normal, scale, push.emitter_count, rng);
        if (e.cos_x > 0.0) {
            sum += brdf_evaluate(g.normal, wo, e.wi, g.albedo, g.roughness, g.metallic) * e.incident * e.cos_x;
        }
    }
    vec4 current = imageLoad(radiance, pixel);
    imageStore(radiance, pixel, vec4(current.rgb + sum / float(push.samples), current.a));
}
