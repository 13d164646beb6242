#version 460
#extension GL_GOOGLE_include_directive : require
// Direct light at every G-buffer pixel: emission plus, for every punctual light, BRDF x irradiance
// x <n, wi> where a shadow ray through the BVH finds the light unoccluded. Background pixels get
// the background radiance.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 9
#include "vplkit/bvh.glsl"
#include "vplkit/brdf.glsl"
#include "vplkit/gbuffer.glsl"
#include "vplkit/lights.glsl"
#include "vplkit/punctual_visibility.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 2, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D gbuffer_normal;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D gbuffer_geometric_normal;
layout(set = 0, binding = 5, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(set = 0, binding = 6, rgba16f) uniform readonly image2D gbuffer_emission;
layout(std430, set = 0, binding = 7) readonly buffer PunctualLightBuffer { PunctualLight items[]; } lights;
layout(set = 0, binding = 8, rgba32f) uniform writeonly image2D radiance;

layout(push_constant) uniform DirectLightPush {
    vec3 camera_position;
    uint light_count;
    vec3 background;  // radiance of pixels without a surface
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(radiance)))) {
        return;
    }
    GbufferSample g = gbuffer_decode(imageLoad(gbuffer_position, pixel), imageLoad(gbuffer_normal, pixel),
                                     imageLoad(gbuffer_geometric_normal, pixel), imageLoad(gbuffer_albedo, pixel),
                                     imageLoad(gbuffer_emission, pixel));
    if (!g.covered) {
        imageStore(radiance, pixel, vec4(push.background, 1.0));
        return;
    }
    vec3 wo = normalize(push.camera_position - g.position);
    float scale = bvh_scene_scale();
    vec3 origin = offset_ray_origin(g.position, g.geometric_normal, scale);
    vec3 total = g.emission;
    for (uint i = 0u; i < push.light_count; ++i) {
        LightIncidence light = light_incidence(lights.items[i], g.position);
        float cos_theta = dot(g.normal, light.wi);
        // Light arriving from behind the geometric surface never reaches it, whatever a normal
        // map says: without this test it would leak through walls.
        if (cos_theta <= 0.0 || dot(g.geometric_normal, light.wi) <= 0.0 || all(equal(light.irradiance, vec3(0.0)))) {
            continue;
        }
        if (!punctual_light_visible(lights.items[i], light, origin, scale)) {
            continue;
        }
        total += brdf_evaluate(g.normal, wo, light.wi, g.albedo, g.roughness, g.metallic) * light.irradiance * cos_theta;
    }
    imageStore(radiance, pixel, vec4(total, 1.0));
}
