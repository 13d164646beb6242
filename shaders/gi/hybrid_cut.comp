#version 460
#extension GL_GOOGLE_include_directive : require
// Shallow light cuts for the `hybrid` method (the thesis sec. 5.1): one cut of at most cut_size
// SST nodes per block_size x block_size pixel block, chosen for the block's representative pixel.
// Starting from the root, the cut node with the highest expected contribution (eq. 5.2 cosine x
// material x intensity / clamped squared distance) is replaced by its children until the cut
// holds cut_size nodes or only leaves. Sec. 5.1 leaves out children whose box lies fully behind
// the surface; here they stay in the cut unsplit (only padding and dark nodes are left out), so
// the cut still covers every VPL for the other pixels that use it.
//
// The specialization constant kCutPriority swaps eq. 5.2 for rtslc's bound F I / max(d_min^2, eps^2)
// (rtslc_node_bound, the RTSLC paper sec. 3.3) as the split order: hybrid-lightcuts (hybrid_gi.comp's
// kTraversal) takes it with rtslc's traversal. Why (reasoned): eq. 5.2 weighs a node by the
// distance to its mean, so a cluster reaching close to the representative pixel looks no brighter
// than its mean's distance says and stays unsplit, and the traversal's near samples below it are
// heavy; the bound splits it first. Measured (tests/gi/test_hybrid_residue.cpp's glossy room, 64
// frames): hybrid-lightcuts' per-frame noise 1.46x rtslc's with eq. 5.2 (and the lobe MIS),
// 0.71x with the bound; on Sponza-lite the block noise is rtslc's either way
// (docs/measurements.md, *Hybrid's floor*).
//
// Writes blocks[b] (HybridBlock) and cuts[b * cut_size + i]: the nodes in the order of their first
// leaf (empty slots kCutEmptySlot at the end). Leaf order is the sorted (Morton) order, so slot i
// of neighbouring blocks' cuts tends to cover the same part of the scene: cut blending picks slot
// i from one of four cuts, and this keeps the blended cut close to a partition.

