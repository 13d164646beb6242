#ifndef VPLKIT_RTSLC_TREE_SAMPLING_GLSL
#define VPLKIT_RTSLC_TREE_SAMPLING_GLSL

// Real-time stochastic lightcuts over one perfect light tree (the RTSLC paper sec. 3.2-3.3): the cut
// selection at a block's representative pixel and the traversal from a cut node to a leaf. What
// the leaves are does not matter here: rtslc GI's trees hold VPLs (gi/rtslc_cut.comp,
// gi/rtslc_gi.comp), direct light's tree the scene's lights (lighting/direct_light_tree.comp);
// both select and traverse with these two functions, so they are one code path. A two-level tree
// (two_level_light_tree.glsl) selects its cut in the top tree and traverses each level with
// rtslc_traverse_in, the traversal of a tree at any offset of the node array.
//
// Including it: define the set-0 binding of the light tree (LightTreeNode[]) first,
//     #define VPLKIT_LIGHT_TREE_BINDING 6
// and include vplkit/rng.glsl before (the traversal draws from an Rng).

#if !defined(VPLKIT_LIGHT_TREE_BINDING)
#error "define VPLKIT_LIGHT_TREE_BINDING before including vplkit/rtslc_tree_sampling.glsl"
#endif

#include "vplkit/brdf.glsl"
#include "vplkit/gi_bounds.glsl"
#include "vplkit/light_tree.glsl"
#include "vplkit/rtslc.glsl"
#include "vplkit/gi_lobe.glsl"
#include "vplkit/rtslc_lobe_mis.glsl"

layout(std430, set = 0, binding = VPLKIT_LIGHT_TREE_BINDING) readonly buffer LightTreeBuffer {
    LightTreeNode items[];
} light_tree;

// The tree has at most 2^31 leaves: a traversal descends at most 31 levels.
const uint kRtslcMaxLevels = 31u;

// A cut node split into its real children, with their bounds at s: `first` takes the node's
// place in the cut, `second` (when `two`) is added. Bogus children hold no light and are dropped;
// a real node's left child is real (the real leaves come first), written for either.
struct RtslcSplit {
    uint first;
    float first_bound;
    bool two;
    uint second;
    float second_bound;
};

RtslcSplit rtslc_split(RtslcShading s, uint node, float min_distance2) {
    uint left = light_tree_left_child(node);
    uint right = light_tree_right_child(node);
    LightTreeNode left_node = light_tree.items[left];
    LightTreeNode right_node = light_tree.items[right];
    bool left_real = !light_tree_is_bogus(left_node);
    bool right_real = !light_tree_is_bogus(right_node);
    RtslcSplit split = RtslcSplit(right, 0.0, false, right, 0.0);
    if (left_real) {
        split.first = left;
        split.first_bound = rtslc_node_bound(s, left_node, min_distance2);
        if (right_real) {
            split.two = true;
            split.second_bound = rtslc_node_bound(s, right_node, min_distance2);
        }
    } else {
        split.first_bound = rtslc_node_bound(s, right_node, min_distance2);
    }
    return split;
}

