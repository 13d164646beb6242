#version 460
#extension GL_GOOGLE_include_directive : require
// Indirect light by the `hybrid` method (the thesis ch. 5): each pixel blends the shallow cuts of
// the four blocks around it (Alg. 1: bilinear x geometric-similarity weights; one cut drawn per
// pixel, where Alg. 1 draws one per slot: see main), or takes the mock cut when none of the four
// is similar; from every node of its cut it traverses the SST with the expected-contribution
// weights (eqs. 5.2, 5.4; mixed with box-distance weights: sst_defensive_probability), stopping
// early at suitable nodes (eq. 5.6) far enough from the pixel (sst_substitute_far_enough), and
// evaluates the node reached with one shadow ray: a leaf as its VPL, a suitable node by one of
// its VPLs drawn by intensity (hybrid_add_cluster_sample, where sec. 5.3 evaluates the node's
// Gaussian substitute: see there why). The pixel's estimate is the sum over its cut's nodes. The
// specialization constant kTraversal swaps the traversal for rtslc's to a leaf (sec. 7.1's
// comparison protocol), with rtslc's one-sample MIS over the lobes on glossy receivers
// (sst_traverse_lightcuts_lobe_mis), and hybrid_cut.comp then splits the cuts by rtslc's bound.
// With kGlossyLobe (gi_lobe.glsl), a glossy receiver picks the diffuse or the glossy lobe per cut
// node's traversal (the SST paper sec. 4.2); the cut itself, shared by the block, is chosen for
// the whole BRDF, and the node's share of the estimate is weighed by the probability of the lobe
// it was sampled in.
//
// indirect.rgb: the estimate; indirect.a: the pixel's dropped samples. Background pixels: 0.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 12
#define VPLKIT_SST_NODES_BINDING 6
#define VPLKIT_SST_LEAVES_BINDING 7
#define VPLKIT_GI_COUNTERS_BINDING 11
#include "vplkit/bvh.glsl"
#include "vplkit/brdf.glsl"
#include "vplkit/gbuffer.glsl"
#include "vplkit/geometric_similarity.glsl"
#include "vplkit/rng.glsl"
#include "vplkit/vpl.glsl"
#include "vplkit/vpl_eval.glsl"
#include "vplkit/gi_bounds.glsl"
#include "vplkit/gi_counters.glsl"
#include "vplkit/gi_evaluate.glsl"
#include "vplkit/gi_lobe.glsl"
#include "vplkit/sst.glsl"
#include "vplkit/sst_sampling.glsl"
#include "vplkit/sst_evaluate.glsl"
#include "vplkit/light_tree.glsl"
#include "vplkit/rtslc.glsl"
#include "vplkit/sst_lightcuts_traversal.glsl"
#include "vplkit/cut_blending.glsl"
#include "vplkit/hybrid_traversal.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 2, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D gbuffer_normal;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D gbuffer_geometric_normal;
layout(set = 0, binding = 5, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(std430, set = 0, binding = 8) readonly buffer HybridBlockBuffer { HybridBlock items[]; } blocks;
layout(std430, set = 0, binding = 9) readonly buffer HybridCutBuffer { uint items[]; } cuts;
layout(set = 0, binding = 10, rgba32f) uniform writeonly image2D indirect;

layout(push_constant) uniform HybridGiPush {
    vec3 camera_position;
    uint block_size;
    uint blocks_x;
    uint blocks_y;
    uint cut_size;
    uint leaf_count;
    uint vpl_count;
    uint seed;
    uint frame;            // decorrelates frames: one stream per (seed, frame, pixel)
    uint visibility;       // 0: no shadow rays (tests)
    float min_cos;         // eq. 5.3 thresholds for blending
    float max_distance;
    uint mock_cuts;        // 0: a pixel with no similar block traverses from the root instead (ch. 7.3's comparison)
} push;

// The traversal below a cut node: the thesis' (expected-contribution weights, early stop at a
// suitable node, its substitute), or stochastic lightcuts' to a leaf (sec. 7.1's protocol). A
// specialization constant: the comparison's branch costs the default pipeline nothing.
const uint kHybridTraversalSubstitute = 0u;
const uint kHybridTraversalLightcuts = 1u;
layout(constant_id = 0) const uint kTraversal = kHybridTraversalSubstitute;

// The light of the node a traversal stopped at, added to `total` with one shadow ray. A leaf is
// its VPL. A suitable inner node is estimated by one of its VPLs, drawn with probability its
// intensity / the node's (sst_leaf_by_intensity) and weighed by the inverse: the VPL's flux x
// node intensity / its intensity, over the path probability. That is unbiased for the node's
// light, and it keeps what made the early stop worth it: below the suitable node the descent
// reads intensities only, with no shading-point weights (the receiver is at least the node's
// extent away, sst_substitute_far_enough, where those weights barely differ between its VPLs).
// Why not the thesis' Gaussian substitute (sec. 5.3, as `sst` keeps it): its shadow ray must go
// to a real VPL (sst_shadow_target says why), and a position drawn from the Gaussian lit through
// the visibility of an independently drawn VPL loses the correlation between where a VPL is and
// whether it is seen; that, not the blur, was most of hybrid's converged residue
// (tests/gi/test_hybrid_residue.cpp: 256 frames' 4 x 4-block error 1.97x rtslc's with the
// substitute, 1.55x with it only 3 extents away from x, 1.17x at 3 extents without shadows;
// 1.21x this way, as hybrid-lightcuts' 1.19x). Evaluating the substitute at the drawn VPL with
// the node's summed colour instead keeps the colour blur: 1.37x (the VPLs' colours differ).
void hybrid_add_cluster_sample(GiPoint p, HybridSample s, uint lobe, float min_distance, float scale, inout Rng rng,
                               inout vec3 total, inout uint dropped) {
    Vpl light;
    if (sst_is_leaf(s.node, push.leaf_count)) {
        light = sst_leaves.items[push.leaf_count == 1u ? 0u : sst_leaf_index(s.node, push.leaf_count)];
        light.flux /= s.probability;
    } else {
        uint leaf = sst_leaf_by_intensity(s.node, push.leaf_count, push.vpl_count, rng);
        light = sst_leaves.items[sst_leaf_index(leaf, push.leaf_count)];
        float intensity = sst_intensity(light.flux);
        if (!(intensity > 0.0)) {
            return;  // drawn only when the whole node is dark (both children 0): no light
        }
        light.flux *= s.intensity / (intensity * s.probability);
    }
    gi_add_sample(p.position, p.normal, p.geometric_normal, p.wo, p.albedo, p.roughness, p.metallic, lobe, light,
                  light.position, light.normal, min_distance, scale, push.visibility != 0u, total, dropped);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(indirect);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec4 position = imageLoad(gbuffer_position, pixel);
    if (position.w <= 0.5) {
        imageStore(indirect, pixel, vec4(0.0));
        return;
    }
    GbufferSample g = gbuffer_decode(position, imageLoad(gbuffer_normal, pixel),
                                     imageLoad(gbuffer_geometric_normal, pixel), imageLoad(gbuffer_albedo, pixel),
                                     vec4(0.0));
    GiPoint p = GiPoint(g.position, g.normal, g.geometric_normal, normalize(push.camera_position - g.position),
                        g.albedo, g.roughness, g.metallic);
    float scale = bvh_scene_scale();
    float min_distance = vpl_min_distance(scale);
    Rng rng = rng_create(pcg_hash(push.seed ^ pcg_hash(push.frame)), uint(pixel.y * size.x + pixel.x));

    ivec2 neighbour_block[4];
    float bilinear[4];
    cut_blend_neighbours(pixel, push.block_size, ivec2(push.blocks_x, push.blocks_y), neighbour_block, bilinear);
    HybridBlock neighbour[4];
    uint neighbour_index[4];
    for (int k = 0; k < 4; ++k) {
        neighbour_index[k] = uint(neighbour_block[k].y) * push.blocks_x + uint(neighbour_block[k].x);
        neighbour[k] = blocks.items[neighbour_index[k]];
    }
    float weight[4];
    bool blended = cut_blend_weights(p.position, p.normal, neighbour, bilinear, push.min_cos, push.max_distance, weight);
    uint mock_level = mock_cut_level(push.cut_size, push.leaf_count);
    bool mock = !blended && push.mock_cuts != 0u;
    uint slots = mock ? (1u << mock_level) : push.cut_size;
    // Alg. 1 line 8 draws one of the four cuts for every slot i by the blending weights. Here one
    // cut is drawn for the whole pixel, by the same weights, and all its slots are traversed: each
    // cut covers every VPL with light once, so the estimate's mean is the same (sum_k weight[k] x
    // cut k's light = the tree's light) and the blocks still blend, pixel by pixel, in the mean;
    // but the slots of one cut never overlap nor leave gaps, where slot i of one cut and slot j
    // of another cover the same VPLs or none of some (the cuts differ in depth and length), a
    // variance per-slot choices add (tests/gi/test_hybrid_residue.cpp: 64 frames' 4 x 4-block
    // error of hybrid-lightcuts 1.9x rtslc's per slot, 1.4x per pixel). The per-slot draw also
    // had to say what a cut shorter than slot i gives: it renormalized over the cuts that have a
    // slot i, which counted a longer cut's extra slots in full on top of a shorter cut's light.
    int chosen = -1;
    if (blended) {
        float u = rng_next_float(rng);
        for (int k = 0; k < 4; ++k) {
            if (weight[k] > 0.0) {
                chosen = k;  // the last weighted one also takes u's rounding at the top
                if (u < weight[k]) {
                    break;
                }
                u -= weight[k];
            }
        }
        slots = neighbour[chosen].cut_size;
    }

    vec3 total = vec3(0.0);
    uint dropped = 0u, traversals = 0u, levels = 0u, dead = 0u;
    bool completed = false;  // the sentinel of exact_gi.comp: lavapipe's silent loop limit
    for (uint i = 0u; i <= slots; ++i) {
        if (i == slots) {
            completed = true;
            break;
        }
        uint start;
        if (blended) {
            start = cuts.items[neighbour_index[chosen] * push.cut_size + i];
        } else if (mock) {
            // Alg. 1 lines 11-14: the mock cut.
            start = (1u << mock_level) - 1u + i;
        } else {
            // Without mock cuts, the alternative the thesis compares them with: every sample from
            // the root, averaged (each is an estimate of the whole tree).
            start = 0u;
        }
        if (mock && sst_fetch(start, push.leaf_count, push.vpl_count).leaf_count == 0u) {
            continue;  // a padding node of the mock cut (a blended cut holds none)
        }
        GiLobe lobe = gi_choose_lobe(p.normal, p.wo, p.albedo, p.roughness, p.metallic, rng);
        HybridSample s;
        uint evaluated_lobe = lobe.kind;
        if (kTraversal == kHybridTraversalLightcuts && lobe.kind != kBrdfLobeBoth) {
            // rtslc's lobe MIS (rtslc_gi.comp's default): the whole BRDF over the lobes' mixture pmf.
            float q_glossy = lobe.kind == kBrdfLobeGlossy ? lobe.probability : 1.0 - lobe.probability;
            s = hybrid_sample_of(sst_traverse_lightcuts_lobe_mis(p, start, push.leaf_count, push.vpl_count, lobe,
                                                                 q_glossy, min_distance, rng));
            evaluated_lobe = kBrdfLobeBoth;
        } else if (kTraversal == kHybridTraversalLightcuts) {
            s = hybrid_sample_of(
                sst_traverse_lightcuts(p, start, push.leaf_count, push.vpl_count, lobe, min_distance, rng));
        } else if (lobe.kind == kBrdfLobeGlossy) {
            s = hybrid_sample_of(sst_traverse(p, start, push.leaf_count, push.vpl_count, kSstWeightExpected, lobe,
                                              min_distance, rng));
        } else {
            s = hybrid_traverse(p, start, push.leaf_count, push.vpl_count, lobe, min_distance, rng);
        }
        ++traversals;
        levels += s.levels;
        if (s.dead) {
            ++dead;
            continue;
        }
        hybrid_add_cluster_sample(p, s, evaluated_lobe, min_distance, scale, rng, total, dropped);
    }
    if (!blended && !mock) {
        total /= float(push.cut_size);  // cut_size estimates of the whole tree
    }
    gi_counters_add(dropped, traversals, levels, dead, !blended, completed);
    imageStore(indirect, pixel, vec4(total, float(dropped)));
}
