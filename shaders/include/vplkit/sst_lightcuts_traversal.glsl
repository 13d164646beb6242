#ifndef VPLKIT_SST_LIGHTCUTS_TRAVERSAL_GLSL
#define VPLKIT_SST_LIGHTCUTS_TRAVERSAL_GLSL

// The stochastic-lightcuts traversal (the RTSLC paper eqs. 1-2: min/max-distance child probabilities,
// rtslc.glsl) run over the SST's nodes, to a leaf: the thesis' comparison protocol (the thesis
// sec. 7.1) compares rtslc and hybrid over the *same* cuts and blending, differing only in the
// traversal below the cut node. The SST's inner nodes carry what a light-tree node does (the box,
// the summed intensity, the count of real VPLs), so the same probability function serves both;
// no substitute is used and no early stop: the sample is the leaf's VPL over its path
// probability, unbiased for the start node's subtree.
//
// Include vplkit/rtslc.glsl, vplkit/gi_lobe.glsl (and what they need) and vplkit/sst_sampling.glsl first.

#include "vplkit/rtslc_lobe_mis.glsl"

LightTreeNode sst_as_light_tree_node(SstNode node) {
    if (node.leaf_count == 0u) {
        return light_tree_empty_node();
    }
    return LightTreeNode(node.box_lo, node.intensity, node.box_hi, node.leaf_count);
}

// Descends from `start` to a leaf with the weights of the sample's lobe (gi_lobe.glsl); s.data
// is the leaf, s.probability the lobe's probability x the path's.
SstSample sst_traverse_lightcuts(GiPoint p, uint start, uint leaf_count, uint count, GiLobe lobe, float min_distance,
                                 inout Rng rng) {
    RtslcShading shading = RtslcShading(p.position, p.normal, p.wo, p.albedo, p.roughness, p.metallic);
    SstSample s = sst_sample_at(start, leaf_count, count, lobe.probability);
    bool glossy = lobe.kind == kBrdfLobeGlossy;
    GiGlossyPath path = GiGlossyPath(true, 1.0, 1.0);
    if (glossy) {
        path = gi_glossy_path_start(rng);  // gi_lobe.glsl: the glossy lobe's two-strategy mixture
    }
    for (uint level = 0u; level < kSstMaxLevels; ++level) {
        if (sst_is_leaf(s.node, leaf_count)) {
            break;
        }
        uint left = sst_left_child(s.node), right = sst_right_child(s.node);
        SstNode l = sst_fetch(left, leaf_count, count), r = sst_fetch(right, leaf_count, count);
        LightTreeNode node_left = sst_as_light_tree_node(l), node_right = sst_as_light_tree_node(r);
        RtslcChildProbability c =
            rtslc_child_probability(shading, node_left, node_right, min_distance * min_distance, lobe.kind);
        RtslcChildProbability at_mean = c;
        if (glossy) {
            at_mean = rtslc_child_probability(shading, node_left, node_right, min_distance * min_distance,
                                              kGiWeightGlossyAtMean);
        }
        bool by_reflection = !glossy || path.by_reflection;
        if (by_reflection ? c.dead : at_mean.dead) {
            s.dead = true;
            break;
        }
        bool go_left = rtslc_choose_left(by_reflection ? c.left : at_mean.left, rng_next_float(rng));
        s.node = go_left ? left : right;
        s.data = go_left ? l : r;
        if (glossy) {
            gi_glossy_path_step(path, c.dead ? -1.0 : c.left, at_mean.dead ? -1.0 : at_mean.left, go_left);
        } else {
            s.probability *= rtslc_choice_probability(c.left, go_left);
        }
        ++s.levels;
    }
    if (glossy) {
        s.probability = lobe.probability * gi_glossy_path_probability(path);
    }
    return s;
}

// rtslc_traverse_lobe_mis over the SST (one-sample MIS over the lobes, balance heuristic): steers
// by the lobe chosen, as sst_traverse_lightcuts does, but tracks the path's probability under
// both lobes, and s.probability is q_d P_d(path) + q_g P_g(path), the probability that a
// traversal from `start` reaches this leaf whichever lobe it chose; the caller evaluates the
// whole BRDF at the leaf over it. rtslc's default (rtslc_gi.comp): with one lobe per sample each
// lobe's estimate is weighed by 1 / q; on Sponza-lite (1000 frames) that left hybrid-lightcuts'
// per-pixel noise at 1.06x rtslc's (7x its variance in the sunlit floor's corner block); with
// the MIS 0.98x (4.6x). `q_glossy` is gi_glossy_lobe_probability.
SstSample sst_traverse_lightcuts_lobe_mis(GiPoint p, uint start, uint leaf_count, uint count, GiLobe lobe,
                                          float q_glossy, float min_distance, inout Rng rng) {
    RtslcShading shading = RtslcShading(p.position, p.normal, p.wo, p.albedo, p.roughness, p.metallic);
    SstSample s = sst_sample_at(start, leaf_count, count, 0.0);
    bool glossy = lobe.kind == kBrdfLobeGlossy;
    // The diffuse choice draws no strategy: the glossy mixture's products do not depend on it.
    GiGlossyPath path = GiGlossyPath(true, 1.0, 1.0);
    if (glossy) {
        path = gi_glossy_path_start(rng);
    }
    float diffuse_path = 1.0;
    float min_distance2 = min_distance * min_distance;
    for (uint level = 0u; level < kSstMaxLevels; ++level) {
        if (sst_is_leaf(s.node, leaf_count)) {
            break;
        }
        uint left = sst_left_child(s.node), right = sst_right_child(s.node);
        SstNode l = sst_fetch(left, leaf_count, count), r = sst_fetch(right, leaf_count, count);
        LightTreeNode node_left = sst_as_light_tree_node(l), node_right = sst_as_light_tree_node(r);
        bool go_left;
        if (!rtslc_lobe_mis_step(shading, node_left, node_right, min_distance2, glossy, path, diffuse_path, rng,
                                 go_left)) {
            s.dead = true;
            break;
        }
        s.node = go_left ? left : right;
        s.data = go_left ? l : r;
        ++s.levels;
    }
    s.probability = (1.0 - q_glossy) * diffuse_path + q_glossy * gi_glossy_path_probability(path);
    return s;
}

#endif
