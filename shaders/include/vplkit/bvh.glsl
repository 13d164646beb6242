#ifndef VPLKIT_BVH_GLSL
#define VPLKIT_BVH_GLSL

// Ray queries against the scene's triangle BVH (built on the host, stages/include/vplkit/bvh.hpp,
// or on the device, stages/include/vplkit/stages/bvh_gpu_build.hpp: the same layout),
// for every stage that needs visibility: shadow rays (bvh_occluded), first hits
// (bvh_closest_hit), and the visibility of a segment between two surface points
// (bvh_segment_occluded). Plain compute code, so it runs on every Vulkan device, lavapipe
// included. Helpers for rays that start on surfaces: bvh_hit_position, bvh_triangle_normal,
// bvh_scene_scale, offset_ray_origin.
//
// Including it: define the set-0 binding numbers of the three buffers first,
//     #define VPLKIT_BVH_NODES_BINDING 0
//     #define VPLKIT_BVH_TRIANGLES_BINDING 1
//     #define VPLKIT_BVH_ALPHA_BINDING 4
//     #include "vplkit/bvh.glsl"
// which declares `bvh_nodes`, `bvh_triangles` and `bvh_alpha` (generated Bindings fields of the
// same names; stages::bind_bvh fills them).
//
// Where the nodes and triangles are read: through the `bvh_nodes` and `bvh_triangles` bindings,
// or, for a BVH larger than a binding's range (maxStorageBufferRange: 128 MiB on lavapipe, 4.2M
// nodes or 2.8M triangles), at their buffer device addresses (GL_EXT_buffer_reference), which
// the header in words 0-11 of `bvh_alpha` holds; the specialization constant kBvhAddressed
// (stages::bvh_spec, from BvhBuffers::addressed) picks one, so each pipeline has one path and
// pays nothing for the other. Why not always the addresses: lavapipe (Mesa 22) loads through a
// pointer one component at a time for each lane, where a binding's load fetches a lane's whole
// record at once: tracing took about 2x as long. With kBvhAddressed the bindings stay bound
// (bind_bvh: one record's range) so that a step list still sees which buffers a step reads and
// orders it after the passes that write them.
// Header (vplkit::kBvhHeaderWords words; stages::bvh_header writes it; words 1-11 are read only
// with kBvhAddressed):
//   word 0     the masked subtree's root of a split BVH, 0 for one tree (bvh_masked_root)
//   word 1     how many words the alpha buffer holds, 0 when its address is not in words 8-9
//              (the alpha-test records are then read through the binding)
//   words 2-3  the device address of BvhNode[0] (low word first)
//   words 4-5  the device address of BvhTriangle[0]
//   word 6     how many nodes the node buffer holds, word 7 how many triangles: indices are
//              clamped below them (and alpha words below word 1), so a malformed tree reads
//              wrong records, never outside the buffers (as a binding's range keeps it inside).
//   words 8-9  the device address of the alpha buffer's word 0 (this header's first word): the
//              alpha-test records past a binding's range are read there
//   words 10-11 0
//
// Alpha-tested triangles (glTF MASK and BLEND materials): rays pass through them where the
// G-buffer discards; the records in `bvh_alpha` past its header and the test that reads them
// are in vplkit/bvh_alpha_test.glsl.
//
// Layout. Nodes are 32 bytes, in depth-first order: an interior node's first child is the next
// node and `index` holds its second child; a leaf's `index` is its first triangle and `meta`
// holds kBvhLeafFlag | count (count <= 4, 0 only in the empty scene's single leaf). An
// interior node's `meta` is the axis it was split along: the child on the side the ray comes
// from is visited first. Triangles are stored in leaf order, three vertices each (48 bytes,
// 16-byte aligned rows), with the caller's id. With alpha tests the tree may be split
// (vplkit/bvh.hpp, build_bvh_split): node 0 over an opaque subtree at node 1 and a masked subtree
// at bvh_masked_root(), traversed one after the other (bvh_closest_hit).
//
// Rays. Hits count in the open interval tmin < t < tmax; the direction need not be unit length
// (t is in units of it). tmax = +infinity means unbounded (it becomes kBvhMaxT, the largest
// float). A ray is answered "miss" when its origin, direction or tmin is not finite, its tmax
// is NaN or -infinity, its direction is shorter than kBvhMinDirection in every component, or
// tmin >= tmax. Coordinates must stay below 2^32 in magnitude (the host refuses larger ones):
// then every product in here stays finite.
//
// Numerical robustness, without relying on IEEE infinities or NaNs (Vulkan lets a driver flush
// them and denormals):
// - Slab test: a direction component below kBvhMinDirection is raised to it (sign kept), so
//   1 / d stays finite and there is no 0 * inf. The perturbed ray strays from the true one by at
//   most t * 2^-64, less than the host's box padding of 2^-20 * scene scale for any
//   t < 2^44 * scene scale; the padding also keeps an axis-parallel ray lying exactly in a box
//   face inside the box. The exit distance is widened by 1 + 2 gamma(3) (pbrt-v4, Bounds3::
//   IntersectP) against the rounding of the slab distances of rays from far outside the scene.
// - Triangles: watertight test (Woop, Benthin and Wald 2013, "Watertight Ray/Triangle
//   Intersection", JCGT 2(1)), float only (no double fallback: not every device has
//   shaderFloat64). Rounding is monotonic, so the sign of a float edge function is either exact
//   or 0; an edge function of exactly 0 counts as inside for both triangles that share the edge,
//   whose edge functions are bit-exact negatives (computed from the same projected vertices,
//   with `precise` forbidding FMA contraction). A ray through an edge or a vertex therefore hits
//   at least one of the triangles around it, never none; it may hit two, at about the same t.
//
// Self-intersection (origins on surfaces): offset_ray_origin below, after Wachter and Binder,
// "A Fast and Robust Method for Avoiding Self-Intersection" (Ray Tracing Gems, 2019, ch. 6).

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#if !defined(VPLKIT_BVH_NODES_BINDING) || !defined(VPLKIT_BVH_TRIANGLES_BINDING) || !defined(VPLKIT_BVH_ALPHA_BINDING)
#error "define VPLKIT_BVH_NODES_BINDING, VPLKIT_BVH_TRIANGLES_BINDING and VPLKIT_BVH_ALPHA_BINDING before including vplkit/bvh.glsl"
#endif

