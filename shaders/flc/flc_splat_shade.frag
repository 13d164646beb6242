#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// Forward light cuts, splatting (the FLC paper sec. 5), fragment stage: the receiver is the G-buffer
// surface at this pixel; the VPL's light there, unshadowed (the paper's one bounce has no
// visibility), times its level's partition weight f~^k(d) (eq. 14, flc_partition.glsl), is added
// into the indirect image by the pipeline's blending (ONE, ONE, ADD): each kept VPL adds its share,
// and the shares of all levels sum to the one-bounce light (eq. 11). The light is the formula
// every indirect method uses (vpl_eval.glsl), so flc differs from `exact` only in which VPLs it
// sums, their weights and the missing visibility. Background pixels and non-finite results add 0.
//
// The VPL's emission is Lambertian (radiance rho E / pi, vpl_eval.glsl), not eq. 6's lobe
// rho E 3/(2 pi) <n, w>_+. Eq. 6 is a different reflector, not a different estimator: it emits the
// same power B = rho E but 1.5 cos(theta) times the Lambertian radiance, so it converges to another
// image than `exact` (a wall lights a perpendicular floor near their corner, where theta is near
// 90 degrees, up to 100% less, and what faces it 50% more), and the kit measures every method
// against `exact`, whose VPLs are Lambertian as a diffuse surface is. The paper takes eq. 6 for its
// convenience alone ("no important changes appear"): with it, max over receiver normals of H is
// proportional to 1 / d(t, x)^2 exactly, so eq. 13's balls of significance are the level sets of
// eq. 14's d. Unbiasedness does not need that: eqs. 8-11 hold for any transfer H once
// sum_k f~^k(d(x)) = 1 at every x, so the supports keep eq. 14's shape, and a Lambertian VPL's
// light is partitioned among the levels exactly as well; only the heuristic of where a VPL is
// "significant" (eq. 12) is looser at grazing exit angles. In the closed sphere both lobes give the
// same answer (indirect / direct = albedo): the test could not tell them apart.
// With n x n interleaved sub-tiles (flc_splat_proxy.vert) the fragment's target pixel stands for
// image pixel (u n + a, v n + b), and each VPL's light is scaled by n^2: its sub-tile sees one VPL
// in n^2, so the sub-tile's sum stays an unbiased estimate of the whole.

#include "vplkit/brdf.glsl"
#include "vplkit/flc_partition.glsl"
#include "vplkit/gbuffer.glsl"
#include "vplkit/vpl.glsl"
#include "vplkit/vpl_eval.glsl"

layout(set = 0, binding = 3, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D gbuffer_normal;
layout(set = 0, binding = 5, rgba32f) uniform readonly image2D gbuffer_geometric_normal;
layout(set = 0, binding = 6, rgba16f) uniform readonly image2D gbuffer_albedo;

layout(push_constant) uniform FlcSplatPush {
    mat4 view_projection;
    vec3 camera_position;
    float scene_scale;
    uvec2 image_size;
    uvec2 subtile_size;
    uint subtiles;
    uint level_count;
    float d0;
    float mu;
} push;

layout(location = 0) flat in vec3 vpl_position;
layout(location = 1) flat in vec3 vpl_normal;
layout(location = 2) flat in vec3 vpl_flux;
layout(location = 3) flat in int vpl_level;

layout(location = 0) out vec4 indirect;

void main() {
    indirect = vec4(0.0);
    uvec2 target = uvec2(gl_FragCoord.xy);
    uvec2 tile = target / push.subtile_size;
    uvec2 image_pixel = (target % push.subtile_size) * push.subtiles + tile;
    if (any(greaterThanEqual(image_pixel, push.image_size))) {
        return;  // a sub-tile's padding: the image size is not a multiple of n
    }
    ivec2 pixel = ivec2(image_pixel);
    vec4 position = imageLoad(gbuffer_position, pixel);
    if (position.w <= 0.5) {
        return;
    }
    float d = flc_support_distance(position.xyz, vpl_position, vpl_normal);
    float weight = flc_partition_weight(vpl_level, d, int(push.level_count), push.d0, push.mu);
    if (weight == 0.0) {
        return;
    }
    GbufferSample g = gbuffer_decode(position, imageLoad(gbuffer_normal, pixel),
                                     imageLoad(gbuffer_geometric_normal, pixel), imageLoad(gbuffer_albedo, pixel),
                                     vec4(0.0));
    vec3 wo = normalize(push.camera_position - g.position);
    Vpl vpl;
    vpl.position = vpl_position;
    vpl.normal = vpl_normal;
    vpl.flux = vpl_flux;
    vec3 c = weight * float(push.subtiles * push.subtiles) * vpl_contribution(g.position, g.normal, g.geometric_normal, wo, g.albedo, g.roughness, g.metallic,
                                       vpl, vpl_min_distance(push.scene_scale));
    if (vpl_finite(c)) {
        indirect = vec4(c, 0.0);
    }
}
