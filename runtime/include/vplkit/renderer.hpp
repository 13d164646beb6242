#pragma once
// A whole frame: the G-buffer raster pass, direct light from punctual lights and from emissive
// triangles (area-light sampling) with BVH shadow rays, VPLs and indirect light by the chosen
// method (optionally at half resolution), the tonemap; what `vplkit render` runs. Scene data is uploaded and the BVH
// built once, at construction; render() can then be called for any camera and size. A scene that
// moves (scene::PosableScene) is followed with update_pose(), which uploads only what moved.

#include "vplkit/antialias.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/bvh_gpu_build.hpp"
#include "vplkit/denoiser.hpp"
#include "vplkit/gpu_light_tree.hpp"
#include "vplkit/gpu_lights.hpp"
#include "vplkit/gpu_pose.hpp"
#include "vplkit/gpu_two_level_light_tree.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/render_settings.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_pose.hpp"
#include "vplkit/stages/brsm.hpp"
#include "vplkit/stages/gi_counters.hpp"
#include "vplkit/stages/sst.hpp"
#include "vplkit/smc_state.hpp"
#include "vplkit/vpl_tracing_buffers.hpp"
#include "vplkit/stages/upsample.hpp"
#include "vplkit/vpl_trees.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace vplkit {

class Context;
class Image;
class FrameRecording;
struct GbufferImages;

// One VPL as the host sees it (RenderedImage::vpls).
struct VplPoint {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f};
    glm::vec3 flux{0.0f};
};

struct RenderedImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba8;           // tonemapped sRGB, rows top to bottom
    float exposure = 1.0f;                // the scale the tone curve was given (settings' or automatic)
    std::vector<float> radiance;          // linear RGB, 3 floats per pixel, rows top to bottom: direct + indirect
    std::vector<float> direct;            // the direct part alone (same layout)
    std::vector<float> indirect;          // the indirect part alone (zero with GiMethod::none)
    uint32_t vpl_count = 0;               // VPLs the indirect light came from
    std::vector<VplPoint> vpls;           // with vpls_only: the VPLs
    std::vector<float> gbuffer_position;  // with vpls_only: xyz + covered (1/0), 4 floats per pixel
    std::vector<std::string> notes;       // what a user should know about this frame (e.g. a light without VPLs)
    uint32_t dropped_pixels = 0;          // pixels where a non-finite VPL contribution was left out
    std::vector<PassTiming> timings;      // GPU time per pass
    double exact_gi_wall_ms = 0.0;        // GiMethod::exact: the gather's host wall clock (ExactGiResult::wall_ms)
    stages::GiCounts gi_counts;           // sst, rtslc, hybrid: traversals, levels, dropped samples, mock cuts
    DirectSampler direct_sampler = DirectSampler::flat;  // how direct light was sampled (the plan's choice)
    stages::GiCounts direct_counts;                      // the tree sampler's traversals, levels, dropped samples
    stages::UpsampleCounts upsample_counts;              // half_resolution_gi: pixels no similar sample reached
    float sst_sigma_max = 0.0f;  // sst, hybrid: the sigma_max the tree was built with (world units)
    uint32_t gi_width = 0;       // the size indirect light was computed at
    uint32_t gi_height = 0;
    std::string plan_summary;              // the frame's plan in one line (FramePlan::summary, planner.hpp)
    std::vector<std::string> stages_run;   // the stages the plan ran (stage_name), in order
    VplSource vpl_source = VplSource::ir;  // where this frame's VPLs came from (automatic resolved)
    bool reused_vpls = false;              // the previous frame's VPLs (and, below, trees) served this one
    bool reused_trees = false;
    std::optional<SmcCounts> smc;    // --vpl-source smc: what this frame's update counted
    uint32_t non_finite_pixels = 0;  // shown magenta in rgba8; a correct frame has none
    // --denoise: the firefly clamp's luminance moved (taken off outliers of the accumulated image,
    // spread over their neighbours: none is lost) over the luminance it was given.
    double firefly_moved_fraction = 0.0;
    FramePlan plan;  // every stage, kept or left out, with the reason (planner.hpp)
    // With RenderSettings::read_back_aovs, rows top to bottom: the G-buffer's linear base colour
    // and unit shading normal (3 floats per pixel; 0 where no surface was drawn), the distance
    // along the camera's forward axis (1 float; +infinity where no surface was drawn) and, when
    // the denoiser ran, its luminance variance of the demodulated indirect light (1 float); the
    // G-buffer's motion (3 floats: where the point was in the previous frame's pose less where
    // it is, world space; 0 where nothing moved or no surface was drawn).
    std::vector<float> albedo, normal, depth, indirect_variance, motion;
};