struct BvhNode {
    vec3 lo;     // box, padded outward by the host (see above)
    uint index;  // interior: the second child; leaf: the first triangle
    vec3 hi;
    uint meta;   // interior: split axis 0..2; leaf: kBvhLeafFlag | triangle count
};

struct BvhTriangle {
    vec3 v0;
    uint id;     // the caller's id for this triangle (its input index unless ids were given)
    vec3 v1;
    uint alpha;  // 0: opaque; else its record's offset in bvh_alpha (see above)
    vec3 v2;
};

layout(std430, set = 0, binding = VPLKIT_BVH_NODES_BINDING) readonly buffer BvhNodeBuffer {
    BvhNode items[];
} bvh_nodes;

layout(std430, set = 0, binding = VPLKIT_BVH_TRIANGLES_BINDING) readonly buffer BvhTriangleBuffer {
    BvhTriangle items[];
} bvh_triangles;

layout(std430, set = 0, binding = VPLKIT_BVH_ALPHA_BINDING) readonly buffer BvhAlphaBuffer {
    uint words[];
} bvh_alpha;

// Whether nodes and triangles (and alpha-test records, when word 1 says where) are read at the
// header's addresses instead of through their bindings (see the top of this file);
// stages::bvh_spec sets it from BvhBuffers::addressed.
layout(constant_id = 24) const uint kBvhAddressed = 0u;

// The same records at the addresses in the header (kBvhAddressed).
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer BvhNodeArray {
    BvhNode items[];
};

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer BvhTriangleArray {
    BvhTriangle items[];
};

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer BvhAlphaWordArray {
    uint words[];
};

// Word i of the alpha buffer: at the header's address with kBvhAddressed (when word 1 gives it;
// clamped below it), else through the binding.
uint bvh_alpha_word(uint i) {
    if (kBvhAddressed != 0u && bvh_alpha.words[1] != 0u) {
        BvhAlphaWordArray words = BvhAlphaWordArray(uvec2(bvh_alpha.words[8], bvh_alpha.words[9]));
        return words.words[min(i, bvh_alpha.words[1] - 1u)];
    }
    return bvh_alpha.words[i];
}