#define VPLKIT_SST_NODES_BINDING 0
#define VPLKIT_SST_LEAVES_BINDING 1
#include "vplkit/brdf.glsl"
#include "vplkit/gbuffer.glsl"
#include "vplkit/geometric_similarity.glsl"
#include "vplkit/rng.glsl"
#include "vplkit/vpl.glsl"
#include "vplkit/vpl_eval.glsl"
#include "vplkit/gi_bounds.glsl"
#include "vplkit/gi_lobe.glsl"
#include "vplkit/sst.glsl"
#include "vplkit/sst_sampling.glsl"
#include "vplkit/light_tree.glsl"
#include "vplkit/rtslc.glsl"
#include "vplkit/sst_lightcuts_traversal.glsl"
#include "vplkit/cut_blending.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 2, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D gbuffer_normal;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D gbuffer_geometric_normal;
layout(set = 0, binding = 5, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(std430, set = 0, binding = 6) writeonly buffer HybridBlockBuffer { HybridBlock items[]; } blocks;
layout(std430, set = 0, binding = 7) writeonly buffer HybridCutBuffer { uint items[]; } cuts;

layout(push_constant) uniform HybridCutPush {
    vec3 camera_position;
    uint block_size;
    uint blocks_x;
    uint blocks_y;
    uint cut_size;
    uint leaf_count;
    uint vpl_count;
    float scene_scale;  // bvh_scene_scale() on the host: the evaluation's distance clamp
} push;

// The split order: the thesis' expected contribution (eq. 5.2), or rtslc's bound (hybrid-lightcuts).
const uint kCutPriorityExpected = 0u;
const uint kCutPriorityBound = 1u;
layout(constant_id = 0) const uint kCutPriority = kCutPriorityExpected;

// A node's priority for the split at p; 0 where it cannot light p (its box behind the surface).
float cut_priority(GiPoint p, SstNode data, float min_distance) {
    if (kCutPriority == kCutPriorityBound) {
        RtslcShading s = RtslcShading(p.position, p.normal, p.wo, p.albedo, p.roughness, p.metallic);
        return rtslc_node_bound(s, sst_as_light_tree_node(data), min_distance * min_distance);
    }
    float d2;
    float a = sst_weight_numerator(p, data, kSstWeightExpected, min_distance, d2);
    return a > 0.0 ? a / d2 : 0.0;
}

// The first leaf below heap node `node` of a tree with leaf_count = 2^depth leaves.
uint first_leaf(uint node, uint depth) {
    uint level = uint(findMSB(node + 1u));
    return ((node + 1u) << (depth - level)) - push.leaf_count;
}

void main() {
    uint block = linear_thread_index();
    if (block >= push.blocks_x * push.blocks_y) {
        return;
    }
    ivec2 origin = ivec2(block % push.blocks_x, block / push.blocks_x) * int(push.block_size);
    ivec2 size = imageSize(gbuffer_position);
    ivec2 end = min(origin + int(push.block_size), size);

    // The representative pixel: the covered pixel nearest the block's centre (sec. 5.1.2 uses the
    // centre; on a block's background centre the nearest surface pixel stands in for it).
    vec2 centre = vec2(origin + end - 1) * 0.5;
    ivec2 best = ivec2(-1);
    float best_d2 = kGiBigFloat;
    for (int y = origin.y; y < end.y; ++y) {
        for (int x = origin.x; x < end.x; ++x) {
            if (imageLoad(gbuffer_position, ivec2(x, y)).w > 0.5) {
                vec2 d = vec2(x, y) - centre;
                float d2 = dot(d, d);
                if (d2 < best_d2) {
                    best_d2 = d2;
                    best = ivec2(x, y);
                }
            }
        }
    }
    uint base = block * push.cut_size;
    if (best.x < 0) {
        blocks.items[block] = HybridBlock(vec3(0.0), 0u, vec3(0.0), 0u);
        for (uint i = 0u; i < push.cut_size; ++i) {
            cuts.items[base + i] = kCutEmptySlot;
        }
        return;
    }
    GbufferSample g = gbuffer_decode(imageLoad(gbuffer_position, best), imageLoad(gbuffer_normal, best),
                                     imageLoad(gbuffer_geometric_normal, best), imageLoad(gbuffer_albedo, best), vec4(0.0));
    GiPoint p = GiPoint(g.position, g.normal, g.geometric_normal, normalize(push.camera_position - g.position), g.albedo,
                        g.roughness, g.metallic);
    float min_distance = vpl_min_distance(push.scene_scale);

    uint node[kGiMaxSamplesPerPixel];
    float priority[kGiMaxSamplesPerPixel];  // cut_priority, or -1 for a leaf (never split)
    uint size_now = 0u;
    // The root always starts the cut, even when it looks dark from here: other pixels of the
    // block may see its light, and an empty cut would give them none.
    SstNode root = sst_fetch(0u, push.leaf_count, push.vpl_count);
    if (root.leaf_count > 0u) {
        node[0] = 0u;
        priority[0] = sst_is_leaf(0u, push.leaf_count) ? -1.0 : cut_priority(p, root, min_distance);
        size_now = 1u;
    }
    while (size_now < push.cut_size) {
        // The splittable node of highest expected contribution (sec. 5.1.1).
        int pick = -1;
        float best_priority = -1.0;
        for (uint i = 0u; i < size_now; ++i) {
            if (priority[i] > best_priority) {
                best_priority = priority[i];
                pick = int(i);
            }
        }
        if (pick < 0) {
            break;  // only leaves left
        }
        uint parent = node[pick];
        uint kept = 0u;
        uint child_node[2];
        float child_priority[2];
        for (uint c = 0u; c < 2u; ++c) {
            uint child = c == 0u ? sst_left_child(parent) : sst_right_child(parent);
            SstNode data = sst_fetch(child, push.leaf_count, push.vpl_count);
            // Left out: only padding and nodes without light, which light no pixel.
            if (data.leaf_count == 0u || !(data.intensity > 0.0)) {
                continue;
            }
            float a = cut_priority(p, data, min_distance);
            // A child that cannot light the representative pixel (its box behind the surface, a = 0)
            // stays in the cut but is never split (priority -1, as a leaf): the cut serves every
            // pixel of the block and the pixels that blend with it, and a pixel at another place
            // may see that light. Dropped, its light was lost to all of them (with spp >= 2 a
            // block whose representative sees the root only from behind had an empty cut).
            child_node[kept] = child;
            child_priority[kept] = a > 0.0 && !sst_is_leaf(child, push.leaf_count) ? a : -1.0;
            ++kept;
        }
        if (kept == 0u) {
            // No child holds light: only a root whose VPLs are all dark (it starts every cut).
            --size_now;
            node[pick] = node[size_now];
            priority[pick] = priority[size_now];
            continue;
        }
        node[pick] = child_node[0];
        priority[pick] = child_priority[0];
        if (kept == 2u) {
            node[size_now] = child_node[1];
            priority[size_now] = child_priority[1];
            ++size_now;
        }
    }
    // Leaf order (insertion sort: at most 64 nodes). Nodes of one cut never overlap, so their
    // first leaves are distinct.
    uint depth = uint(findMSB(push.leaf_count));
    for (uint i = 1u; i < size_now; ++i) {
        uint v = node[i];
        uint key = first_leaf(v, depth);
        int j = int(i) - 1;
        while (j >= 0 && first_leaf(node[j], depth) > key) {
            node[j + 1] = node[j];
            --j;
        }
        node[j + 1] = v;
    }
    blocks.items[block] = HybridBlock(g.position, 1u, g.normal, size_now);
    for (uint i = 0u; i < push.cut_size; ++i) {
        cuts.items[base + i] = i < size_now ? node[i] : kCutEmptySlot;
    }
}
