#version 460
#extension GL_GOOGLE_include_directive : require
// Temporal accumulation with reprojection (SVGF, Schied et al. 2017, sec. 4.1): each pixel's
// world position in the previous frame (its position plus the G-buffer's motion: where a moving
// object's point was) is projected with the previous frame's view-projection; the previous frame's
// four pixels around that point are the history, each tap kept only if it shows the same surface
// (covered, within max_plane_distance of the tangent plane through the point's previous position,
// normals within min_normal_cos:
// the mesh-id test of SVGF is left to these two, as the G-buffer holds no ids), bilinear weights
// renormalized over the kept taps. No tap kept: a disocclusion, the history restarts at 1.
// A pixel whose point reprojects onto its own centre (within kStaticPixels: a static camera, up
// to float rounding) reads that one previous pixel, no bilinear blend, and its history length is
// capped by static_max_history (0: no cap) instead of max_history: unbiased frames on a static
// view then average with exact 1 / n weights and converge to their mean (SVGF's cap, there to
// forget what reprojection blurs and lighting changes leave behind, would stop the convergence
// at an exponential average of the last max_history frames).
//   n = min(previous n + 1, cap), alpha = 1 / n
//   colour  = mix(history colour, current, alpha)           (a running mean until the cap)
//   moments = mix(history (m1, m2), (l, l^2), alpha),  variance = max(m2 - m1^2, 0)
// Writes: accumulated (rgb, a = variance), moments (m1, m2, n, 0), and this frame's geometry into
// the history images the next frame reads (history_position, history_normal).

#include "vplkit/denoise.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D irradiance;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D position;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D normal;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D previous_position;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D previous_normal;
layout(set = 0, binding = 5, rgba32f) uniform readonly image2D previous_color;
layout(set = 0, binding = 6, rgba32f) uniform readonly image2D previous_moments;
layout(set = 0, binding = 7, rgba32f) uniform writeonly image2D accumulated;
layout(set = 0, binding = 8, rgba32f) uniform writeonly image2D moments;
layout(set = 0, binding = 9, rgba32f) uniform writeonly image2D history_position;
layout(set = 0, binding = 10, rgba32f) uniform writeonly image2D history_normal;
// xyz: previous position - position (gbuffer.glsl's motion); read only when push.has_motion is 1.
layout(set = 0, binding = 11, rgba32f) uniform readonly image2D motion;

layout(push_constant) uniform TemporalAccumulatePush {
    mat4 previous_view_projection;  // world -> the previous frame's Vulkan clip space
    float max_plane_distance;       // world units
    float min_normal_cos;
    uint max_history;               // the cap on n: alpha never falls below 1 / max_history
    uint has_history;               // 0 on the first frame: the previous images hold nothing
    uint static_max_history;        // the cap where a pixel reprojects onto itself; 0: none
    uint has_motion;                // 1: `motion` holds the G-buffer's motion; 0: nothing moved
} push;

// How far (in pixels, per axis) a reprojected point may sit from the pixel's own centre and still
// count as static: float rounding of a static camera's round trip is ~1e-4 pixel; a camera that
// drifts by less than this per frame is treated as still (its history lags by that much).
const float kStaticPixels = 0.01;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(accumulated);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec4 p = imageLoad(position, pixel);
    vec4 n = imageLoad(normal, pixel);
    imageStore(history_position, pixel, p);
    imageStore(history_normal, pixel, n);
    if (p.w <= 0.5) {
        imageStore(accumulated, pixel, vec4(0.0));
        imageStore(moments, pixel, vec4(0.0));
        return;
    }
    vec3 c = imageLoad(irradiance, pixel).rgb;
    float l = denoise_luminance(c);

    vec3 history_color = vec3(0.0);
    vec3 history_moments = vec3(0.0);  // m1, m2, n
    float weights = 0.0;
    bool still = false;
    // Where the point was: a moving object's history is found where it was, and the test below
    // (the tap on the point's previous tangent plane) rejects what now stands there instead. The
    // motion is exactly 0 where nothing moved: those pixels reproject as with the camera alone.
    vec3 was = push.has_motion != 0u ? p.xyz + imageLoad(motion, pixel).xyz : p.xyz;
    vec4 clip = push.previous_view_projection * vec4(was, 1.0);
    if (push.has_history != 0u && clip.w > 0.0) {
        // Pixel centres at integers: pixel i covers NDC [2i / W - 1, 2(i + 1) / W - 1].
        vec2 at = (clip.xy / clip.w * 0.5 + 0.5) * vec2(size) - 0.5;
        still = all(lessThanEqual(abs(at - vec2(pixel)), vec2(kStaticPixels)));
        if (still) {
            at = vec2(pixel);  // the pixel itself, weight 1
        }
        ivec2 base = ivec2(floor(at));
        vec2 f = at - vec2(base);
        for (int k = 0; k < 4; ++k) {
            ivec2 offset = ivec2(k & 1, k >> 1);
            ivec2 q = base + offset;
            float bilinear = (offset.x == 1 ? f.x : 1.0 - f.x) * (offset.y == 1 ? f.y : 1.0 - f.y);
            if (bilinear <= 0.0 || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) {
                continue;
            }
            vec4 pq = imageLoad(previous_position, q);
            vec3 nq = imageLoad(previous_normal, q).xyz;
            if (pq.w <= 0.5 || abs(dot(n.xyz, pq.xyz - was)) > push.max_plane_distance ||
                dot(n.xyz, nq) < push.min_normal_cos) {
                continue;
            }
            history_color += bilinear * imageLoad(previous_color, q).rgb;
            history_moments += bilinear * imageLoad(previous_moments, q).xyz;
            weights += bilinear;
        }
    }
    float count = 1.0;
    vec3 out_color = c;
    vec2 out_moments = vec2(l, l * l);
    // A history that only grazes the kept taps (weights ~0) is as good as none: SVGF's threshold.
    if (weights > 0.01) {
        history_color /= weights;
        history_moments /= weights;
        count = floor(history_moments.z + 0.5) + 1.0;
        uint cap = still ? push.static_max_history : push.max_history;
        if (cap != 0u) {
            count = min(count, float(cap));
        }
        float alpha = 1.0 / count;
        out_color = mix(history_color, c, alpha);
        out_moments = mix(history_moments.xy, out_moments, alpha);
    }
    float variance = max(out_moments.y - out_moments.x * out_moments.x, 0.0);
    imageStore(accumulated, pixel, vec4(out_color, variance));
    imageStore(moments, pixel, vec4(out_moments, count, 0.0));
}