// Selects the cut of at most min(cut_size, kRtslcMaxCutSize) nodes at shading point s: starting
// from the root, the cut node with the largest bound F I / max(d_min^2, eps^2) (rtslc_node_bound)
// is split into its children until the cut is full or holds only leaves. Every real child enters
// the cut, even one of zero weight at s: other pixels of the block see other weights, and
// leaving its lights out would lose their light there (bias). Bogus children are dropped: they
// hold no light. So the cut always partitions the real leaves. Ties between bounds go to the
// smaller node index, so the cut is a function of the tree and s alone. The tree must hold at
// least one real leaf. Returns the number of nodes in `cut`; `selected` is false when the loop
// ran out before the cut was done (lavapipe's loop limit: the caller counts it).
uint rtslc_select_cut(RtslcShading s, uint leaf_count, uint cut_size, float min_distance2,
                      out uint cut[kRtslcMaxCutSize], out bool selected) {
    float bound[kRtslcMaxCutSize];
    uint cut_nodes = 1u;
    cut[0] = 0u;  // the root: real, the tree has a light
    bound[0] = rtslc_node_bound(s, light_tree.items[0], min_distance2);
    uint first_leaf = leaf_count - 1u;
    uint target = min(cut_size, kRtslcMaxCutSize);
    // A split adds a node (at most n - 1 times) or, where a node has one real child, replaces it
    // by that child: only nodes on the path to the last real leaf have a bogus child, one per
    // level, so at most 31 such splits. 128 passes cannot run out before the cut is done.
    selected = false;
    for (uint pass = 0u; pass < 128u; ++pass) {
        if (cut_nodes >= target) {
            selected = true;
            break;
        }
        uint best = kRtslcNoNode;
        for (uint i = 0u; i < cut_nodes; ++i) {
            if (cut[i] >= first_leaf) {
                continue;  // a leaf cannot be split
            }
            if (best == kRtslcNoNode || bound[i] > bound[best] || (bound[i] == bound[best] && cut[i] < cut[best])) {
                best = i;
            }
        }
        if (best == kRtslcNoNode) {
            selected = true;  // only leaves left
            break;
        }
        RtslcSplit split = rtslc_split(s, cut[best], min_distance2);
        cut[best] = split.first;
        bound[best] = split.first_bound;
        if (split.two) {
            cut[cut_nodes] = split.second;
            bound[cut_nodes] = split.second_bound;
            ++cut_nodes;
        }
    }
    return cut_nodes;
}

// The cut of rtslc_select_cut with its samples shared out by bound (direct light through the
// tree): every slot of the cut holds a node, and a node gets as many of the
// min(cut_size, kRtslcMaxCutSize) slots as its bound earns. Starting from the root with one
// sample, the entry with the largest bound per sample (bound / samples) is refined: an inner node
// is split as rtslc_select_cut splits it, a leaf gets one more sample. Why: rtslc_select_cut gives
// every cut node one sample, so once a large emissive triangle close to the representative pixel
// is a leaf of the cut it keeps one area sample per pixel however many the pixel takes, while the
// flat power CDF gives it spp x its power share (the tree's error stopped falling as
// 1 / sqrt(spp) on irregular mesh lights, its variance in the pixels next to big lamps). VPL
// leaves (rtslc GI) gain nothing from a second sample of a point, so GI keeps rtslc_select_cut.
//
// `samples[i]` is entry i's sample count (>= 1, summing to the slots when `selected`); the nodes
// are distinct and still partition the real leaves. Ties go to the smaller node index, so the cut
// is a function of the tree and s alone. Returns the number of entries.
uint rtslc_select_cut_shared_out(RtslcShading s, uint leaf_count, uint cut_size, float min_distance2,
                                 out uint cut[kRtslcMaxCutSize], out uint samples[kRtslcMaxCutSize],
                                 out bool selected) {
    float bound[kRtslcMaxCutSize];
    uint entries = 1u, total = 1u;
    cut[0] = 0u;  // the root: real, the tree has a light
    samples[0] = 1u;
    bound[0] = rtslc_node_bound(s, light_tree.items[0], min_distance2);
    uint first_leaf = leaf_count - 1u;
    uint target = min(cut_size, kRtslcMaxCutSize);
    // Each pass adds a slot (at most target - 1 times) or replaces a node by its one real child
    // (at most 31 times, as in rtslc_select_cut): 128 passes cannot run out for target <= 64.
    selected = false;
    for (uint pass = 0u; pass < 128u; ++pass) {
        if (total >= target) {
            selected = true;
            break;
        }
        uint best = 0u;
        float best_share = bound[0] / float(samples[0]);
        for (uint i = 1u; i < entries; ++i) {
            float share = bound[i] / float(samples[i]);
            if (share > best_share || (share == best_share && cut[i] < cut[best])) {
                best = i;
                best_share = share;
            }
        }
        if (cut[best] >= first_leaf) {
            ++samples[best];
            ++total;
            continue;
        }
        RtslcSplit split = rtslc_split(s, cut[best], min_distance2);
        cut[best] = split.first;
        bound[best] = split.first_bound;
        if (split.two) {
            cut[entries] = split.second;
            bound[entries] = split.second_bound;
            samples[entries] = 1u;
            ++entries;
            ++total;
        }
    }
    return entries;
}

