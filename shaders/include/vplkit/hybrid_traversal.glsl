#ifndef VPLKIT_HYBRID_TRAVERSAL_GLSL
#define VPLKIT_HYBRID_TRAVERSAL_GLSL

// hybrid's traversal below a cut node for the whole BRDF or the diffuse lobe: sst_traverse's steps
// with kSstWeightExpected (the same weights, probabilities and random numbers, so the same
// samples), but reading only the node fields a step needs. sst_traverse carries three whole
// SstNodes (96 bytes each: the substitute's normal, variances and colour too) through every
// level and builds a full node from each leaf it looks at; on lavapipe, whose invocations are
// SIMD lanes of one CPU thread, that is register pressure every level pays for. The glossy lobe
// keeps sst_traverse (it steers by the glossy path's mixture and goes to a leaf anyway).
//
// Include vplkit/sst_sampling.glsl first.

// What a traversal step reads of a node: sst.glsl's SstNode without normal, nu, variance, colour.
struct HybridNode {
    vec3 mean;
    float intensity;
    vec3 box_lo;
    uint leaf_count;  // 0: an empty node (padding), weight 0
    vec3 box_hi;
    uint flags;
};

// sst_fetch's node, field by field. A leaf's flags are 0: a leaf ends the traversal whatever they say.
HybridNode hybrid_fetch(uint node, uint leaf_count, uint count) {
    if (leaf_count == 1u || !sst_is_leaf(node, leaf_count)) {
        uint i = leaf_count == 1u ? 0u : node;
        return HybridNode(sst_nodes.items[i].mean, sst_nodes.items[i].intensity, sst_nodes.items[i].box_lo,
                          sst_nodes.items[i].leaf_count, sst_nodes.items[i].box_hi, sst_nodes.items[i].flags);
    }
    uint leaf = sst_leaf_index(node, leaf_count);
    HybridNode empty = HybridNode(vec3(0.0), 0.0, vec3(0.0), 0u, vec3(0.0), 0u);
    if (leaf >= count) {
        return empty;
    }
    vec3 position = sst_leaves.items[leaf].position;
    // sst_fetch's rule: padding past a count the GPU wrote is the all-zero bogus leaf.
    if (sst_leaves.items[leaf].normal == vec3(0.0)) {
        return empty;
    }
    return HybridNode(position, sst_intensity(sst_leaves.items[leaf].flux), position, 1u, position, 0u);
}

// The end of a traversal: the node reached, its intensity and the path's probability.
struct HybridSample {
    uint node;
    float intensity;
    float probability;  // the lobe's probability x the child probabilities from the start node
    uint levels;
    bool dead;  // ended where both children weigh 0: no light
};

HybridSample hybrid_sample_of(SstSample s) {
    return HybridSample(s.node, s.data.intensity, s.probability, s.levels, s.dead);
}

// sst_traverse(p, start, ..., kSstWeightExpected, lobe, ...) for a lobe other than the glossy one.
HybridSample hybrid_traverse(GiPoint p, uint start, uint leaf_count, uint count, GiLobe lobe, float min_distance,
                             inout Rng rng) {
    HybridNode n = hybrid_fetch(start, leaf_count, count);
    HybridSample s = HybridSample(start, n.intensity, lobe.probability, 0u, false);
    for (uint level = 0u; level < kSstMaxLevels; ++level) {
        if (sst_is_leaf(s.node, leaf_count)) {
            break;
        }
        // sst_substitute_far_enough on the fields.
        vec3 extent = n.box_hi - n.box_lo;
        if ((n.flags & kSstFlagSuitable) != 0u &&
            gi_box_distance2_min(p.position, n.box_lo, n.box_hi) >=
                kSstSubstituteFarRatio * kSstSubstituteFarRatio * dot(extent, extent)) {
            break;
        }
        uint left = sst_left_child(s.node), right = sst_right_child(s.node);
        HybridNode l = hybrid_fetch(left, leaf_count, count), r = hybrid_fetch(right, leaf_count, count);
        float d2_left, d2_right;
        float a_left = sst_weight_numerator(p, l.mean, l.intensity, l.leaf_count, l.box_lo, l.box_hi,
                                            kSstWeightExpected, lobe.kind, min_distance, d2_left);
        float a_right = sst_weight_numerator(p, r.mean, r.intensity, r.leaf_count, r.box_lo, r.box_hi,
                                             kSstWeightExpected, lobe.kind, min_distance, d2_right);
        float p_left = sst_defensive_probability(p, l.box_lo, l.box_hi, r.box_lo, r.box_hi, kSstWeightExpected, a_left,
                                                 d2_left, a_right, d2_right, min_distance);
        if (p_left < 0.0) {
            s.dead = true;
            break;
        }
        bool go_left = rng_next_float(rng) < p_left;
        s.node = go_left ? left : right;
        n = go_left ? l : r;
        s.intensity = n.intensity;
        s.probability *= go_left ? p_left : 1.0 - p_left;
        ++s.levels;
    }
    return s;
}

#endif
