#ifndef VPLKIT_SST_SAMPLING_GLSL
#define VPLKIT_SST_SAMPLING_GLSL

// Sampling the stochastic substitute tree at a shading point: the traversal of the SST paper sec. 4.1
// (`sst`, from the root) and of the thesis sec. 5.2 (`hybrid`, from a cut node), both stopping at
// the first node suitable for sampling (eq. 5.6, flagged at build time) or at a leaf, and the
// cluster evaluation of the thesis sec. 5.3 / the SST paper sec. 4.2.
//
// Define VPLKIT_SST_NODES_BINDING and VPLKIT_SST_LEAVES_BINDING, and include vplkit/brdf.glsl,
// vplkit/vpl.glsl, vplkit/vpl_eval.glsl, vplkit/gi_bounds.glsl, vplkit/sst.glsl and
// vplkit/rng.glsl and vplkit/gi_lobe.glsl first. Node indices are sst.glsl's: inner nodes 0 .. L - 2, leaf c - (L - 1).

layout(std430, set = 0, binding = VPLKIT_SST_NODES_BINDING) readonly buffer SstNodeBuffer { SstNode items[]; } sst_nodes;
layout(std430, set = 0, binding = VPLKIT_SST_LEAVES_BINDING) readonly buffer SstLeafBuffer { Vpl items[]; } sst_leaves;

// The shading point every weight and evaluation needs (from the G-buffer).
struct GiPoint {
    vec3 position;
    vec3 normal;            // shading normal, unit
    vec3 geometric_normal;  // unit, same side
    vec3 wo;                // unit, towards the viewer
    vec3 albedo;
    float roughness;
    float metallic;
};

// Which weight the traversal uses.
const uint kSstWeightUpperBound = 0u;  // sst: cosine upper bound over the box (the SST paper sec. 4.1)
const uint kSstWeightExpected = 1u;    // hybrid: average clamped corner cosine (the thesis eq. 5.2)

// Node `node` of a tree with `leaf_count` leaves over `count` real VPLs. A leaf index past the
// real VPLs is bogus padding, told apart by index: an empty node (leaf_count 0, weight 0).
SstNode sst_fetch(uint node, uint leaf_count, uint count) {
    if (leaf_count == 1u) {
        return sst_nodes.items[0];  // one VPL: node 0 is its leaf record
    }
    if (!sst_is_leaf(node, leaf_count)) {
        return sst_nodes.items[node];
    }
    uint leaf = sst_leaf_index(node, leaf_count);
    if (leaf >= count) {
        return sst_empty_node();
    }
    Vpl vpl = sst_leaves.items[leaf];
    // A tree built over a count the GPU wrote (element_count.glsl) is sized for its capacity:
    // `count` is then the capacity and the padding past the real count is told by its data, the
    // all-zero bogus leaf (gather_leaves.comp). A real VPL's normal is never zero (one that were
    // would reflect nothing anyway).
    if (vpl.normal == vec3(0.0)) {
        return sst_empty_node();
    }
    // Thresholds do not matter: a leaf always ends a traversal.
    return sst_leaf_node(vpl, 0.0, 0.0);
}

// A child's weight w = a / d2 (the SST paper eq. 5 with V = 1): a = material x cosine x intensity,
// d2 = the squared distance to the node's mean, clamped below by the evaluation's own d_min^2
// (vpl_eval.glsl): "distance to a VPL -> 0" is clamped with the same scene-relative epsilon in
// every method, and the shading point inside the node's box needs no special case (the SST paper
// sec. 4.1 bounds the distance from below by an epsilon rather than dropping it as stochastic
// lightcuts do, which loses colour bleeding). An empty node weighs 0 and is never measured.
// Why the mean and not the box: the lightcuts bound 1/d_min^2 to the box was tried and is far
// worse for sampling: every box around x gets the epsilon's huge weight, so the child that holds
// the light is drawn rarely and weighed hugely (the unbiasedness test's mean over 256 seeds came
// out 10x low at some pixels, the heavy tail never drawn). RTSLC tames this by averaging its
// min- and max-distance probabilities (rtslc.glsl); the SST has its means.
//
// The material term is that of the sample's lobe (`lobe`: brdf.glsl's kBrdfLobe*, or
// kGiWeightGlossyAtMean): the whole BRDF, the diffuse lobe or the glossy lobe towards the node's
// mean, or for kBrdfLobeGlossy in gi_glossy_direction's direction into its box (gi_lobe.glsl).
float sst_weight_numerator(GiPoint p, vec3 mean, float intensity, uint leaf_count, vec3 box_lo, vec3 box_hi,
                           uint weight_kind, uint lobe, float min_distance, out float d2) {
    vec3 to_mean = mean - p.position;
    d2 = max(dot(to_mean, to_mean), min_distance * min_distance);
    if (leaf_count == 0u || !(intensity > 0.0)) {
        return 0.0;
    }
    float cosine = weight_kind == kSstWeightExpected ? gi_average_corner_cosine(p.position, p.normal, box_lo, box_hi)
                                                     : gi_box_cosine_bound(p.position, p.normal, box_lo, box_hi);
    if (cosine == 0.0) {
        return 0.0;  // the whole box lies behind the surface
    }
    float len2 = dot(to_mean, to_mean);
    vec3 wi = len2 > 0.0 ? to_mean * inversesqrt(len2) : p.normal;
    if (lobe == kBrdfLobeGlossy) {
        wi = gi_glossy_direction(p.position, p.normal, p.wo, box_lo, box_hi);
    }
    return gi_lobe_material_weight(p.normal, p.wo, wi, p.albedo, p.roughness, p.metallic, lobe) * cosine * intensity;
}