// Equals vplkit::kBvhMaxDepth: the host builds no leaf deeper than this, and the traversal
// pushes at most one node per level of the path it is on, so the stack never overflows for a
// BVH from build_bvh. A foreign, deeper tree would have subtrees skipped, never memory
// written out of bounds.
const uint kBvhStackSize = 32u;
const uint kBvhLeafFlag = 0x80000000u;
const uint kBvhCountMask = 0x7fffffffu;
const uint kBvhNoHit = 0xffffffffu;
// 2^-64: |1 / d| <= 2^64, so (coordinate difference < 2^33) * (1 / d) < 2^97 stays finite.
const float kBvhMinDirection = 5.421010862427522e-20;
// 1 + 2 gamma(3), gamma(n) = n u / (1 - n u), u = 2^-24 (pbrt-v4, Bounds3::IntersectP).
const float kBvhExitWiden = 1.0000004;
// offset_ray_origin: 2^-16, i.e. 128 to 256 float ulps of max(scene scale, |p|) (Wachter and
// Binder offset by 256 ulps).
const float kBvhOriginOffset = 1.52587890625e-5;
// Floor of the scene scale, so a point at the origin of an empty scene still moves.
const float kBvhMinScale = 1e-30;
// The largest float: what tmax = +infinity becomes.
const float kBvhMaxT = 3.4028234663852886e38;

struct BvhHit {
    float t;            // tmax when nothing was hit (kBvhMaxT for tmax = +infinity)
    uint id;            // BvhTriangle.id, kBvhNoHit when nothing was hit
    vec2 barycentrics;  // weights of v1 and v2: p = (1 - b.x - b.y) v0 + b.x v1 + b.y v2
    uint triangle;      // index into bvh_triangles (leaf order), kBvhNoHit when nothing was hit
};

// A ray as stages store it in buffers (32 bytes). Hits count for tmin < t < tmax.
struct BvhRay {
    vec3 origin;
    float tmin;
    vec3 direction;  // any length: t is in units of it
    float tmax;
};

// Everything the traversal derives from a ray once.
struct BvhRayState {
    vec3 origin;
    vec3 direction;
    vec3 inv_direction;  // 1 / direction with tiny components raised to kBvhMinDirection
    ivec3 axes;          // kx, ky, kz: kz the largest |direction| component (Woop et al. sec. 3)
    vec3 shear;          // Sx, Sy, Sz (Woop et al. sec. 3)
    vec3 origin_k;       // origin permuted to (kx, ky, kz)
};

bool bvh_finite(vec3 v) {
    return !any(isnan(v)) && !any(isinf(v));
}

// tmax after bvh_bounded_tmax.
bool bvh_ray_valid(vec3 origin, vec3 direction, float tmin, float tmax) {
    return bvh_finite(origin) && bvh_finite(direction) && !isnan(tmin) && !isinf(tmin) && !isnan(tmax) &&
           !isinf(tmax) && tmin < tmax && max(max(abs(direction.x), abs(direction.y)), abs(direction.z)) >= kBvhMinDirection;
}

float bvh_bounded_tmax(float tmax) {
    return (isinf(tmax) && tmax > 0.0) ? kBvhMaxT : tmax;
}

vec3 bvh_permute(vec3 v, ivec3 axes) {
    return vec3(v[axes.x], v[axes.y], v[axes.z]);
}

BvhRayState bvh_make_ray(vec3 origin, vec3 direction) {
    BvhRayState ray;
    ray.origin = origin;
    ray.direction = direction;
    vec3 safe = mix(vec3(kBvhMinDirection), abs(direction), greaterThanEqual(abs(direction), vec3(kBvhMinDirection)));
    // A zero component, +0.0 or -0.0, becomes +kBvhMinDirection: which side does not matter, the
    // box padding covers both.
    safe *= mix(vec3(1.0), vec3(-1.0), lessThan(direction, vec3(0.0)));
    ray.inv_direction = 1.0 / safe;

    vec3 a = abs(direction);
    int kz = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    // Woop et al. sec. 3: swap kx and ky when direction[kz] < 0, so the winding (and with it the
    // sign of the edge functions) does not depend on which way the ray points.
    if (direction[kz] < 0.0) {
        int swap = kx;
        kx = ky;
        ky = swap;
    }
    ray.axes = ivec3(kx, ky, kz);
    float dz = direction[kz];
    ray.shear = vec3(direction[kx] / dz, direction[ky] / dz, 1.0 / dz);
    ray.origin_k = bvh_permute(origin, ray.axes);
    return ray;
}

