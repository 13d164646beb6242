#ifndef VPLKIT_RTSLC_GLSL
#define VPLKIT_RTSLC_GLSL

// Real-time stochastic lightcuts (the RTSLC paper sec. 3.2-3.4) over the perfect light tree
// (light_tree.glsl): the child weights and probabilities of the traversal, the cut-selection
// bound, and the interleaved assignment of cut nodes to pixels. Shared by rtslc_cut.comp,
// rtslc_gi.comp, rtslc_interleave.comp and the test shader that checks the probabilities.
//
// Needs vplkit/brdf.glsl, vplkit/light_tree.glsl and vplkit/gi_bounds.glsl included first.

// A cut slot without a node (a cut smaller than samples_per_pixel, or a block without surface).
const uint kRtslcNoNode = 0xFFFFFFFFu;
// The most nodes a cut may hold: the size of the cut shader's local arrays.
const uint kRtslcMaxCutSize = kGiMaxSamplesPerPixel;  // gi_bounds.glsl
// The smallest material weight a child may get (see rtslc_material_weight).
const float kRtslcMinMaterialWeight = 1e-8;

// What a traversal knows about the shading point: position, shading normal, direction to the
// viewer (unit) and material.
struct RtslcShading {
    vec3 position;
    vec3 normal;
    vec3 wo;
    vec3 base_color;
    float roughness;
    float metallic;
};

// The material term of F_j (the RTSLC paper eq. 1), towards the centre of the node's box. Two
// guards keep it from excluding a child that can light x, which would bias the estimator:
// when the centre lies at x or on or below the horizon (a box straddling the tangent plane can
// still hold VPLs above it), the direction is the normal instead; and the weight is at least
// kRtslcMinMaterialWeight, because a black metal seen head-on has a BRDF of exactly 0 at one
// direction (Fresnel F(0) = base colour = 0) but not around it. Any positive weight keeps the
// estimator unbiased; the weight only steers the variance.
//
// `lobe` (gi_lobe.glsl): the part of the BRDF the sample stands for; the glossy lobe looks in
// gi_glossy_direction's direction (the SST paper sec. 4.1's perfect-reflection heuristic), the same
// lobe choice as sst's and hybrid's, so that the methods compare fairly.
float rtslc_material_weight(RtslcShading s, LightTreeNode node, uint lobe) {
    vec3 to_centre = 0.5 * (node.box_min + node.box_max) - s.position;
    float along_normal = dot(s.normal, to_centre);
    vec3 wi = along_normal > 0.0 ? normalize(to_centre) : s.normal;
    if (lobe == kBrdfLobeGlossy) {
        wi = gi_glossy_direction(s.position, s.normal, s.wo, node.box_min, node.box_max);
    }
    float weight = gi_lobe_material_weight(s.normal, s.wo, wi, s.base_color, s.roughness, s.metallic, lobe);
    // Written so that a NaN weight stays NaN (max(NaN, c) may return c).
    return weight < kRtslcMinMaterialWeight ? kRtslcMinMaterialWeight : weight;
}

// F_j I_j, the numerator of both weights of the RTSLC paper eq. 1: the lightcuts cosine bound of the
// box x the material weight x the node's intensity. 0 exactly when no VPL below the node can
// light x: a bogus node (its box is the empty sentinel and is never measured), zero intensity
// (all flux black), or a box wholly behind the shading normal (vpl_geometry gives those VPLs
// 0). A NaN intensity (non-finite flux below) stays NaN, so the sample it leads to is dropped
// and counted, not silently weighted.
float rtslc_node_importance(RtslcShading s, LightTreeNode node, uint lobe) {
    if (light_tree_is_bogus(node) || node.intensity == 0.0) {
        return 0.0;
    }
    float cosine = gi_box_cosine_bound(s.position, s.normal, node.box_min, node.box_max);
    if (cosine == 0.0) {
        return 0.0;
    }
    return cosine * rtslc_material_weight(s, node, lobe) * node.intensity;
}

float rtslc_node_importance(RtslcShading s, LightTreeNode node) {
    return rtslc_node_importance(s, node, kBrdfLobeBoth);
}

// The lightcuts-style bound of a cut node at the representative pixel, F I / max(d_min^2, eps^2):
// the light the node could send at most, up to the VPL's own cosine. The cut splits the node
// with the largest one. eps = vpl_min_distance(scale), the evaluation's clamp: a shading point
// inside the box (d_min = 0) gets the bound the evaluation itself would allow at most.
float rtslc_node_bound(RtslcShading s, LightTreeNode node, float min_distance2) {
    float importance = rtslc_node_importance(s, node);
    if (importance == 0.0) {
        return 0.0;
    }
    return importance / max(gi_box_distance2_min(s.position, node.box_min, node.box_max), min_distance2);
}

struct RtslcChildProbability {
    float left;  // probability of the left child; the right one's is exactly 1 - left
    bool dead;   // both children weigh 0: the traversal returns no light (the RTSLC paper sec. 3.2)
};

