#ifndef VPLKIT_RTSLC_LOBE_MIS_GLSL
#define VPLKIT_RTSLC_LOBE_MIS_GLSL

// One level of the lobe-MIS descent, shared by the light tree's (rtslc_traverse_lobe_mis) and the
// SST's (sst_traverse_lightcuts_lobe_mis): steers by the lobe chosen, the diffuse weights or the
// glossy mixture's strategy, and multiplies both lobes' path probabilities by this choice's.
// Returns false at a dead branch (the steering lobe gives both children 0); go_left is then unset.
//
// Include vplkit/rtslc.glsl and vplkit/gi_lobe.glsl (and what they need) first.

bool rtslc_lobe_mis_step(RtslcShading s, LightTreeNode node_left, LightTreeNode node_right, float min_distance2,
                         bool glossy, inout GiGlossyPath glossy_path, inout float diffuse_path, inout Rng rng,
                         out bool go_left) {
    RtslcChildProbability diffuse = rtslc_child_probability(s, node_left, node_right, min_distance2, kBrdfLobeDiffuse);
    RtslcChildProbability reflection =
        rtslc_child_probability(s, node_left, node_right, min_distance2, kBrdfLobeGlossy);
    RtslcChildProbability at_mean =
        rtslc_child_probability(s, node_left, node_right, min_distance2, kGiWeightGlossyAtMean);
    RtslcChildProbability steer = !glossy ? diffuse : glossy_path.by_reflection ? reflection : at_mean;
    go_left = false;
    if (steer.dead) {
        return false;
    }
    go_left = rtslc_choose_left(steer.left, rng_next_float(rng));
    diffuse_path *= diffuse.dead ? 0.0 : rtslc_choice_probability(diffuse.left, go_left);
    gi_glossy_path_step(glossy_path, reflection.dead ? -1.0 : reflection.left, at_mean.dead ? -1.0 : at_mean.left,
                        go_left);
    return true;
}

#endif