// How a traversal ended.
const uint kRtslcReachedLeaf = 0u;   // `node` is a leaf, reached with `path_probability`
const uint kRtslcDeadBranch = 1u;    // both children weigh 0: no light (the RTSLC paper sec. 3.2)
const uint kRtslcTraversalShort = 2u;  // the level loop ended early (lavapipe's loop limit)

struct RtslcTraversal {
    uint node;               // the node the traversal stopped at (a leaf when it reached one)
    float path_probability;  // the product of the child choices' probabilities: the leaf's pmf
    uint levels;             // levels descended
    uint status;             // kRtslcReachedLeaf, kRtslcDeadBranch or kRtslcTraversalShort
};

// The traversal from cut node `node` to a leaf (the RTSLC paper sec. 3.2) for the BRDF lobe `lobe`
// (gi_lobe.glsl; gi_lobe_both() without the glossy branch): one child per level with the eq. 1-2
// probabilities at s (rtslc_child_probability for the lobe), a fresh random number per level from
// `rng`. The glossy lobe steers each path by the perfect-reflection weights or by the lobe at the
// children's means (the SST paper sec. 4.2, gi_glossy_path_*), and its pmf is that mixture's. The pmf
// of the leaf reached is path_probability: the lobe's probability times the path's, exactly the
// probability of the path taken (each choice's probability is on rng_next_float's grid:
// rtslc_choose_left).
//
// The tree is the perfect tree whose root is light_tree.items[base] (`node` and the result's node
// are heap indices within it, light_tree.glsl): base 0 for a tree alone in the buffer, a bottom
// tree's node_base in a two-level tree (two_level_light_tree.glsl).
RtslcTraversal rtslc_traverse_in(RtslcShading s, uint base, uint node, uint leaf_count, float min_distance2,
                                 GiLobe lobe, inout Rng rng) {
    RtslcTraversal t = RtslcTraversal(node, lobe.probability, 0u, kRtslcTraversalShort);
    bool glossy = lobe.kind == kBrdfLobeGlossy;
    GiGlossyPath glossy_path = GiGlossyPath(true, 1.0, 1.0);
    if (glossy) {
        glossy_path = gi_glossy_path_start(rng);  // gi_lobe.glsl: the glossy lobe's two-strategy mixture
    }
    uint first_leaf = leaf_count - 1u;
    for (uint level = 0u; level <= kRtslcMaxLevels; ++level) {
        if (t.node >= first_leaf) {
            t.status = kRtslcReachedLeaf;
            break;
        }
        uint left = light_tree_left_child(t.node);
        LightTreeNode node_left = light_tree.items[base + left], node_right = light_tree.items[base + left + 1u];
        RtslcChildProbability choice = rtslc_child_probability(s, node_left, node_right, min_distance2, lobe.kind);
        RtslcChildProbability at_mean = choice;
        if (glossy) {
            at_mean = rtslc_child_probability(s, node_left, node_right, min_distance2, kGiWeightGlossyAtMean);
        }
        bool by_reflection = !glossy || glossy_path.by_reflection;
        // the RTSLC paper sec. 3.2: a dead branch (both children weigh 0) returns no light. Exactly 0
        // then: every light below has zero weight, so none of them could light s.
        if (by_reflection ? choice.dead : at_mean.dead) {
            t.status = kRtslcDeadBranch;
            break;
        }
        bool go_left = rtslc_choose_left(by_reflection ? choice.left : at_mean.left, rng_next_float(rng));
        if (glossy) {
            gi_glossy_path_step(glossy_path, choice.dead ? -1.0 : choice.left, at_mean.dead ? -1.0 : at_mean.left,
                                go_left);
        } else {
            t.path_probability *= rtslc_choice_probability(choice.left, go_left);
        }
        t.node = go_left ? left : left + 1u;
        ++t.levels;
    }
    if (glossy && t.status == kRtslcReachedLeaf) {
        t.path_probability = lobe.probability * gi_glossy_path_probability(glossy_path);
    }
    return t;
}

