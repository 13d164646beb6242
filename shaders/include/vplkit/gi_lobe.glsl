#ifndef VPLKIT_GI_LOBE_GLSL
#define VPLKIT_GI_LOBE_GLSL

// The lobe choice of the SST paper sec. 4.2: before each traversal, a sample picks the diffuse or the
// glossy lobe of the BRDF (brdf_evaluate_lobe) with probability from the magnitude of each lobe's
// material term, traverses with that lobe's child weights (the glossy lobe: the perfect-reflection
// heuristic, gi_glossy_direction, and no substitutes: it goes to a leaf VPL), evaluates only that
// lobe and divides by the lobe's probability. The two lobes add up to the BRDF, so the estimate
// stays that of the whole BRDF: sum over lobes q_L * (f_L / q_L) = f.
//
// Where a cut or a mock cut shares a traversal's start between pixels, the start node's share of
// the estimate is the traversal's over its path probability, and that path probability starts at
// the lobe's: GiLobe::probability is the factor every traversal begins with (sst_sample_at).
//
// kGlossyLobe turns the branch on (the planner sets it when a material of the scene can be smoother
// than kGlossyMaxRoughness); off, every sample takes kBrdfLobeBoth with probability 1, draws no
// random number and runs the same code as without this file: a matte scene's frame is
// bit-identical with the branch on or off, and its shaders pay nothing for it.
//
// Needs vplkit/brdf.glsl, vplkit/gi_bounds.glsl and vplkit/rng.glsl included first.

layout(constant_id = 21) const bool kGlossyLobe = false;
// Receivers at least this rough keep the whole BRDF per sample, as without the branch. Why 0.5:
// GGX's peak D(h = n) = 1 / (pi alpha^2), alpha = roughness^2, times F(0.04) rises above a
// diffuse term of albedo 0.5 (0.5 / pi) only where alpha^2 < 0.08, i.e. roughness < 0.53: rougher,
// the glossy lobe is no brighter anywhere than the diffuse one and the mean direction of a
// cluster serves both. vplkit::glossy_max_roughness() on the host reads this default.
layout(constant_id = 22) const float kGlossyMaxRoughness = 0.5;

struct GiLobe {
    uint kind;          // kBrdfLobeBoth, kBrdfLobeDiffuse or kBrdfLobeGlossy
    float probability;  // of choosing it (1 for kBrdfLobeBoth)
};

GiLobe gi_lobe_both() {
    return GiLobe(kBrdfLobeBoth, 1.0);
}

// Whether a receiver of this roughness chooses a lobe per sample (never a Lambertian one).
bool gi_lobe_choice_applies(float roughness) {
    return kGlossyLobe && roughness >= 0.0 && roughness < kGlossyMaxRoughness;
}

// The probability of the glossy lobe: each lobe's magnitude (luminances), the diffuse
// (1 - metallic) (1 - F_avg) base colour, F_avg = 0.04 + 0.96 / 21 the hemispherical mean of
// Schlick's F(0.04), and the glossy F(f0, n.wo) with f0 = mix(0.04, base colour, metallic).
// Why F_avg and not F(0.04, n.wo) in the diffuse term: the diffuse lobe's Fresnel factor is
// 1 - F(0.04, wo.h), and h lies between wo and the light, so at a grazing view it stays far from
// F(n.wo) ~ 1; with F(n.wo) the diffuse lobe's probability fell towards 0 at grazing views while
// its value did not (a dark floor seen at n.wo = 0.1: probability 0.05, weight 20). Measured on the
// glossy set-up (96 x 96, 16 spp, 3 seeds) the change is small: tonemapped RMSE 0.3% lower for
// sst, rtslc and hybrid. A lobe that is 0 everywhere (the
// diffuse one of a metal or of a black base colour) gets exactly 0; otherwise the probability is
// on rng_next_float's 2^-24 grid in [2^-24, 1 - 2^-24] (gi_grid_probability), so a lobe that can
// be non-zero is always chosen sometimes and chosen with exactly the probability divided by.
float gi_glossy_lobe_probability(vec3 n, vec3 wo, vec3 base_color, float metallic) {
    const vec3 luminance = vec3(0.2126, 0.7152, 0.0722);
    const float mean_dielectric_fresnel = 0.04 + 0.96 / 21.0;
    float n_dot_v = clamp(dot(n, wo), 0.0, 1.0);
    float diffuse = (1.0 - metallic) * (1.0 - mean_dielectric_fresnel) * dot(base_color, luminance);
    float glossy = dot(schlick_fresnel(mix(vec3(0.04), base_color, metallic), n_dot_v), luminance);
    if (!(diffuse > 0.0)) {
        return 1.0;
    }
    if (!(glossy > 0.0)) {
        return 0.0;
    }
    return gi_grid_probability(glossy / (diffuse + glossy));
}