// Whether the ray meets the box somewhere in [tmin, tmax].
bool bvh_box_hit(BvhRayState ray, vec3 lo, vec3 hi, float tmin, float tmax) {
    vec3 t0 = (lo - ray.origin) * ray.inv_direction;
    vec3 t1 = (hi - ray.origin) * ray.inv_direction;
    vec3 near = min(t0, t1);
    vec3 far = max(t0, t1);
    float enter = max(max(near.x, near.y), max(near.z, tmin));
    float exit = min(min(far.x, far.y), far.z) * kBvhExitWiden;
    return enter <= min(exit, tmax);
}

// Woop, Benthin and Wald 2013, sec. 3 (float version, see the top of this file). On a hit with
// tmin < t < tmax: true, t, and the barycentric weights of v1 and v2.
bool bvh_intersect_triangle(BvhRayState ray, BvhTriangle tri, float tmin, float tmax, out float t, out vec2 barycentrics) {
    // Vertices relative to the origin, permuted to (kx, ky, kz).
    vec3 a = bvh_permute(tri.v0, ray.axes) - ray.origin_k;
    vec3 b = bvh_permute(tri.v1, ray.axes) - ray.origin_k;
    vec3 c = bvh_permute(tri.v2, ray.axes) - ray.origin_k;
    // Shear into ray space, where the ray is the +z axis from (0, 0, 0). A vertex shared by two
    // triangles is projected by the same operations on the same floats: bit-identical results.
    precise float ax = a.x - ray.shear.x * a.z;
    precise float ay = a.y - ray.shear.y * a.z;
    precise float bx = b.x - ray.shear.x * b.z;
    precise float by = b.y - ray.shear.y * b.z;
    precise float cx = c.x - ray.shear.x * c.z;
    precise float cy = c.y - ray.shear.y * c.z;
    // 2D edge functions (twice the signed areas of (origin, edge)); u belongs to v0, v to v1, w to v2.
    precise float u = cx * by - cy * bx;
    precise float v = ax * cy - ay * cx;
    precise float w = bx * ay - by * ax;
    // Outside when the signs differ; a zero edge function agrees with either sign (watertight).
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) {
        return false;
    }
    float det = u + v + w;
    // A zero determinant: the ray lies in the triangle's plane, or the triangle projects to a line.
    if (det == 0.0) {
        return false;
    }
    float scaled_t = u * (ray.shear.z * a.z) + v * (ray.shear.z * b.z) + w * (ray.shear.z * c.z);
    float hit_t = scaled_t / det;
    if (!(hit_t > tmin && hit_t < tmax)) {
        return false;
    }
    t = hit_t;
    barycentrics = vec2(v, w) / det;
    return true;
}

#include "vplkit/bvh_alpha_test.glsl"

BvhHit bvh_no_hit(float tmax) {
    BvhHit hit;
    hit.t = tmax;
    hit.id = kBvhNoHit;
    hit.barycentrics = vec2(0.0);
    hit.triangle = kBvhNoHit;
    return hit;
}

// The header's addresses and record counts, read once per ray (only with kBvhAddressed).
struct BvhArrays {
    BvhNodeArray nodes;
    BvhTriangleArray triangles;
    uint last_node;  // the last node and triangle the buffers hold
    uint last_triangle;
};

BvhArrays bvh_arrays() {
    BvhArrays arrays;
    if (kBvhAddressed != 0u) {
        arrays.nodes = BvhNodeArray(uvec2(bvh_alpha.words[2], bvh_alpha.words[3]));
        arrays.triangles = BvhTriangleArray(uvec2(bvh_alpha.words[4], bvh_alpha.words[5]));
        arrays.last_node = max(bvh_alpha.words[6], 1u) - 1u;
        arrays.last_triangle = max(bvh_alpha.words[7], 1u) - 1u;
    }
    return arrays;
}

BvhNode bvh_node(BvhArrays arrays, uint index) {
    if (kBvhAddressed != 0u) {
        return arrays.nodes.items[min(index, arrays.last_node)];
    }
    return bvh_nodes.items[index];
}

BvhTriangle bvh_triangle(BvhArrays arrays, uint index) {
    if (kBvhAddressed != 0u) {
        return arrays.triangles.items[min(index, arrays.last_triangle)];
    }
    return bvh_triangles.items[index];
}

