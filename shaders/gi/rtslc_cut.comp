#version 460
#extension GL_GOOGLE_include_directive : require
// Real-time stochastic lightcuts, cut selection (the RTSLC paper sec. 3.2-3.3): one invocation per
// k x k pixel block. A representative pixel is drawn uniformly among the block's covered pixels;
// at that pixel rtslc_select_cut (rtslc_tree_sampling.glsl) splits the cut from the root by the
// largest bound F I / max(d_min^2, eps^2) until it holds cut_size nodes or only leaves; the cut
// always partitions the tree's real leaves. The tree's leaves may be VPLs (rtslc GI) or the
// scene's lights (direct light through the light tree): this pass is the same for both.
//
// cuts[block * cut_size + i]: the cut's nodes first, then kRtslcNoNode (with kShareOutSlots a
// node may fill several slots in a row, then every slot is filled); a block without covered
// pixels has an empty cut. representatives[block]: the pixel y * width + x whose bounds chose
// the cut, kRtslcNoNode for an empty block. Ties between bounds go to the smaller node index, so
// the cut is a function of the tree and the pixel alone.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 10
#define VPLKIT_GI_COUNTERS_BINDING 8
#include "vplkit/bvh.glsl"
#include "vplkit/brdf.glsl"
#include "vplkit/gbuffer.glsl"
#include "vplkit/light_tree.glsl"
#include "vplkit/gi_bounds.glsl"
#include "vplkit/gi_counters.glsl"
#include "vplkit/rng.glsl"
#include "vplkit/vpl.glsl"
#include "vplkit/vpl_eval.glsl"
#define VPLKIT_LIGHT_TREE_BINDING 6
#include "vplkit/rtslc_tree_sampling.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

// 1: the cut's slots are shared out by bound (rtslc_select_cut_shared_out: a leaf may fill several
// consecutive slots, each one sample of it), as direct light through the tree uses it; 0 (rtslc
// GI): one slot per cut node (rtslc_select_cut).
layout(constant_id = 0) const uint kShareOutSlots = 0u;

layout(set = 0, binding = 2, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D gbuffer_normal;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D gbuffer_geometric_normal;
layout(set = 0, binding = 5, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(std430, set = 0, binding = 7) writeonly buffer RtslcCutBuffer { uint items[]; } cuts;
layout(std430, set = 0, binding = 9) writeonly buffer RtslcRepresentativeBuffer { uint items[]; } representatives;

layout(push_constant) uniform RtslcCutPush {
    vec3 camera_position;
    uint seed;
    uint frame;
    uint block_size;  // k
    uint cut_size;    // n = samples per pixel, 1..kRtslcMaxCutSize
    uint blocks_x;
    uint blocks_y;
    uint leaf_count;  // a power of two; the tree has 2 leaf_count - 1 nodes
} push;

// The stream of the block's representative draw: its own salt, so it never replays a pixel's
// traversal stream (rtslc_gi.comp) for the same seed and frame.
const uint kRtslcCutSalt = 0x9E3779B9u;

void main() {
    uint block = linear_thread_index();
    if (block >= push.blocks_x * push.blocks_y) {
        return;
    }
    ivec2 size = imageSize(gbuffer_position);
    uvec2 block_xy = uvec2(block % push.blocks_x, block / push.blocks_x);
    ivec2 lo = ivec2(block_xy * push.block_size);
    ivec2 hi = min(lo + ivec2(push.block_size), size);
    uint out_base = block * push.cut_size;
    // lavapipe ends every loop of an invocation once its loops together have run 65535
    // iterations (see exact_gi.comp). Here: 2 k^2 for the representative (k <= 32), at most
    // n - 1 + 31 splits each scanning <= 64 cut nodes and measuring two children (8-corner
    // cosine loops), and n writes: ~8000 at most, far below the limit. Each loop still ends
    // through a flag that sets `completed`, so a cut-short cut is counted, not used silently.
    bool completed = true;

    // The representative: the r-th covered pixel of the block, r uniform (modulo bias < 2^-22).
    uint covered = 0u;
    bool counted = false;
    for (int y = lo.y; y <= hi.y; ++y) {
        if (y == hi.y) {
            counted = true;
            break;
        }
        for (int x = lo.x; x < hi.x; ++x) {
            covered += imageLoad(gbuffer_position, ivec2(x, y)).w > 0.5 ? 1u : 0u;
        }
    }
    completed = completed && counted;
    if (covered == 0u || !counted) {
        for (uint i = 0u; i < push.cut_size; ++i) {
            cuts.items[out_base + i] = kRtslcNoNode;
        }
        representatives.items[block] = kRtslcNoNode;
        gi_counters_add(0u, 0u, 0u, 0u, false, completed);
        return;
    }
    Rng rng = rng_create(pcg_hash(push.seed ^ pcg_hash(push.frame)) ^ kRtslcCutSalt, block);
    uint chosen = rng_next_uint(rng) % covered;
    ivec2 representative = lo;
    uint seen = 0u;
    bool found = false;
    for (int y = lo.y; y < hi.y && !found; ++y) {
        for (int x = lo.x; x < hi.x; ++x) {
            if (imageLoad(gbuffer_position, ivec2(x, y)).w > 0.5) {
                if (seen == chosen) {
                    representative = ivec2(x, y);
                    found = true;
                    break;
                }
                ++seen;
            }
        }
    }
    completed = completed && found;

    GbufferSample g = gbuffer_decode(imageLoad(gbuffer_position, representative), imageLoad(gbuffer_normal, representative),
                                     imageLoad(gbuffer_geometric_normal, representative),
                                     imageLoad(gbuffer_albedo, representative), vec4(0.0));
    RtslcShading s = RtslcShading(g.position, g.normal, normalize(push.camera_position - g.position), g.albedo,
                                  g.roughness, g.metallic);
    float min_distance = vpl_min_distance(bvh_scene_scale());
    float min_distance2 = min_distance * min_distance;

    uint cut[kRtslcMaxCutSize];
    bool selected;
    if (kShareOutSlots != 0u) {
        // Each entry's node written samples[i] times in a row: a sampler counts the run.
        uint samples[kRtslcMaxCutSize];
        uint entries = rtslc_select_cut_shared_out(s, push.leaf_count, push.cut_size, min_distance2, cut, samples, selected);
        uint slot = 0u;
        for (uint i = 0u; i < entries; ++i) {
            for (uint k = 0u; k < samples[i]; ++k) {
                cuts.items[out_base + slot] = cut[i];
                ++slot;
            }
        }
        for (; slot < push.cut_size; ++slot) {
            cuts.items[out_base + slot] = kRtslcNoNode;
        }
    } else {
        uint cut_nodes = rtslc_select_cut(s, push.leaf_count, push.cut_size, min_distance2, cut, selected);
        for (uint i = 0u; i < push.cut_size; ++i) {
            cuts.items[out_base + i] = i < cut_nodes ? cut[i] : kRtslcNoNode;
        }
    }
    completed = completed && selected;
    representatives.items[block] = uint(representative.y) * uint(size.x) + uint(representative.x);
    gi_counters_add(0u, 0u, 0u, 0u, false, completed);
}