float sst_weight_numerator(GiPoint p, SstNode node, uint weight_kind, uint lobe, float min_distance, out float d2) {
    return sst_weight_numerator(p, node.mean, node.intensity, node.leaf_count, node.box_lo, node.box_hi, weight_kind,
                                lobe, min_distance, d2);
}

// The whole BRDF's weight (cut selection, and every sample without the glossy branch).
float sst_weight_numerator(GiPoint p, SstNode node, uint weight_kind, float min_distance, out float d2) {
    return sst_weight_numerator(p, node, weight_kind, kBrdfLobeBoth, min_distance, d2);
}

// The left child's probability from the weights a / d2 (gi_child_probability). For hybrid's
// expected-contribution weights (kSstWeightExpected: distance to the node's mean, eq. 5.2's
// average corner cosine; neither bounds the light) it is the mean of that probability and the
// one with the distance to the node's box instead, as rtslc averages its min- and max-distance
// probabilities (the RTSLC paper sec. 3.1): a child whose mean lies far but whose box reaches close to
// x (a wall's cluster seen from the floor beside it) is no longer drawn with a probability far
// below its share of the light, so it is never weighed hugely (in the Cornell box one
// such sample lifted a pixel's mean over 256 frames to 2.2x exact's brightest pixel; Sponza
// read 2052x in another measurement). Alone, the box distance is far worse (see
// sst_weight_numerator); mixed half and half, each probability is at least half of either
// strategy's. Unbiased either way: the sample is divided by the probability it was drawn with.
float sst_defensive_probability(GiPoint p, vec3 l_lo, vec3 l_hi, vec3 r_lo, vec3 r_hi, uint weight_kind, float a_left,
                                float d2_left, float a_right, float d2_right, float min_distance) {
    float p_mean = gi_child_probability(a_left, d2_left, a_right, d2_right);
    if (weight_kind != kSstWeightExpected || !(a_left > 0.0 && a_right > 0.0)) {
        return p_mean;  // dead, or one child without light: 0, 1 or < 0 exactly
    }
    float floor2 = min_distance * min_distance;
    float box_left = max(gi_box_distance2_min(p.position, l_lo, l_hi), floor2);
    float box_right = max(gi_box_distance2_min(p.position, r_lo, r_hi), floor2);
    float p_box = gi_left_probability(a_left, box_left, a_right, box_right);
    return gi_grid_probability(0.5 * (p_mean + p_box));
}

float sst_defensive_probability(GiPoint p, SstNode l, SstNode r, uint weight_kind, float a_left, float d2_left,
                                float a_right, float d2_right, float min_distance) {
    return sst_defensive_probability(p, l.box_lo, l.box_hi, r.box_lo, r.box_hi, weight_kind, a_left, d2_left, a_right,
                                     d2_right, min_distance);
}

// The end of one traversal: the node reached and the probability of the path to it.
struct SstSample {
    uint node;
    SstNode data;
    float probability;  // the lobe's probability x the child probabilities from the start node
    uint levels;        // levels descended from the start node
    bool dead;          // ended where both children weigh 0: no light (the SST paper sec. 4.1)
};

// Kept below 32 so that a tree of up to 2^31 leaves always reaches a leaf.
const uint kSstMaxLevels = 32u;

// A traversal standing at `start`, before its first step, in a lobe chosen with probability
// lobe_probability (1: the whole BRDF): the start node's share of the estimate is weighed by it.
SstSample sst_sample_at(uint start, uint leaf_count, uint count, float lobe_probability) {
    SstSample s;
    s.node = start;
    s.data = sst_fetch(start, leaf_count, count);
    s.probability = lobe_probability;
    s.levels = 0u;
    s.dead = false;
    return s;
}

SstSample sst_sample_at(uint start, uint leaf_count, uint count) {
    return sst_sample_at(start, leaf_count, count, 1.0);
}