// Hits with tmin < t < hit.t in the subtree at `root`. Closest hit (any_hit false): the nearest
// goes into `hit`, hit.t shrinking as hits are found so that boxes behind them are skipped.
// Any hit (a shadow ray): returns true at the first hit found, in no particular order; false
// means none. `alpha_tests` and `any_hit` are constants at every call: after inlining, the code
// of the other case is compiled out of the loop (a runtime flag would cost every iteration:
// lavapipe runs both sides of a branch when its lanes disagree).
bool bvh_traverse(BvhRayState ray, uint root, float tmin, bool alpha_tests, bool any_hit, inout BvhHit hit) {
    BvhArrays arrays = bvh_arrays();
    uint stack[kBvhStackSize];
    uint depth = 0u;
    uint node_index = root;
    while (true) {
        BvhNode node = bvh_node(arrays, node_index);
        if (bvh_box_hit(ray, node.lo, node.hi, tmin, hit.t)) {
            if ((node.meta & kBvhLeafFlag) != 0u) {
                uint end = node.index + (node.meta & kBvhCountMask);
                for (uint i = node.index; i < end; ++i) {
                    float t;
                    vec2 barycentrics;
                    BvhTriangle tri = bvh_triangle(arrays, i);
                    if (bvh_intersect_triangle(ray, tri, tmin, hit.t, t, barycentrics) &&
                        (!alpha_tests || bvh_alpha_passes(tri, barycentrics))) {
                        if (any_hit) {
                            return true;
                        }
                        hit.t = t;
                        hit.id = tri.id;
                        hit.barycentrics = barycentrics;
                        hit.triangle = i;
                    }
                }
            } else {
                // Near child first, so that a closest-hit ray's hit.t shrinks early and prunes
                // the far one.
                uint first = node_index + 1u;
                uint second = node.index;
                bool backwards = ray.direction[node.meta] < 0.0;
                if (depth < kBvhStackSize) {
                    stack[depth++] = backwards ? first : second;
                }
                node_index = backwards ? second : first;
                continue;
            }
        }
        if (depth == 0u) {
            break;
        }
        node_index = stack[--depth];
    }
    return false;
}

// The root of the masked subtree of a split BVH (vplkit/bvh.hpp: node 1 is then the root of the
// opaque subtree, whose triangles have no alpha record), or 0 when the tree is not split. It is word 0
// of bvh_alpha's header (see the top of this file); read only with kBvhAlphaTest.
uint bvh_masked_root() {
    return bvh_alpha.words[0];
}

// The nearest hit with tmin < t < tmax (see BvhHit for a miss).
// With alpha tests, a split BVH is traversed twice: the opaque subtree with the alpha test
// compiled out of its loop, then the masked subtree, with it, up to the opaque hit. Why two
// loops: lavapipe runs a branch in a loop under a lane mask whether or not a lane takes it, and
// a loop ends when every lane is done, so the alpha code is paid only in the iterations spent in
// the (small) masked subtree instead of in every iteration (Sponza: vplkit/bvh.hpp).
BvhHit bvh_closest_hit(vec3 origin, vec3 direction, float tmin, float tmax) {
    tmax = bvh_bounded_tmax(tmax);
    BvhHit hit = bvh_no_hit(tmax);
    if (!bvh_ray_valid(origin, direction, tmin, tmax)) {
        return hit;
    }
    BvhRayState ray = bvh_make_ray(origin, direction);
    if (bvh_has_alpha_tests()) {
        uint masked_root = bvh_masked_root();
        if (masked_root != 0u) {
            bvh_traverse(ray, 1u, tmin, false, false, hit);
        }
        // Not split: the whole tree from node 0, every triangle with a record tested.
        bvh_traverse(ray, masked_root, tmin, true, false, hit);
    } else {
        bvh_traverse(ray, 0u, tmin, false, false, hit);
    }
    return hit;
}

BvhHit bvh_closest_hit(BvhRay ray) {
    return bvh_closest_hit(ray.origin, ray.direction, ray.tmin, ray.tmax);
}

// Whether the subtree at `root` has a hit with tmin < t < tmax. `alpha_tests`: as in
// bvh_traverse.
bool bvh_occluded_in(BvhRayState ray, uint root, float tmin, float tmax, bool alpha_tests) {
    BvhHit hit = bvh_no_hit(tmax);
    return bvh_traverse(ray, root, tmin, alpha_tests, true, hit);
}

// Whether anything lies between tmin and tmax (exclusive) on the ray: a shadow ray. Stops at
// the first hit found, in no particular order. A split BVH (see bvh_closest_hit): the opaque
// subtree first, the masked one only for rays it did not stop.
bool bvh_occluded(vec3 origin, vec3 direction, float tmin, float tmax) {
    tmax = bvh_bounded_tmax(tmax);
    if (!bvh_ray_valid(origin, direction, tmin, tmax)) {
        return false;
    }
    BvhRayState ray = bvh_make_ray(origin, direction);
    if (bvh_has_alpha_tests()) {
        uint masked_root = bvh_masked_root();
        if (masked_root != 0u && bvh_occluded_in(ray, 1u, tmin, tmax, false)) {
            return true;
        }
        return bvh_occluded_in(ray, masked_root, tmin, tmax, true);
    }
    return bvh_occluded_in(ray, 0u, tmin, tmax, false);
}