// How update_pose brought the BVH to the new pose.
enum class BvhUpdate {
    none,     // no vertex moved
    refit,    // the GPU tree's boxes refitted, its topology kept
    rebuild,  // a new GPU build (the first move, or the refitted tree's cost passed the limit)
};

// What Renderer::update_pose did.
struct PoseUpdate {
    bool geometry = false;  // vertices (and emissive triangles) uploaded, the BVH refitted or rebuilt
    bool lights = false;    // lights uploaded
    BvhUpdate bvh = BvhUpdate::none;
    // The BVH's SAH cost (bvh_sah_cost) over its cost right after it was last built: 1 after a
    // rebuild; a refit that moves triangles apart in the tree makes it grow.
    double bvh_cost_ratio = 1.0;
    double refit_cost_ratio = 0.0;  // with BvhUpdate::rebuild after a refit: the refitted tree's ratio
    double upload_ms = 0.0;         // vertices, emitters and lights to the GPU (host wall clock)
    double bvh_ms = 0.0;            // refit and/or build, the triangles' upload included (host wall clock)
    double bvh_gpu_ms = 0.0;        // the GPU's time of the last refit or build
    // Renderer::pose only: the vertices' pose (host wall clock: the host pose, or the nodes' pose,
    // the GPU pass and the posed vertices' readback), and whether the GPU posed them.
    double pose_ms = 0.0;
    bool posed_on_gpu = false;
    double pose_gpu_ms = 0.0;  // the GPU's time of the "pose vertices" pass
    std::string summary;       // one line; the next frame's plan carries it as a note
};

// Where Renderer::pose poses the moving vertices.
enum class PosePath {
    automatic,  // the GPU where it can (PosableScene::vertex_pose_refusal), kGpuPoseMinVertices move and
                // its buffers fit one binding (maxStorageBufferRange); else the host
    host,       // PosableScene::pose (the reference)
    gpu,        // PosableScene::pose_nodes and GpuPose; Error where the scene cannot be
};

// The moving vertices from which the automatic path poses on the GPU. Measured (tests/gltf/
// measure_gpu_pose, lavapipe on 2 shared cores): host 0.10 ms against GPU 0.14 ms at 996 vertices,
// 1.9 against 1.2 ms at 10^4, 41 against 17 ms at 10^5 (docs/gltf.md).
inline constexpr uint32_t kGpuPoseMinVertices = 2048;

// A refitted BVH is rebuilt when its SAH cost passes this multiple of its cost when built.
// Measured (tests/render/measure_pose, 131k triangles, lavapipe): tracing 262k closest-hit rays
// takes 81 ms through a fresh build, 213 ms through a refit at 1.68x the SAH cost, 1756 ms at
// 7.3x; a GPU rebuild costs 35-45 ms more than a refit, so a frame of that many rays gains from
// rebuilding once the ratio passes about 1.5.
inline constexpr double kBvhRebuildCostRatio = 1.5;

// The SAH cost of a BVH's nodes (traversal 1, triangle 1, relative to the root box's area): the
// expected node visits and triangle tests of a ray that meets the root box.
double bvh_sah_cost(std::span<const shaders::BvhNode> nodes);

class Renderer {
public:
    // `scene` must outlive the renderer (the VPL tracer reads its lights and materials).
    // Throws vplkit::Error when the scene has no light at all (no punctual light and no emissive
    // triangle), naming the scene: its image could only be black.
    Renderer(Context& context, const scene::Scene& scene);

