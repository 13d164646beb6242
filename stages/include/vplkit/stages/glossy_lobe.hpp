#pragma once
// The glossy branch of the tree samplers (shaders/include/vplkit/gi_lobe.glsl, the SST paper sec. 4.2):
// with it, a receiver smoother than kGlossyMaxRoughness picks the diffuse or the glossy lobe of
// its BRDF per sample (glossy: perfect-reflection child weights, no substitutes, a leaf VPL).
// A specialization constant of sst gi, hybrid gi and rtslc gi: without it (the default) the
// branch is compiled out, and a frame with it on differs only at such receivers.

#include "vplkit/shaders/sst_gi.hpp"

namespace vplkit::stages {

// Receivers at least this rough keep the whole BRDF per sample (gi_lobe.glsl says why 0.5): the
// shader's own default, so the planner's rule and the shaders cannot disagree.
inline constexpr float kGlossyMaxRoughness = shaders::sst_gi::Spec{}.kGlossyMaxRoughness;

// The branch's settings in SstGiOptions, HybridOptions and RtslcOptions.
struct GlossyLobeOptions {
    bool enabled = false;  // off: compiled out (the planner turns it on for glossy scenes)
    // Receivers smoother than this choose a lobe per sample, >= 0 (tests raise it past 1 to make
    // every receiver choose).
    float max_roughness = kGlossyMaxRoughness;
};

// Throws vplkit::Error naming `stage` for a max_roughness that is negative or not finite.
void validate(const GlossyLobeOptions& options, const char* stage);

// `spec` with the branch's constants set (the shader must include gi_lobe.glsl).
template <typename Spec>
Spec glossy_lobe_spec(const GlossyLobeOptions& options, Spec spec) {
    spec.kGlossyLobe = options.enabled ? VK_TRUE : VK_FALSE;
    spec.kGlossyMaxRoughness = options.max_roughness;
    return spec;
}

}  // namespace vplkit::stages
