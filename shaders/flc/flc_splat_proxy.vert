#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// Forward light cuts, splatting (the FLC paper sec. 5), vertex stage: instance i is kept VPL i, drawn
// as the screen-space rectangle that bounds its support, so the fragment stage runs only where
// the VPL can light something. A level-k VPL at y (normal n) lights x only where
// d(x) = |x - y|^2 / <n, x - y> < D_{k+1} (eq. 14): the level set d = R is the sphere through y
// centred at y + n R / 2, so the support is that ball, of radius R / 2. The rectangle is the
// projection of the ball's bounding cube (its 8 corners), one pixel wider on each side so that a
// receiver inside the ball always has its pixel centre inside; the whole screen when a corner is
// behind the eye, and for the last level, whose support is the whole half-space in front of its
// triangle (flc_partition.glsl: f~^N stays 1 beyond D_N). (The paper's far levels are crescents, the ball less the sphere
// d = D_{k-1}; the fragment stage's f~^k is 0 there, so a ball is a bounded, conservative proxy.)
// A VPL with no light, no normal or a non-finite field draws nothing (a degenerate rectangle).
//
// Interleaved sub-tiles (sec. 6, subtiles = n > 1): the target holds n x n sub-images, sub-tile
// (a, b) the pixels x = u n + a, y = v n + b at (a w + u, b h + v) (w x h the sub-tile size). VPL i
// is drawn into sub-tile i mod n^2 only, its rectangle mapped there and clamped to it: each
// sub-tile sees 1/n^2 of the VPLs at 1/n^2 of the pixels (flc_untile.comp puts them back).

#include "vplkit/flc_candidate.glsl"
#include "vplkit/flc_partition.glsl"
#include "vplkit/vpl.glsl"

layout(std430, set = 0, binding = 0) readonly buffer FlcCandidateBuffer { FlcCandidate items[]; } candidates;
layout(std430, set = 0, binding = 1) readonly buffer KeptTriangleBuffer { uint items[]; } kept_triangles;
layout(std430, set = 0, binding = 2) readonly buffer VplBuffer { Vpl items[]; } vpls;

layout(push_constant) uniform FlcSplatPush {
    mat4 view_projection;  // world -> Vulkan clip space (the G-buffer's camera)
    vec3 camera_position;
    float scene_scale;     // for vpl_min_distance, as exact_gi.comp clamps 1/d^2
    uvec2 image_size;      // the G-buffer's
    uvec2 subtile_size;    // ceil(image_size / subtiles): the target is subtiles x that
    uint subtiles;         // n: n x n interleaved sub-tiles (1: off)
    uint level_count;
    float d0;
    float mu;
} push;

layout(location = 0) flat out vec3 vpl_position;
layout(location = 1) flat out vec3 vpl_normal;
layout(location = 2) flat out vec3 vpl_flux;
layout(location = 3) flat out int vpl_level;

bool finite3(vec3 v) {
    return !any(isnan(v)) && !any(isinf(v));
}

void main() {
    uint i = uint(gl_InstanceIndex);
    Vpl vpl = vpls.items[i];
    int level = candidates.items[kept_triangles.items[i]].level;
    vpl_position = vpl.position;
    vpl_normal = vpl.normal;
    vpl_flux = vpl.flux;
    vpl_level = level;

    // Outside the screen, zero area: nothing is rasterized.
    gl_Position = vec4(-2.0, -2.0, 0.0, 1.0);
    int last = int(push.level_count) - 1;
    if (level < 0 || level > last || !finite3(vpl.position) || !finite3(vpl.normal) || !finite3(vpl.flux) ||
        all(equal(vpl.flux, vec3(0.0))) || dot(vpl.normal, vpl.normal) == 0.0) {
        return;
    }
    float reach = flc_influence_distance(min(level + 1, last), push.d0, push.mu);
    float radius = 0.5 * reach;
    vec3 centre = vpl.position + vpl.normal * radius;
    vec2 lo = vec2(0.0), hi = vec2(0.0);
    bool whole_screen = level == last;
    for (int c = 0; c < 8 && !whole_screen; ++c) {
        vec3 corner = centre + radius * vec3((c & 1) != 0 ? 1.0 : -1.0, (c & 2) != 0 ? 1.0 : -1.0,
                                             (c & 4) != 0 ? 1.0 : -1.0);
        vec4 clip = push.view_projection * vec4(corner, 1.0);
        if (!(clip.w > 0.0)) {
            whole_screen = true;
            break;
        }
        vec2 ndc = clip.xy / clip.w;
        lo = c == 0 ? ndc : min(lo, ndc);
        hi = c == 0 ? ndc : max(hi, ndc);
    }
    uint n = push.subtiles;
    uint s = i % (n * n);
    vec2 tile = vec2(float(s % n), float(s / n));
    vec2 size = vec2(push.subtile_size);
    vec2 region_lo = tile * size, region_hi = region_lo + size;  // the sub-tile, in target pixels
    vec2 t_lo = region_lo, t_hi = region_hi;
    if (!whole_screen) {
        // In image pixels, one pixel wider; image pixel x = u n + a (centre x + 0.5) sits at target
        // centre a w + u + 0.5, so the rectangle maps by (x - 0.5 - a) / n + 0.5, one target pixel wider.
        vec2 image = vec2(push.image_size);
        vec2 p_lo = (lo * 0.5 + 0.5) * image - 1.0;
        vec2 p_hi = (hi * 0.5 + 0.5) * image + 1.0;
        t_lo = max(region_lo + (p_lo - 0.5 - tile) / float(n) - 0.5, region_lo);
        t_hi = min(region_lo + (p_hi - 0.5 - tile) / float(n) + 1.5, region_hi);
        if (any(greaterThanEqual(t_lo, t_hi))) {
            return;  // off screen
        }
    }
    vec2 target = float(n) * size;
    // Two triangles: (0,0) (1,0) (0,1), (1,0) (1,1) (0,1).
    const vec2 corners[6] = vec2[6](vec2(0, 0), vec2(1, 0), vec2(0, 1), vec2(1, 0), vec2(1, 1), vec2(0, 1));
    gl_Position = vec4(mix(t_lo, t_hi, corners[gl_VertexIndex % 6]) / target * 2.0 - 1.0, 0.0, 1.0);
}