// A suitable node's substitute stands for its VPLs only where the receiver is far from the
// cluster compared with its extent: the substitute matches the VPLs' mean and per-axis variances,
// so the light at x (1/d^2 and the cosines, smooth in the VPL's position far away) differs from
// their mean light by terms of order (extent / distance)^2. Near the cluster (a receiver on the
// wall beside a floor cluster, inside a cluster's box) those terms are not small: the
// substitute's drawn positions, clamped to the box, can land nearer x than any of its VPLs or
// behind x's surface, and its merged normal can hide VPLs that face x. There the
// traversal descends further, to a node that is far compared with its own extent, or a leaf: the
// papers' blur at the depth where it is a blur (the SST paper eq. 3 / the thesis eq. 5.6 judge a
// cluster's shape alone, not where it is seen from). The distance is to the node's box, 0 inside
// it; the extent is the box's diagonal.
const float kSstSubstituteFarRatio = 1.0;
bool sst_substitute_far_enough(vec3 x, SstNode node) {
    vec3 extent = node.box_hi - node.box_lo;
    return gi_box_distance2_min(x, node.box_lo, node.box_hi) >=
           kSstSubstituteFarRatio * kSstSubstituteFarRatio * dot(extent, extent);
}

// Descends from `start` until a leaf or a suitable node (eq. 5.6) far enough from x, picking a
// child with probability w / (w_left + w_right) (the thesis eq. 5.4; for hybrid's weights
// sst_defensive_probability's mixture) and a fresh random number per level, with the weights of
// the sample's lobe. The glossy lobe ignores the substitutes and descends to
// a leaf VPL (the SST paper sec. 4.2: a substitute would blur a sharp reflection).
// The glossy lobe steers by the mixture of gi_lobe.glsl (GiGlossyPath), and its probability is
// the mixture's.
SstSample sst_traverse(GiPoint p, uint start, uint leaf_count, uint count, uint weight_kind, GiLobe lobe,
                       float min_distance, inout Rng rng) {
    SstSample s = sst_sample_at(start, leaf_count, count, lobe.probability);
    bool glossy = lobe.kind == kBrdfLobeGlossy;
    GiGlossyPath path = GiGlossyPath(true, 1.0, 1.0);
    if (glossy) {
        path = gi_glossy_path_start(rng);
    }
    for (uint level = 0u; level < kSstMaxLevels; ++level) {
        if (sst_is_leaf(s.node, leaf_count) || (!glossy && (s.data.flags & kSstFlagSuitable) != 0u &&
                                                  sst_substitute_far_enough(p.position, s.data))) {
            break;
        }
        uint left = sst_left_child(s.node), right = sst_right_child(s.node);
        SstNode l = sst_fetch(left, leaf_count, count), r = sst_fetch(right, leaf_count, count);
        float d2_left, d2_right;
        float a_left = sst_weight_numerator(p, l, weight_kind, lobe.kind, min_distance, d2_left);
        float a_right = sst_weight_numerator(p, r, weight_kind, lobe.kind, min_distance, d2_right);
        // Cross-multiplied (gi_left_probability): no 1/d2, no inf/inf; < 0 marks a dead branch,
        // where the sample ends with no light (backtracking would cost a shader loop per level).
        float p_left = sst_defensive_probability(p, l, r, weight_kind, a_left, d2_left, a_right, d2_right,
                                                 min_distance);
        float p_left_reflection = p_left, p_left_at_mean = p_left;
        if (glossy) {
            float a_left_at_mean = sst_weight_numerator(p, l, weight_kind, kGiWeightGlossyAtMean, min_distance, d2_left);
            float a_right_at_mean =
                sst_weight_numerator(p, r, weight_kind, kGiWeightGlossyAtMean, min_distance, d2_right);
            p_left_at_mean = gi_child_probability(a_left_at_mean, d2_left, a_right_at_mean, d2_right);
            p_left = gi_glossy_path_left(path, p_left, p_left_at_mean);
        }
        if (p_left < 0.0) {
            s.dead = true;
            break;
        }
        // u < p_left is never true for p_left = 0 and always for p_left = 1 (u in [0, 1)): a child
        // of zero weight is never chosen. With both weights above 0, p_left is on u's grid
        // (gi_child_probability), so each child is taken with the probability divided by.
        bool go_left = rng_next_float(rng) < p_left;
        s.node = go_left ? left : right;
        s.data = go_left ? l : r;
        if (glossy) {
            gi_glossy_path_step(path, p_left_reflection, p_left_at_mean, go_left);
        } else {
            s.probability *= go_left ? p_left : 1.0 - p_left;
        }
        ++s.levels;
    }
    if (glossy) {
        s.probability = lobe.probability * gi_glossy_path_probability(path);
    }
    return s;
}

SstSample sst_traverse(GiPoint p, uint start, uint leaf_count, uint count, uint weight_kind, float min_distance,
                       inout Rng rng) {
    return sst_traverse(p, start, leaf_count, count, weight_kind, gi_lobe_both(), min_distance, rng);
}

