#version 460
#extension GL_GOOGLE_include_directive : require
// Exact indirect light (the ground truth): every VPL of the chunk [vpl_first,
// vpl_first + vpl_count) at every G-buffer pixel, each with its own shadow ray. Accumulates into
// `indirect` (read-modify-write of the thread's own pixel), so dispatches over consecutive
// chunks add up to the sum over all VPLs; the host clears `indirect` and `counters` first.
//
// indirect.rgb: the sum of the finite contributions; indirect.a: how many contributions this
// pixel dropped (see below), 0 for a clean pixel. Background pixels stay 0.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 9
#include "vplkit/bvh.glsl"
#include "vplkit/brdf.glsl"
#include "vplkit/gbuffer.glsl"
#include "vplkit/vpl.glsl"
#include "vplkit/vpl_eval.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// d_min of the 1/d^2 clamp over the scene scale: vpl_eval.glsl's kVplMinDistanceFraction, which
// every sampling method shares, unless specialized (stages::ExactGiOptions::min_distance_fraction);
// 0 evaluates each VPL unclamped, as a path tracer would (for comparisons with one).
layout(constant_id = 0) const float kExactMinDistanceFraction = 1e-2;

layout(set = 0, binding = 2, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D gbuffer_normal;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D gbuffer_geometric_normal;
layout(set = 0, binding = 5, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(std430, set = 0, binding = 6) readonly buffer VplBuffer { Vpl items[]; } vpls;
layout(set = 0, binding = 7, rgba32f) uniform image2D indirect;
// dropped_pixels: pixels with at least one dropped contribution (counted once, when its first
// drop happens); dropped_contributions: dropped (pixel, VPL) pairs, exact below 2^32;
// cut_short: invocations whose loops the driver ended early (see the sentinel below).
layout(std430, set = 0, binding = 8) buffer ExactGiCounters {
    uint dropped_pixels;
    uint dropped_contributions;
    uint cut_short;
} counters;

layout(push_constant) uniform ExactGiPush {
    vec3 camera_position;
    uint vpl_first;
    uint vpl_count;
} push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(indirect)))) {
        return;
    }
    vec4 position = imageLoad(gbuffer_position, pixel);
    if (position.w <= 0.5) {
        return;
    }
    GbufferSample g = gbuffer_decode(position, imageLoad(gbuffer_normal, pixel),
                                     imageLoad(gbuffer_geometric_normal, pixel), imageLoad(gbuffer_albedo, pixel),
                                     vec4(0.0));
    vec3 wo = normalize(push.camera_position - g.position);
    float scale = bvh_scene_scale();
    float min_distance = kExactMinDistanceFraction * scale;
    vec4 previous = imageLoad(indirect, pixel);
    // Added in VPL order onto the running total, so any chunking sums in the same order.
    vec3 total = previous.rgb;
    uint dropped = 0u;
    uint end = push.vpl_first + push.vpl_count;
    // lavapipe (llvmpipe) ends every loop of a SIMD batch of invocations, silently, once its
    // loops together have run 65535 iterations (LP_MAX_TGSI_LOOP_ITERATIONS, shared between every
    // loop of a shader): 4096 VPLs in one dispatch lost 38% of the Cornell box's indirect light.
    // So the loop runs one sentinel iteration past the last VPL; if the driver cut it short, that
    // iteration never ran and the pixel is counted in cut_short (the host refuses the result).
    // The limiter fires at a loop's end, so a cut inside the last VPL's shadow ray still skips
    // the sentinel.
    bool completed = false;
    for (uint i = push.vpl_first; i <= end; ++i) {
        if (i == end) {
            completed = true;
            break;
        }
        Vpl vpl = vpls.items[i];
        vec3 c = vpl_contribution(g.position, g.normal, g.geometric_normal, wo, g.albedo, g.roughness, g.metallic, vpl,
                                  min_distance);
        // Bad data never reaches the image: the per-pixel result is finite or the sample is counted as dropped. A
        // non-finite contribution (bad VPL data), or one that would overflow the total, is left
        // out and counted; it is never traced, whatever its visibility.
        vec3 next = total + c;
        if (!vpl_finite(c) || !vpl_finite(next)) {
            ++dropped;
            continue;
        }
        if (all(equal(c, vec3(0.0)))) {
            continue;
        }
        // The VPL lies on a surface facing x (its normal points to x's side: cos_y > 0 above),
        // so both ends are moved off their surfaces and neither can shadow the segment.
        if (bvh_segment_occluded(g.position, g.geometric_normal, vpl.position, vpl.normal, scale)) {
            continue;
        }
        total = next;
    }
    if (!completed) {
        atomicAdd(counters.cut_short, 1u);
    }
    if (dropped > 0u) {
        if (previous.a == 0.0) {
            atomicAdd(counters.dropped_pixels, 1u);
        }
        atomicAdd(counters.dropped_contributions, dropped);
    }
    imageStore(indirect, pixel, vec4(total, previous.a + float(dropped)));
}