bool bvh_occluded(BvhRay ray) {
    return bvh_occluded(ray.origin, ray.direction, ray.tmin, ray.tmax);
}

// The scene scale: the largest coordinate magnitude of the root box, which bounds every vertex
// and so every distance an intersection's rounding is relative to.
float bvh_scene_scale() {
    BvhNode root = bvh_node(bvh_arrays(), 0u);
    vec3 m = max(abs(root.lo), abs(root.hi));
    return max(max(m.x, m.y), max(m.z, kBvhMinScale));
}

// Geometric normal of a triangle (unnormalized: twice its area; the winding v0 -> v1 -> v2 is
// counter-clockwise seen from the side it points to).
vec3 bvh_triangle_normal(uint triangle) {
    BvhTriangle tri = bvh_triangle(bvh_arrays(), triangle);
    return cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
}

// The hit point from the barycentrics: accurate to a few ulps of the vertex coordinates, where
// origin + t * direction carries the error of t times the ray length (Wachter and Binder sec. 6.2).
vec3 bvh_hit_position(BvhHit hit) {
    BvhTriangle tri = bvh_triangle(bvh_arrays(), hit.triangle);
    return (1.0 - hit.barycentrics.x - hit.barycentrics.y) * tri.v0 + hit.barycentrics.x * tri.v1 +
           hit.barycentrics.y * tri.v2;
}

// Moves a point p on a surface off it, to the side the geometric normal n points to (unit
// length or not), so that a ray leaving p on that side cannot hit the surface it starts on.
// Policy: p + n_unit * 2^-16 * max(scale, |p|_max), scale = bvh_scene_scale().
// Why this distance: a hit point (bvh_hit_position) is off by a few ulps of its coordinates, and
// the watertight test rounds relative to the vertex coordinates, both bounded by
// ulp(max(scale, |p|)) = 2^-23 * that; 2^-16 leaves a margin of 128 (Wachter and Binder add 256
// ulps). Their method offsets each coordinate by 256 of its own ulps, with a fixed 1/65536
// near the world origin: absolute, which is 1.5% of a 1e-3-sized scene and would hide nearby
// occluders there. Tying the offset to the scene scale instead makes it the same fraction
// (1.5e-5) of any scene: occluders farther than that from the surface are never missed.
// A shadow ray towards a point q on another surface stops short of it the same way: offset q
// too (along its own normal), and trace origin o' towards q' with direction q' - o', tmax = 1
// (bvh_segment_occluded does exactly that). n must not be zero.
// What it cannot do: move p off a second surface it also lies on (a point on the edge where a
// wall meets the ceiling is on both planes, within rounding; moving along one normal leaves it
// on the other, and a ray into the room may meet that one at t ~ 0). G-buffer points therefore
// arrive already moved toward the viewer, in front of both (gbuffer_shade.frag); hit points of
// light paths lie on an edge only with probability ~0.
vec3 offset_ray_origin(vec3 p, vec3 n, float scale) {
    vec3 m = abs(p);
    float h = kBvhOriginOffset * max(max(scale, kBvhMinScale), max(max(m.x, m.y), m.z));
    return p + normalize(n) * h;
}

// Whether anything blocks the segment between surface point p and point q: the visibility term
// between a shading point and a VPL or a light. np is p's geometric normal oriented to the side
// the segment leaves p on (a caller with two-sided surfaces flips it when q lies behind); nq is
// q's, oriented to the side facing p, or vec3(0) when q is not on a surface (a point light).
// Both ends are moved off their surfaces with offset_ray_origin, then one shadow ray goes from
// p' to q' with tmax = 1, so neither surface the segment ends on can block it.
bool bvh_segment_occluded(vec3 p, vec3 np, vec3 q, vec3 nq, float scale) {
    vec3 origin = offset_ray_origin(p, np, scale);
    vec3 target = dot(nq, nq) > 0.0 ? offset_ray_origin(q, nq, scale) : q;
    return bvh_occluded(origin, target - origin, 0.0, 1.0);
}

#endif