// Two independent standard normal numbers (Box-Muller); 1 - u keeps the logarithm finite.
vec2 sst_normal_pair(inout Rng rng) {
    float radius = sqrt(-2.0 * log(1.0 - rng_next_float(rng)));
    float angle = 2.0 * kPi * rng_next_float(rng);
    return radius * vec2(cos(angle), sin(angle));
}

// The point light a traversal's end stands for (the thesis sec. 5.3): a leaf is its VPL; a
// suitable inner node draws a position from its substitute distribution (normal in its plane
// frame, the SST paper sec. 4.2), clamped to its box, with the node's normal and summed colour.
// The flux is divided by the path probability, so the estimate of the start node's subtree is
// unbiased over the choice of child (the substitute position itself is the method's bias).
Vpl sst_sample_light(SstSample s, uint leaf_count, inout Rng rng) {
    Vpl light;
    if (sst_is_leaf(s.node, leaf_count)) {
        light = sst_leaves.items[leaf_count == 1u ? 0u : sst_leaf_index(s.node, leaf_count)];
    } else {
        vec3 t, b;
        sst_frame(s.data.normal, t, b);
        vec3 sigma = sqrt(s.data.variance);
        vec2 g01 = sst_normal_pair(rng);
        float g2 = sst_normal_pair(rng).x;
        vec3 offset = t * (sigma.x * g01.x) + b * (sigma.y * g01.y) + s.data.normal * (sigma.z * g2);
        light.position = clamp(s.data.mean + offset, s.data.box_lo, s.data.box_hi);
        light.normal = s.data.normal;
        light.flux = s.data.colour;
    }
    light.flux /= s.probability;
    return light;
}

// Luminance of node `node` (0 for padding), read without the rest of the node.
float sst_node_intensity(uint node, uint leaf_count, uint count) {
    if (leaf_count == 1u || !sst_is_leaf(node, leaf_count)) {
        return sst_nodes.items[node].intensity;
    }
    uint leaf = sst_leaf_index(node, leaf_count);
    return leaf < count ? sst_intensity(sst_leaves.items[leaf].flux) : 0.0;
}

// A leaf below `node` drawn with probability its intensity / the node's: a descent by the stored
// intensities alone (no shading-point weights, so it is cheap). Both children dark: the left
// one (always real when its parent is: padding fills the end); the node's light is about 0 then.
uint sst_leaf_by_intensity(uint node, uint leaf_count, uint count, inout Rng rng) {
    for (uint level = 0u; level < kSstMaxLevels; ++level) {
        if (sst_is_leaf(node, leaf_count)) {
            break;
        }
        uint left = sst_left_child(node), right = sst_right_child(node);
        float i_left = sst_node_intensity(left, leaf_count, count);
        float i_right = sst_node_intensity(right, leaf_count, count);
        float sum = i_left + i_right;
        bool go_left = !(sum > 0.0) || rng_next_float(rng) * sum < i_left;
        node = go_left ? left : right;
    }
    return node;
}

// Where the shadow ray of a traversal's end goes: a real VPL of the node reached, drawn with
// probability intensity / node intensity (sst_leaf_by_intensity), or the leaf's own VPL.
//
// Why not the substitute position itself (the thesis sec. 5.3, the SST paper sec. 4.2 shoot the ray
// there): that point lies on the cluster's plane, spread by its variances and clamped to its
// box, not on the scene's surfaces. Where the cluster is curved or spans parallel surfaces at
// different heights (a floor and the top of a block on it, the inside of a sphere), the point
// falls inside or behind the geometry, and the ray to it is blocked although every VPL it stands
// for is visible: measured, a point light inside a closed diffuse sphere lost 38% of sst's and
// hybrid's one-bounce light, the Cornell box 16-19% (see the note of tests/render/
// test_gi_energy.cpp). The SST paper names the cause ("drawn light positions may also be slightly
// inside geometry") and offsets the ray by an epsilon, which helps only when "slightly" holds.
// A real VPL lies on a surface its light reached, so the ray to it is blocked only by what
// really blocks that VPL: the visibility of a VPL drawn by intensity is an unbiased estimate of
// the node's intensity-weighted mean visibility, and the substitute keeps the blur of the
// position, direction and distance terms (the papers' bias, which spreads light, never loses it).
void sst_shadow_target(SstSample s, uint leaf_count, uint count, inout Rng rng, out vec3 position,
                       out vec3 normal) {
    uint leaf = sst_leaf_by_intensity(s.node, leaf_count, count, rng);
    Vpl vpl = sst_leaves.items[leaf_count == 1u ? 0u : sst_leaf_index(leaf, leaf_count)];
    position = vpl.position;
    normal = vpl.normal;
}

#endif