// the RTSLC paper eqs. 1-2: w_j = F_j I_j / d_j^2 at the closest (d_min) and farthest (d_max) points of
// child j's box, p_j = (p_j^min + p_j^max) / 2 with p_j^min = w_j^min / (w_j^min + w_k^min) and
// the same for max.
//
// The squared distances are clamped below by eps^2 = vpl_min_distance(scale)^2, the clamp of the
// evaluation (vpl_eval.glsl). That covers both d_min = 0 cases without a special case: a shading
// point inside one box gives that box the largest weight the evaluation allows any VPL, and a
// point inside both boxes (or on a VPL) gives both d_min^2 = eps^2, so p^min reduces to
// F_j I_j / (F_j I_j + F_k I_k): the paper's "ignore the distance terms", which eq. 2 then needs
// no branch for.
//
// Numerics: both weights enter in the cross-multiplied form of gi_left_probability, after
// dividing the F I by their larger one and each pair of d^2 by its larger one, so every product
// is at most 1 (no overflow even for 1e6 flux in a 1e4-sized scene) and no 1/d^2 is formed. Both
// normalized d^2 are at least eps^2 / (largest d^2), ~1e-5 for boxes within the scene, so the sum
// cannot underflow; should it (a VPL far outside the scene), p^min falls back to the distance-free
// ratio, which is as unbiased as any positive choice.
//
// The probability is then rounded up to a multiple of 2^-24, and kept in [2^-24, 1 - 2^-24] when
// both children weigh more than 0: rtslc_choose_left compares it with rng_next_float's k 2^-24, so
// the left child is taken with exactly that probability and the estimator divides by the
// probability it actually sampled with. A child of zero weight gets exactly 0 and is never
// chosen; one of positive weight is never rounded to 0 (that would bias), whatever its ratio.
RtslcChildProbability rtslc_child_probability(RtslcShading s, LightTreeNode left, LightTreeNode right,
                                              float min_distance2, uint lobe) {
    RtslcChildProbability result;
    float a_left = rtslc_node_importance(s, left, lobe);
    float a_right = rtslc_node_importance(s, right, lobe);
    result.dead = a_left == 0.0 && a_right == 0.0;
    result.left = 0.0;
    if (result.dead) {
        return result;
    }
    if (a_left == 0.0 || a_right == 0.0) {
        result.left = a_left == 0.0 ? 0.0 : 1.0;
        return result;
    }
    // Both children are real here (a bogus one weighs 0), so both boxes may be measured.
    float d2_min_left = max(gi_box_distance2_min(s.position, left.box_min, left.box_max), min_distance2);
    float d2_min_right = max(gi_box_distance2_min(s.position, right.box_min, right.box_max), min_distance2);
    float d2_max_left = max(gi_box_distance2_max(s.position, left.box_min, left.box_max), min_distance2);
    float d2_max_right = max(gi_box_distance2_max(s.position, right.box_min, right.box_max), min_distance2);
    float a_scale = max(a_left, a_right);
    float al = a_left / a_scale;
    float ar = a_right / a_scale;
    float d2_min_scale = max(d2_min_left, d2_min_right);
    float d2_max_scale = max(d2_max_left, d2_max_right);
    float p_min = gi_left_probability(al, d2_min_left / d2_min_scale, ar, d2_min_right / d2_min_scale);
    float p_max = gi_left_probability(al, d2_max_left / d2_max_scale, ar, d2_max_right / d2_max_scale);
    if (p_min < 0.0) {
        p_min = al / (al + ar);
    }
    if (p_max < 0.0) {
        p_max = al / (al + ar);
    }
    float p = 0.5 * (p_min + p_max);
    // A NaN (from a NaN intensity) is passed on as it is: the sample is dropped and counted.
    result.left = gi_grid_probability(p);
    return result;
}

// The whole BRDF's probabilities (every sample without the glossy branch).
RtslcChildProbability rtslc_child_probability(RtslcShading s, LightTreeNode left, LightTreeNode right,
                                              float min_distance2) {
    return rtslc_child_probability(s, left, right, min_distance2, kBrdfLobeBoth);
}

// The child pick of the traversal and its probability (the sample / pmf pair): u from
// rng_next_float (k 2^-24), p_left from rtslc_child_probability (a multiple of 2^-24), so
// P(left) = p_left exactly. p_left = 0 never picks left (u >= 0); p_left = 1 always does.
bool rtslc_choose_left(float p_left, float u) {
    return u < p_left;
}

float rtslc_choice_probability(float p_left, bool left) {
    return left ? p_left : 1.0 - p_left;
}

// Interleaved sampling (the RTSLC paper sec. 3.4 and eq. 3, with the per-frame rotation of sec. 4): the
// pixel with index i in its m x m sub-block takes p = (i + frame) mod m^2 and samples the cut
// slots [t_p, t_{p+1}), t_p = floor(p c / m^2), where c is the number of nodes the block's cut
// holds (its nodes come first). The sub-block's pixels together sample every node once. A cut
// with fewer than m^2 nodes (a tree with few VPLs) cannot be shared out so that every pixel gets
// one, so then every pixel samples the whole cut, and the reconstruction averages. m = 1: the
// whole cut. Returns [first, end).
uvec2 rtslc_interleave_slots(uvec2 pixel, uint interleave, uint frame, uint cut_nodes) {
    uint m2 = interleave * interleave;
    if (interleave <= 1u || cut_nodes < m2) {
        return uvec2(0u, cut_nodes);
    }
    uint i = (pixel.y % interleave) * interleave + pixel.x % interleave;
    uint p = (i + frame % m2) % m2;  // frame % m2 first: i + frame must not wrap at 2^32
    return uvec2(p * cut_nodes / m2, (p + 1u) * cut_nodes / m2);
}

#endif