// The lobe of one sample and its probability (the sample / pmf pair is gi_lobe_probability).
// Draws one random number only where the choice applies.
GiLobe gi_choose_lobe(vec3 n, vec3 wo, vec3 base_color, float roughness, float metallic, inout Rng rng) {
    if (!gi_lobe_choice_applies(roughness)) {
        return gi_lobe_both();
    }
    float q = gi_glossy_lobe_probability(n, wo, base_color, metallic);
    // u < q: never for q = 0, always for q = 1 (u in [0, 1)).
    return rng_next_float(rng) < q ? GiLobe(kBrdfLobeGlossy, q) : GiLobe(kBrdfLobeDiffuse, 1.0 - q);
}

// The glossy lobe's traversal. the SST paper sec. 4.1's perfect-reflection weights alone
// (kBrdfLobeGlossy) were measured to leave a heavy tail: in the unbiasedness test
// (tests/gi/test_glossy_lobe.cpp) a metal of roughness 0.35 whose reflection ray leaves the room
// read 10x low over 100 seeds (worst z 166) and right over 400 (z 3.7): a box that the ray passes
// near wins every level although its VPLs lie off the lobe, and the VPL that holds the light is
// drawn rarely and weighed hugely. So each glossy traversal is one sample of a two-strategy
// mixture (one-sample MIS, balance heuristic): with probability kGlossyReflectionFraction it
// steers by the perfect-reflection weights, otherwise by the glossy lobe towards each cluster's
// mean (kGiWeightGlossyAtMean, the weights the whole BRDF uses), and the path's probability is
// the mixture's, (1 - b) P_reflection + b P_mean, both products tracked along the one path taken.
// The estimate is no worse than twice either strategy's alone, and has the tail of neither.
const float kGlossyReflectionFraction = 0.5;

struct GiGlossyPath {
    bool by_reflection;        // the strategy this traversal steers by
    float reflection;          // the path's probability under each strategy
    float at_mean;
};

GiGlossyPath gi_glossy_path_start(inout Rng rng) {
    return GiGlossyPath(rng_next_float(rng) < kGlossyReflectionFraction, 1.0, 1.0);
}

// The left child's probability to draw with (u < p), from the two strategies' probabilities
// (negative: dead branch under that strategy).
float gi_glossy_path_left(GiGlossyPath path, float p_reflection, float p_at_mean) {
    return path.by_reflection ? p_reflection : p_at_mean;
}

// One level down: both strategies' probabilities of the child taken (0 where one saw a dead branch).
void gi_glossy_path_step(inout GiGlossyPath path, float p_reflection, float p_at_mean, bool go_left) {
    path.reflection *= p_reflection < 0.0 ? 0.0 : go_left ? p_reflection : 1.0 - p_reflection;
    path.at_mean *= p_at_mean < 0.0 ? 0.0 : go_left ? p_at_mean : 1.0 - p_at_mean;
}

// The probability of the path taken under the mixture.
float gi_glossy_path_probability(GiGlossyPath path) {
    return kGlossyReflectionFraction * path.reflection + (1.0 - kGlossyReflectionFraction) * path.at_mean;
}

float gi_lobe_probability(vec3 n, vec3 wo, vec3 base_color, float roughness, float metallic, uint kind) {
    if (!gi_lobe_choice_applies(roughness)) {
        return kind == kBrdfLobeBoth ? 1.0 : 0.0;
    }
    float q = gi_glossy_lobe_probability(n, wo, base_color, metallic);
    return kind == kBrdfLobeGlossy ? q : kind == kBrdfLobeDiffuse ? 1.0 - q : 0.0;
}

#endif