// rtslc_traverse_in over the tree alone in the buffer (root light_tree.items[0]).
RtslcTraversal rtslc_traverse(RtslcShading s, uint node, uint leaf_count, float min_distance2, GiLobe lobe,
                              inout Rng rng) {
    return rtslc_traverse_in(s, 0u, node, leaf_count, min_distance2, lobe, rng);
}

// The lobe-MIS traversal (one-sample MIS over the lobes, balance heuristic): it steers by the
// lobe chosen (`lobe`, diffuse or glossy, as rtslc_traverse does) but tracks the path's
// probability under both lobes at once, the diffuse one's and the glossy one's own mixture pmf
// (gi_glossy_path_*), and returns as path_probability q_d P_d(path) + q_g P_g(path): exactly the
// probability that a traversal from `node` reaches this leaf, whichever lobe it chose. The caller
// evaluates the whole BRDF at the leaf and divides by it. Why: with one lobe per sample, each
// lobe's estimate is weighed by 1 / q, and rtslc's leaf-only traversal was measured to lose to
// the whole BRDF by that split (README, glossy table). A child the unchosen lobe gives
// probability 0 (or a dead branch there) zeroes that lobe's term only; the chosen lobe's is > 0
// (its choices were sampled with it), so the sum is too. `q_glossy` is gi_glossy_lobe_probability.
RtslcTraversal rtslc_traverse_lobe_mis(RtslcShading s, uint node, uint leaf_count, float min_distance2, GiLobe lobe,
                                       float q_glossy, inout Rng rng) {
    RtslcTraversal t = RtslcTraversal(node, 0.0, 0u, kRtslcTraversalShort);
    bool glossy = lobe.kind == kBrdfLobeGlossy;
    // The diffuse choice draws no strategy: the glossy mixture's products do not depend on it.
    GiGlossyPath glossy_path = GiGlossyPath(true, 1.0, 1.0);
    if (glossy) {
        glossy_path = gi_glossy_path_start(rng);
    }
    float diffuse_path = 1.0;
    uint first_leaf = leaf_count - 1u;
    for (uint level = 0u; level <= kRtslcMaxLevels; ++level) {
        if (t.node >= first_leaf) {
            t.status = kRtslcReachedLeaf;
            break;
        }
        uint left = light_tree_left_child(t.node);
        LightTreeNode node_left = light_tree.items[left], node_right = light_tree.items[left + 1u];
        bool go_left;
        if (!rtslc_lobe_mis_step(s, node_left, node_right, min_distance2, glossy, glossy_path, diffuse_path, rng,
                                 go_left)) {
            t.status = kRtslcDeadBranch;
            break;
        }
        t.node = go_left ? left : left + 1u;
        ++t.levels;
    }
    if (t.status == kRtslcReachedLeaf) {
        t.path_probability =
            (1.0 - q_glossy) * diffuse_path + q_glossy * gi_glossy_path_probability(glossy_path);
    }
    return t;
}

// The probability of a power-only step (the RTSLC paper's I_j alone, no geometry): the left child's
// share of the two children's intensities, on u's grid as rtslc_child_probability's; 0 or 1 when
// one child holds no light, negative when neither does (a dead branch).
float rtslc_power_left(LightTreeNode left, LightTreeNode right) {
    float i_left = light_tree_is_bogus(left) ? 0.0 : left.intensity;
    float i_right = light_tree_is_bogus(right) ? 0.0 : right.intensity;
    return gi_child_probability(i_left, 1.0, i_right, 1.0);
}

