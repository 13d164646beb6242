#pragma once
// What a frame is asked to do (RenderSettings: size, the indirect-light method and its options,
// the VPL source): read by the planner (planner.hpp) and the renderer (renderer.hpp), which
// includes this header, so neither needs the other.
//
// The runtime's messages (errors, the planner's reasons) name a setting by its member path in
// backquotes with its value after it, "`vpl_source` ir", "`sst.nu_min`", and the scene's lights as
// "`scene.lights`": the library speaks its own terms, and a front end rewrites these names to its
// own (the CLI to its flags: samples/vplkit/setting_flags.cpp).

#include "vplkit/stages/brsm.hpp"
#include "vplkit/stages/denoise.hpp"
#include "vplkit/stages/hybrid_gi.hpp"
#include "vplkit/stages/smc.hpp"
#include "vplkit/stages/sst.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <optional>

namespace vplkit {

// How indirect light is computed. What each method reads and takes: its row in the method table
// (gi_methods.hpp), in this order.
enum class GiMethod {
    none,    // direct light only
    exact,   // every VPL at every pixel with a shadow ray each: the ground truth
    sst,     // stochastic substitute tree traversals from the root (the SST paper)
    rtslc,   // real-time stochastic lightcuts: a cut per block, traversals to leaves (the RTSLC paper)
    hybrid,  // the thesis method: shallow SST cuts per block, blended, early-stop traversals (the thesis)
    flc,     // forward light cuts (the FLC paper): a VPL per kept triangle, splatted unshadowed, one bounce
};

// The method's name in the method table (gi_methods.hpp): "direct" for none.
const char* gi_method_name(GiMethod method);

// How direct light from emissive triangles, point and spot lights is sampled (directional lights
// are evaluated one by one either way).
enum class DirectSampler {
    flat,   // point and spot lights one by one, emissive triangles from one power CDF
    tree,   // one light tree over all of them, stochastic lightcuts (the RTSLC paper; direct_light_tree.hpp)
    tree2,  // the same with a two-level tree: a bottom tree per mesh light under a top tree (the RTSLC paper sec. 3.1)
    automatic,  // the planner's choice: the tree above kDirectTreeMinLights such lights
};

// "flat", "tree", "tree2", "auto".
const char* direct_sampler_name(DirectSampler sampler);

// The planner samples direct light through the tree when the scene has more emissive triangles,
// point and spot lights together than this ("more than a handful"): with a few, the
// flat sampler evaluates each punctual light exactly and has few emitters to choose from.
inline constexpr uint32_t kDirectTreeMinLights = 8;

// Where the VPLs come from.
enum class VplSource {
    ir,         // instant radiosity: light paths through the BVH, a VPL per diffuse hit (multi-bounce)
    brsm,       // bidirectional reflective shadow maps: one-bounce VPLs where the camera sees their light
    smc,        // sequential Monte Carlo instant radiosity (the SMC paper): a VPL set kept across frames,
                // at most M_max moved per frame, on the surfaces the camera sees indirectly
    automatic,  // the planner's choice: BRSM for one bounce from punctual lights, else light paths
};

// Filtering of the indirect light (stages/denoise.hpp; the runtime's Denoiser keeps the history).
enum class DenoiseMode {
    off,       // the raw Monte Carlo frame
    temporal,  // reprojected temporal accumulation only (a running mean on a static camera)
    svgf,      // temporal accumulation, then the variance-guided a-trous filter (SVGF)
};

// "off", "temporal", "svgf".
const char* denoise_mode_name(DenoiseMode mode);

// How the denoiser's history meets geometry that moved (RenderSettings::denoise_motion).
enum class DenoiseMotion {
    follow,       // reprojected with the G-buffer's motion: each point's history where it was
    camera_only,  // reprojected with the camera alone (a moved object drags its old light along)
    drop,         // dropped whenever geometry moved (no trail, and no averaging while it moves)
};

// The glossy branch of sst, rtslc and hybrid (stages/glossy_lobe.hpp, the SST paper sec. 4.2): a glossy
// receiver picks the diffuse or the glossy lobe per sample. automatic: the planner turns it on
// when a material of the scene can be smoother than stages::kGlossyMaxRoughness.
enum class GlossyBranch { automatic, on, off };

// The default suitability threshold sigma_max (the thesis eq. 5.6) as a fraction of the scene scale:
// the thesis' 0.3 in its Sponza, whose scale is ~25 (0.3 / 25.5). Measured (lavapipe, 320x180,
// 4096 BRSM VPLs, mean indirect against exact): the absolute 0.3 in the Breakfast room (scale ~2.3,
// so 13% of it) merged clusters thick enough that their substitutes lost 10% of the light (sst
// 0.90, hybrid 0.93); 1.2% of its scale (0.028) gives sst 0.99-1.00, hybrid 0.97, and lower RMSE.
inline constexpr float kSigmaMaxSceneFraction = 0.012f;

struct RenderSettings {
    uint32_t width = 640;
    uint32_t height = 360;
    float exposure = 1.0f;  // linear scale before the tone curve (unless auto_exposure)
    // The scale from the frame's own radiance instead (auto_exposure.hpp); RenderedImage::exposure
    // is the one used.
    bool auto_exposure = false;
    // Anti-aliasing on a static camera (antialias.hpp): the G-buffer of frame `frame` > 0 is
    // rastered with a Halton(2,3) sub-pixel offset (frame 0 at the pixel centres, as without it),
    // and the image is the mean of the frames since frame 0 on this camera (direct light; the
    // indirect light too, unless the denoiser accumulates it).
    bool antialias = false;
    glm::vec3 background{0.0f};  // radiance where no surface was drawn
    // Samples per pixel of sampled direct light. flat: area samples of the emissive triangles
    // (averaged); tree: cut nodes per block, one light sample each (summed), 1..64.
    uint32_t direct_samples = 16;
    DirectSampler direct_sampler = DirectSampler::automatic;
    // tree: interleaved sampling over m x m sub-blocks of the 8 x 8 cut blocks (1: off; m divides
    // 8, m^2 <= direct_samples), reconstructed from similar neighbours (an approximation).
    uint32_t direct_interleave = 1;
    uint32_t seed = 0;  // the same seed gives the same image
    GiMethod method = GiMethod::none;
    VplSource vpl_source = VplSource::automatic;
    uint32_t vpl_paths = 4096;  // ir: light paths traced for VPLs
    uint32_t vpl_bounces = 2;   // ir: surface hits per path at most
    // exact: the 1/d^2 clamp's d_min over the scene scale (stages::ExactGiOptions::
    // min_distance_fraction): 0.01, the sampling methods' own; 0: unclamped, as a path tracer.
    float exact_min_distance_fraction = 0.01f;
    // brsm: its options (vpl_count is the VPL budget over all punctual lights; the seed is
    // replaced by `seed`), and the side of each light's RSM face.
    stages::BrsmOptions brsm;
    uint32_t rsm_resolution = 512;
    // smc: its options (budget I, M_max, resampling ratio, radiosity samples and bounces; the
    // seed is replaced by `seed`), and the updates run before the first frame's (the paper runs
    // 100 so the first frame is already well distributed; each is a whole update).
    stages::SmcOptions smc;
    uint32_t smc_warmup = 100;
    // sst, rtslc, hybrid: samples per pixel (sst: traversals from the root, averaged; rtslc and
    // hybrid: the cut size, one traversal per cut node, summed), 1..64.
    uint32_t samples_per_pixel = 8;
    uint32_t block_size = 8;  // rtslc, hybrid: pixels along a cut block's side, 1..32
    uint32_t interleave = 1;  // rtslc: interleaved sampling over m x m sub-blocks (1: off)
    // The frame counter: sst, rtslc and hybrid draw other random numbers in each frame (for
    // temporal accumulation); rtslc also rotates its interleaved shares. The VPLs follow `seed`.
    // Frame 0 also starts the denoiser's history afresh (--denoise).
    uint32_t frame = 0;
    bool mock_cuts = true;  // hybrid: mock cuts where no block is alike (false: root traversals)
    // hybrid: the traversal below the cut nodes (lightcuts: the thesis' comparison protocol).
    stages::HybridTraversal hybrid_traversal = stages::HybridTraversal::substitute;
    // Every stage that can run for the method runs (direct emissive light without emitters, both
    // trees) and nothing is reused from the previous frame: the planner's baseline (planner.hpp).
    bool force_all_stages = false;
    // A frame whose VPL set and tree settings equal the previous frame's reuses its VPLs and
    // trees (the scene's geometry and lights never change within a renderer). false: rebuild
    // every frame (benchmarks that time the whole pipeline).
    bool reuse_static_work = true;
    GlossyBranch glossy_branch = GlossyBranch::automatic;  // sst, rtslc, hybrid
    stages::SstOptions sst;  // sst, hybrid: the suitability thresholds nu_min, sigma_max (absolute)
    // sst, hybrid: when set (the default), sst.sigma_max is replaced by this fraction of the scene
    // scale (the BVH's largest coordinate magnitude), so the threshold means the same in a room
    // and in a hall, in metres and in millimetres; unset: sst.sigma_max as given. See
    // kSigmaMaxSceneFraction.
    std::optional<float> sigma_max_scene_fraction = kSigmaMaxSceneFraction;
    // Indirect light computed on a half-resolution G-buffer (every second pixel) and brought to
    // full resolution by joint bilateral upsampling (the thesis ch. 6); any method but none.
    bool half_resolution_gi = false;
    // Indirect light filtered (demodulated, accumulated over frames with reprojection, a-trous)
    // before compose; the history lives in the Renderer from frame to frame.
    DenoiseMode denoise = DenoiseMode::off;
    stages::DenoiseOptions denoise_options;  // scene_scale is the renderer's (the BVH's)
    // How the denoiser's history meets geometry that update_pose moved: follow reprojects it with
    // the G-buffer's motion (each point's history where it was in the previous frame's pose);
    // camera_only with the camera alone (a moved object drags its old light along: for
    // comparisons); drop starts the history again whenever geometry moved (no trail, no averaging).
    DenoiseMotion denoise_motion = DenoiseMotion::follow;
    // Generate the VPLs (by vpl_source, whatever the method), return them in RenderedImage::vpls
    // with the G-buffer's positions, and compute no indirect light: for looking at the VPLs.
    bool vpls_only = false;
    // flc (the FLC paper): the partition's levels N + 1 and ratio mu (S_k = S_0 mu^k), and N_avg, about
    // how many VPLs at least D_near away light each point (eq. 1: S_0 = 4 pi D_near^2 / N_avg, D_near
    // = 0.2 x the scene radius): flc's quality knob, its VPL count grows with it. Emitter samples:
    // area samples of the emissive triangles per VPL for its light.
    uint32_t flc_levels = 8;  // with mu 2: D_N = 0.2 x 2^3.5 = 2.26 scene radii, past the scene diameter
    float flc_mu = 2.0f;
    float flc_vpls_per_point = 64.0f;
    uint32_t flc_emitter_samples = 4;
    // flc: n x n interleaved sub-tiles (the FLC paper sec. 6; 1: off): the splat's cost / n^2, then
    // untiling and a geometry-aware n x n blur.
    uint32_t flc_subtiles = 1;
    // Also return what a layered image file holds beside the light: RenderedImage::albedo, normal,
    // depth and, with a denoiser, indirect_variance. Three or four more downloads a frame.
    bool read_back_aovs = false;
    // Called during long indirect-light work with (done, total) units of work.
    std::function<void(uint32_t done, uint32_t total)> progress;
    // Called during the SMC warm-up with (updates done, updates in all).
    std::function<void(uint32_t done, uint32_t total)> smc_warmup_progress;
};

// Throws vplkit::Error naming the first bad sampling option of `settings` (samples per pixel,
// block size, interleave, SST thresholds) for its method; render() checks them first too, so a
// bad option fails before any work, whether or not the frame gets VPLs.
void validate_gi_settings(const RenderSettings& settings);
// Throws vplkit::Error naming the first bad flc option (levels, mu, N_avg, emitter samples, half resolution).
void validate_flc_settings(const RenderSettings& settings);

// `settings` with the scene-relative thresholds made absolute for a scene of `scene_scale`
// (sst.sigma_max from sigma_max_scene_fraction, when set); render() does this first.
RenderSettings with_scene_relative_thresholds(RenderSettings settings, float scene_scale);

}  // namespace vplkit