    // Throws vplkit::Error for a zero size, a bad exposure, bad BRSM or sampling options, BRSM
    // asked of a scene without a punctual light, or a sampling dispatch the driver cut short.
    RenderedImage render(const scene::Camera& camera, const RenderSettings& settings);

    // After the scene given at construction was posed again (scene::PosableScene::pose returned
    // `change`): uploads the moved vertices, refits the BVH on the GPU (built there on the first
    // move; rebuilt when the refit's cost passes kBvhRebuildCostRatio) and uploads moved lights.
    // The next frames' plans make again what depended on what moved (VPLs and their trees, the
    // direct light tree, the denoiser's history after geometry moved) and reuse the rest.
    // Throws Error when the scene's vertex or triangle count changed (a renderer keeps its
    // triangles) or a moved vertex is not finite.
    PoseUpdate update_pose(const scene::PoseChange& change);
    // Poses `posable` (the scene this renderer was made with) at `time` and brings this renderer to
    // it (update_pose). On the GPU path, the moving vertices are posed by one "pose vertices" pass
    // from the frame's joint matrices and morph weights into this renderer's vertex buffer, and the
    // BVH is refitted from it in the same submission: posable.scene() keeps its vertices, except
    // where this renderer computes on the host from them (emissive triangles, directional lights'
    // bounds, forward light cuts once used: then they are read back into it; the summary says
    // which). A BVH build (the first move, a rebuild) reads the posed positions back for itself.
    // The host path is PosableScene::pose. Throws Error for another scene than this renderer's,
    // and what pose, pose_nodes and update_pose throw.
    PoseUpdate pose(scene::PosableScene& posable, double time, PosePath path = PosePath::automatic);
    // The vertices the last GPU pose left on the device read back into posable.scene() (the
    // renderer's own scene), for a reader outside this renderer (a second renderer's update_pose,
    // a reference). Nothing when the host scene already has them.
    void read_pose_back(scene::PosableScene& posable);
    // The pose this renderer's data is at (counts of update_pose's geometry and light moves).
    SceneVersion scene_version() const { return version_; }

    double bvh_build_ms() const { return bvh_build_ms_; }
    // The host's BVH of the scene as constructed (update_pose moves only the GPU's).
    const Bvh& bvh() const { return bvh_; }
    uint32_t light_count() const { return lights_.count; }
    uint32_t emitter_count() const { return emitters_.count; }
    // The direct light tree's lights (0 until a frame sampled direct light through it).
    uint32_t light_tree_count() const { return light_tree_ ? light_tree_->count() : 0; }

private:
    // A frame's VPLs. Their count stays on the GPU while the frame runs: the trees and samplers
    // read it from `count_buffer` (gpu_count()); `count` is read back after the frame.
    struct GeneratedVpls {
        Buffer vpls;  // Vpl[capacity]; the first `count` are the VPLs
        uint32_t capacity = 0;
        Buffer count_buffer;  // the count, at uint32 `count_word`
        uint32_t count_word = 0;
        uint32_t count = 0;  // after the frame that made them ran
        stages::ElementCount gpu_count() const {
            return stages::ElementCount::on_gpu(count_buffer, count_word, capacity);
        }
    };
    // The methods below record into `frame` (one command buffer per frame: frame_recording.hpp)
    // and leave their read-backs (counts, counters, notes) to run after it.

    // VPLs from `source` for the frame whose G-buffer is `gbuffer`; notes into `out`.
    GeneratedVpls generate_vpls(VplSource source, const stages::CameraView& view, GbufferImages& gbuffer,
                                const RenderSettings& settings, FrameRecording& frame, RenderedImage& out);
    // The frame's VPLs: the previous frame's when the plan reuses them, else new ones (kept for
    // the next frame).
    const GeneratedVpls& frame_vpls(const FramePlan& plan, const stages::CameraView& view, GbufferImages& gbuffer,
                                    const RenderSettings& settings, FrameRecording& frame, RenderedImage& out);
    // Indirect light from the cached VPLs by settings.method into `indirect` (full size), at full
    // or half resolution, with the trees the plan builds or reuses (renderer_gi.cpp). At half
    // resolution the light is demodulated before upsampling (texture stays sharp); returns true
    // when `indirect` is left as irradiance for the denoiser to remodulate.
    bool render_indirect(const FramePlan& plan, const stages::CameraView& view, GbufferImages& gbuffer,
                         const RenderSettings& settings, Image& indirect, FrameRecording& frame, RenderedImage& out);

