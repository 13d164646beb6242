#pragma once
// The effects planner: which stages a frame runs, decided from its scene (lights, emissive
// triangles) and its settings (method, VPL source, resolution) and from what the previous frame
// left (VPLs and trees that are still valid), with the reason for every stage kept or left out.
// The Renderer records exactly the stages the plan runs; `vplkit plan` prints the plan.

#include "vplkit/pass_list.hpp"
#include "vplkit/render_settings.hpp"
#include "vplkit/scene.hpp"

#include <optional>
#include <string>
#include <vector>

namespace vplkit {

namespace scene {
struct Scene;
}

// A frame's stages, in the order they run.
enum class FrameStage {
    gbuffer,          // raster pass: position, normals, material, emission
    direct_light,     // emission, background, punctual lights with shadow rays
    direct_emissive,  // area-light sampling of emissive triangles (the flat sampler)
    direct_tree,      // the light tree over emitters, point and spot lights, and sampling through it
    vpl_paths,        // instant radiosity: light paths through the BVH
    brsm_vpls,        // reflective shadow maps and BRSM placement, light by light
    smc_vpls,         // one SMC update of the persistent VPL set (the SMC paper Alg. 1)
    flc_vpls,         // forward light cuts: candidates, decimation, compaction, light at the kept VPLs
    vpl_sort,         // keys, sort, leaves in sorted order
    light_tree,       // the RTSLC light tree
    sst,              // the stochastic substitute tree
    gi_downsample,    // the half-resolution G-buffer
    gi_exact,
    gi_sst,
    gi_rtslc,
    gi_hybrid,
    gi_flc,       // forward light cuts' splatting (raster pipeline, additive blending)
    gi_upsample,  // joint bilateral upsampling to full resolution
    denoise,      // demodulation, temporal accumulation, a-trous, remodulation (stages/denoise.hpp)
    compose,      // direct + indirect
    tonemap,
};

// "direct light", "gi hybrid", ... (what `vplkit plan` prints).
const char* stage_name(FrameStage stage);

// The tag the renderer gives every pass of a stage (StepList::set_tag): a pass belongs to the
// stage whose tag it carries, whatever its name. 0 (untagged) is no stage.
constexpr uint32_t stage_tag(FrameStage stage) {
    return uint32_t(stage) + 1;
}
inline bool stage_owns_pass(FrameStage stage, const PassTiming& pass) {
    return pass.tag == stage_tag(stage);
}

struct PlannedStage {
    FrameStage stage;
    bool runs = false;
    std::string reason;  // why it runs, or why it is left out
};

// Which pose of a scene's geometry and lights a frame sees: each count grows when a renderer's
// update_pose moves vertices (geometry) or lights (renderer.hpp). Work made at another version
// is not reused.
struct SceneVersion {
    uint32_t geometry = 0;
    uint32_t lights = 0;
    bool operator==(const SceneVersion&) const = default;
};

// What the previous frame left that this one may reuse.
struct ReusableWork {
    std::string vpl_key;      // the VPL set the cached VPLs are (empty: none cached)
    bool light_tree = false;  // the cached VPLs' trees, built with the cached tree key
    bool sst = false;
    std::string tree_key;
    bool denoise_history = false;  // the denoiser holds a previous frame of this size
    SceneVersion vpl_scene;        // the pose the cached VPLs and trees were made at
    SceneVersion history_scene;    // the pose of the denoiser's history
    // The direct light tree's pose (none: not built yet); the tree is over lights and emissive
    // triangles, so it is rebuilt when lights move, or geometry with emissive triangles does.
    std::optional<SceneVersion> direct_tree_scene;
};

struct FramePlan {
    std::vector<PlannedStage> stages;                    // every stage, in frame order
    VplSource vpl_source = VplSource::ir;                // the source chosen (VplSource::automatic resolved)
    DirectSampler direct_sampler = DirectSampler::flat;  // the sampler chosen (automatic resolved)
    bool reuse_vpls = false;                             // the previous frame's VPLs serve this frame
    bool reuse_trees = false;                            // and its trees
    // The direct light tree is built this frame (first use, or the lights or emitters moved).
    bool build_direct_tree = false;
    // The denoiser's history is dropped: the geometry moved and RenderSettings::denoise_motion is
    // drop. Lights moving keep it; geometry moving too with follow (the default: the G-buffer's
    // motion finds each point's history) and camera_only (for comparisons: it leaves a trail).
    bool drop_denoise_history = false;
    std::string vpl_key;             // this frame's VPL set
    std::string tree_key;            // this frame's tree settings
    std::vector<std::string> notes;  // e.g. "the scene has no light: the image would be black"
    // The glossy branch of sst, rtslc and hybrid (stages/glossy_lobe.hpp): compiled in or out,
    // and why (the materials that turned it on).
    bool glossy_branch = false;
    std::string glossy_reason;

    bool runs(FrameStage stage) const;
    // One line: "plan: gbuffer, direct light, ... ; left out: direct emissive, ..."
    std::string summary() const;
    // Every stage with its reason, a line each.
    std::string describe() const;
};

// A material that can be smoother than a roughness limit, and the smoothest it can be: its
// roughness factor times the smallest roughness (green) texel of its metallic-roughness texture.
struct GlossyMaterial {
    std::string name;
    float min_roughness = 1.0f;
};
// The scene's materials whose roughness can fall below `max_roughness`, in the scene's order
// (a Lambertian material, `--brdf lambert`, never does).
std::vector<GlossyMaterial> glossy_materials(const scene::Scene& scene, float max_roughness);

// The key of the VPL set a frame with these settings places: everything the VPLs depend on
// (source, budget, bounces, seed, BRSM options; for BRSM also the view and size, since it places
// VPLs where the camera sees their light).
std::string vpl_set_key(const RenderSettings& settings, VplSource source, const std::string& view_key);
// The key of the trees over a VPL set: the SST thresholds.
std::string tree_settings_key(const RenderSettings& settings);

// The plan of one frame. `view_key` names the camera and size (the Renderer's), `previous` what
// the last frame left. Pure: no device work.
// `now` is the pose the frame sees (a renderer's scene version).
FramePlan plan_frame(const scene::Scene& scene, const RenderSettings& settings, const std::string& view_key,
                     const ReusableWork& previous = {}, const SceneVersion& now = {});

}  // namespace vplkit
