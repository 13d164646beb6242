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
#include "vplkit/bvh.glsl"
#include "vplkit/brdf.glsl"
#include "vplkit/emitters.glsl"
#include "vplkit/gbuffer.glsl"
#include "vplkit/rng.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 2, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D gbuffer_normal;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D gbuffer_geometric_normal;
layout(set = 0, binding = 5, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(std430, set = 0, binding = 6) readonly buffer EmissiveTriangleBuffer { EmissiveTriangle items[]; } emitters;
layout(set = 0, binding = 7, rgba32f) uniform image2D radiance;

layout(push_constant) uniform DirectEmissivePush {
    vec3 camera_position;
    uint emitter_count;
    uint samples;  // per pixel
    uint seed;
} push;

// The emitter whose cdf interval holds u (binary search: the first cdf > u).
uint choose_emitter(float u) {
    uint lo = 0u, hi = push.emitter_count - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        if (emitters.items[mid].cdf > u) {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    return lo;
}

// The probability choose_emitter picks emitter i: its CDF step (exact: the CDF is on u's grid).
float emitter_pmf(uint i) {
    return emitters.items[i].cdf - (i == 0u ? 0.0 : emitters.items[i - 1u].cdf);
}

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
        uint chosen = choose_emitter(rng_next_float(rng));
        EmissiveTriangle e = emitters.items[chosen];
        float pmf = emitter_pmf(chosen);
        // Uniform point on the triangle: the square-root warp (pbrt-v4 SampleUniformTriangle).
        float su = sqrt(rng_next_float(rng));
        float v = rng_next_float(rng);
        vec3 y = e.v0 * (1.0 - su) + e.v1 * (su * (1.0 - v)) + e.v2 * (su * v);
        vec3 n_y = normalize(cross(e.v1 - e.v0, e.v2 - e.v0));
        vec3 to_y = y - g.position;
        float d2 = dot(to_y, to_y);
        if (!(d2 > 0.0) || !(pmf > 0.0)) {
            continue;  // on the emitter itself: its own emission is in the G-buffer already
        }
        vec3 wi = to_y * inversesqrt(d2);
        // A double-sided emitter lights x from whichever side faces it.
        if (e.double_sided != 0u && dot(n_y, wi) > 0.0) {
            n_y = -n_y;
        }
        float cos_x = dot(g.normal, wi);
        float cos_y = dot(n_y, -wi);
        if (cos_x <= 0.0 || cos_y <= 0.0 || dot(g.geometric_normal, wi) <= 0.0) {
            continue;  // behind the surface, or the emitter's back
        }
        // Both ends offset off their surfaces; the segment from origin to target must be clear.
        vec3 origin = offset_ray_origin(g.position, g.geometric_normal, scale);
        vec3 target = offset_ray_origin(y, n_y, scale);
        if (bvh_occluded(origin, target - origin, 0.0, 1.0)) {
            continue;
        }
        // pdf of y: pmf / area, so the weight is area / pmf.
        sum += brdf_evaluate(g.normal, wo, wi, g.albedo, g.roughness, g.metallic) * e.radiance * cos_x * cos_y / d2 *
               (e.area / pmf);
    }
    vec4 current = imageLoad(radiance, pixel);
    imageStore(radiance, pixel, vec4(current.rgb + sum / float(push.samples), current.a));
}