    // --denoise: filters `indirect` in place (radiance, or irradiance when `demodulated`) with the
    // history of the previous frames, and keeps this frame as the next one's history.
    void denoise_indirect(const RenderSettings& settings, const stages::CameraView& view, GbufferImages& gbuffer,
                          Image& indirect, bool demodulated, FrameRecording& frame, RenderedImage& out);

    // Forward light cuts (the FLC paper): its own VPLs, splatted into `indirect` (renderer_flc.cpp).
    void render_flc(const stages::CameraView& view, GbufferImages& gbuffer, const RenderSettings& settings,
                    Image& indirect, FrameRecording& frame, RenderedImage& out);
    std::optional<Buffer> flc_vertex_random_;  // scene::Scene::vertex_random, uploaded on first use
    std::vector<double> flc_triangle_areas_;   // each triangle's area, for the subdivision (first use)
    // The triangles by centroid Morton code: the stratified decimation's order (first use).
    std::vector<uint32_t> flc_triangle_order_;

    // What a frame leaves for the next: its VPLs and the trees over them, while the plan's keys
    // (VPL settings, view for BRSM, tree settings) stay the same. The cache is kept only
    // at the pose it was made at (scene, update_pose).
    struct FrameCache {
        std::string vpl_key;  // empty: nothing cached
        SceneVersion scene;   // the pose they were made at
        GeneratedVpls vpls;
        std::vector<std::string> vpl_notes;
        std::string tree_key;
        std::optional<VplTrees> trees;
        bool light_tree = false;
        bool sst = false;
    };
    FrameCache cache_;
    // SMC: the persistent VPL set (while the SMC options stay the same) and the scene's emitters
    // and reflectances it reads, uploaded on first use.
    std::optional<SmcState> smc_;
    // --denoise: the filter's history, while the frame size stays the same.
    std::optional<Denoiser> denoiser_;
    FrameAccumulator accumulator_;  // RenderSettings::antialias: the mean of the frames on this camera
    std::string smc_key_;
    std::optional<VplSources> vpl_sources_;
    const VplSources& vpl_sources();

    Context& context_;
    GpuScene scene_;
    Bvh bvh_;
    GpuBvh gpu_bvh_;
    // Once geometry moved (update_pose): the BVH built and refitted on the GPU, and its SAH cost
    // when built. Until then the host's build above.
    std::optional<GpuBvhBuild> moving_bvh_;
    double moving_bvh_built_cost_ = 0.0;
    const GpuBvh& gpu_bvh() const { return moving_bvh_ ? moving_bvh_->bvh() : gpu_bvh_; }
    // Builds moving_bvh_ over the scene's current positions (its alpha records from bvh_).
    void build_moving_bvh(std::span<const glm::vec3> positions);
    SceneVersion version_;                           // update_pose's moves
    SceneVersion denoise_scene_;                     // the pose of the denoiser's history
    std::optional<SceneVersion> direct_tree_scene_;  // the pose the direct light tree was built at
    std::string pose_note_;                          // the last update_pose's summary, for the next plan
    // Renderer::pose's GPU path: the rest pose uploaded on first use; whether the host scene lacks
    // the pose it wrote into scene_'s vertex buffer.
    std::optional<GpuPose> gpu_pose_;
    bool host_pose_stale_ = false;
    GpuLights lights_;
    GpuEmitters emitters_;
    GpuLights directional_lights_;            // the direct-light pass's lights when the tree samples the rest
    std::optional<GpuLightTree> light_tree_;  // over emitters, point and spot lights; built on first use
    std::optional<GpuTwoLevelLightTree> two_level_light_tree_;  // the same lights in two levels (--direct tree2)
    const scene::Scene& scene_source_;                          // for the VPL sources, uploaded on first use
    double bvh_build_ms_ = 0.0;
};

}  // namespace vplkit