// The defensive traversal (direct light through the tree): with probability
// `defensive` (a multiple of 2^-24, so that u < defensive picks it exactly) the path descends by
// intensity alone (rtslc_power_left), otherwise by the eq. 1-2 weights; both paths' probabilities
// are tracked at every step, and the pmf returned is the mixture's,
//     (1 - defensive) P_tree(path) + defensive P_power(path),
// exactly the probability that this traversal reaches the leaf (one-sample MIS, balance
// heuristic, as rtslc_traverse_lobe_mis does for the lobes). Why: the node holds no orientation
// (the RTSLC paper sec. 4), so a one-sided lamp 1 cm off a wall or ceiling, facing away from it, gets the
// largest weight the distance clamp allows at the wall points right behind it (cosine bound 1,
// d_min 1 cm), where it gives no light at all, and every other light's P_tree there shrinks by
// that lamp's share; the lights that do shine there are weighed by 1 / that tiny pmf: a heavy
// tail (tests/lighting's two-lamp case; on the many-lights scene's irregular mesh lights, which hang 1 cm off
// the ceiling and back wall, the mixture halves the variance, README). The power path's
// probability telescopes to I_leaf / I_node, so every light's pmf is at least `defensive` times
// its power share within the cut node, which is what the flat power CDF gives it over the whole
// scene: each sample's estimate is at most 1 / defensive times the power sampler's. Where the
// weights are good, the mixture costs at most a factor 1 / (1 - defensive) in variance.
RtslcTraversal rtslc_traverse_defensive_in(RtslcShading s, uint base, uint node, uint leaf_count,
                                           float min_distance2, float defensive, inout Rng rng) {
    RtslcTraversal t = RtslcTraversal(node, 0.0, 0u, kRtslcTraversalShort);
    bool by_power = rng_next_float(rng) < defensive;
    float tree_path = 1.0, power_path = 1.0;
    uint first_leaf = leaf_count - 1u;
    for (uint level = 0u; level <= kRtslcMaxLevels; ++level) {
        if (t.node >= first_leaf) {
            t.status = kRtslcReachedLeaf;
            break;
        }
        uint left = light_tree_left_child(t.node);
        LightTreeNode node_left = light_tree.items[base + left], node_right = light_tree.items[base + left + 1u];
        RtslcChildProbability weights = rtslc_child_probability(s, node_left, node_right, min_distance2);
        float power = rtslc_power_left(node_left, node_right);
        // A dead branch of the strategy steering returns no light (exactly 0: under eq. 1-2 every
        // light below has zero weight, under power zero intensity); the other strategy's path
        // probability is then simply not needed.
        if (by_power ? power < 0.0 : weights.dead) {
            t.status = kRtslcDeadBranch;
            break;
        }
        bool go_left = rtslc_choose_left(by_power ? power : weights.left, rng_next_float(rng));
        tree_path *= weights.dead ? 0.0 : rtslc_choice_probability(weights.left, go_left);
        power_path *= power < 0.0 ? 0.0 : rtslc_choice_probability(power, go_left);
        t.node = go_left ? left : left + 1u;
        ++t.levels;
    }
    if (t.status == kRtslcReachedLeaf) {
        t.path_probability = (1.0 - defensive) * tree_path + defensive * power_path;
    }
    return t;
}

// The traversals for the whole BRDF (direct light's, and every sample without the glossy branch).
RtslcTraversal rtslc_traverse(RtslcShading s, uint node, uint leaf_count, float min_distance2, inout Rng rng) {
    return rtslc_traverse(s, node, leaf_count, min_distance2, gi_lobe_both(), rng);
}

RtslcTraversal rtslc_traverse_in(RtslcShading s, uint base, uint node, uint leaf_count, float min_distance2,
                                 inout Rng rng) {
    return rtslc_traverse_in(s, base, node, leaf_count, min_distance2, gi_lobe_both(), rng);
}

#endif
