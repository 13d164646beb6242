#include "vplkit/renderer.hpp"

#include "vplkit/bvh_alpha.hpp"

#include "frame_recording.hpp"

#include "vplkit/auto_exposure.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/stages/compose.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/gi_counters_buffer.hpp"
#include "vplkit/rtslc_scratch.hpp"
#include "vplkit/stages/direct_light_tree.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/brsm_buffers.hpp"
#include "vplkit/shadow_map.hpp"
#include "vplkit/stages/tonemap.hpp"
#include "vplkit/vpl_tracing_buffers.hpp"

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <chrono>
#include <cstddef>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

namespace vplkit {

Renderer::Renderer(Context& context, const scene::Scene& scene) : context_(context), scene_source_(scene) {
    if (scene.lights.empty() && scene.emissive_triangles.empty()) {
        throw Error(scene.source.string() +
                    ": the scene has no light (no punctual light, no emissive triangle): its image would be black; "
                    "add a light (`scene.lights`)");
    }
    scene_ = GpuScene::create(context, scene);
    const auto start = std::chrono::steady_clock::now();
    // MASK and BLEND cut-outs let rays through, as the G-buffer shows them; their triangles in a
    // subtree of their own, so only rays that enter it pay for the alpha test (vplkit/bvh.hpp).
    bvh_ = build_scene_bvh(scene);
    bvh_build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    gpu_bvh_ = upload_bvh(context, bvh_);
    lights_ = upload_lights(context, scene.lights);
    directional_lights_ = upload_lights(context, directional_lights(scene));
    emitters_ = upload_emitters(context, scene);
}

namespace {

std::vector<float> rgb_of(Image& image) {
    const auto texels = image.download<std::array<float, 4>>();
    std::vector<float> rgb;
    rgb.reserve(texels.size() * 3);
    for (const auto& t : texels) rgb.insert(rgb.end(), {t[0], t[1], t[2]});
    return rgb;
}

void append(std::vector<PassTiming>& all, const std::vector<PassTiming>& more) {
    all.insert(all.end(), more.begin(), more.end());
}

// The most a frame keeps of BRSM's per-light shadow maps and buffers before it runs what it has
// recorded (and frees them): many lights' maps would otherwise all live at once.
constexpr uint64_t kBrsmFrameBytes = uint64_t(256) << 20;

// A light's BRSM memory: its map's images (position, normal and flux RGBA32F, depth 32-bit) and
// its working buffers.
uint64_t brsm_light_bytes(const ShadowMap& map, const BrsmLightBuffers& light) {
    const uint64_t texels = uint64_t(map.width()) * map.height();
    return texels * (3 * 16 + 4) + light.contribution.size() + light.contribution_mips.size() + light.flux_mips.size() +
           light.importance_mips.size() + light.samples.size() + light.warp_count.size();
}

// RenderedImage's albedo, normal and depth from the frame's G-buffer (renderer.hpp).
void read_back_aovs(GbufferImages& gbuffer, const scene::Camera& camera, RenderedImage& out) {
    const auto position = gbuffer.position.download<std::array<float, 4>>();
    const auto normal = gbuffer.normal.download<std::array<float, 4>>();
    const auto albedo = gbuffer.albedo.download<std::array<uint16_t, 4>>();  // RGBA16F
    const auto motion = gbuffer.motion.download<std::array<float, 4>>();
    const glm::vec3 forward = glm::normalize(camera.forward);
    for (size_t i = 0; i < position.size(); ++i) {
        const bool covered = position[i][3] > 0.5f;
        const glm::vec3 p{position[i][0], position[i][1], position[i][2]};
        out.depth.push_back(covered ? glm::dot(p - camera.position, forward) : INFINITY);
        for (int c = 0; c < 3; ++c) {
            out.normal.push_back(covered ? normal[i][c] : 0.0f);
            out.albedo.push_back(covered ? glm::unpackHalf1x16(albedo[i][c]) : 0.0f);
            out.motion.push_back(covered ? motion[i][c] : 0.0f);
        }
    }
}

}  // namespace

Renderer::GeneratedVpls Renderer::generate_vpls(VplSource source, const stages::CameraView& view,
                                                GbufferImages& gbuffer, const RenderSettings& settings,
                                                FrameRecording& frame, RenderedImage& out) {
    PassList& passes = frame.passes();
    GeneratedVpls generated;
    if (source == VplSource::smc) {
        // The persistent set: one update per frame (and the warm-up before the first).
        stages::SmcOptions options = settings.smc;
        options.seed = settings.seed;
        const std::string key = vpl_set_key(settings, VplSource::smc, "");
        if (!smc_ || smc_key_ != key) {
            smc_ = SmcState::create(context_, options);
            smc_key_ = key;
        }
        const stages::SmcScene smc_scene{gpu_bvh(), vpl_sources()};
        const uint32_t updates = smc_->empty() ? settings.smc_warmup + 1 : 1;
        if (updates > 1) {
            // The warm-up (a new set's first frame only) reads this frame's G-buffer and reports
            // progress: the frame so far runs first, then each warm-up update on its own.
            frame.submit(context_, out.timings);
            for (uint32_t u = 0; u + 1 < updates; ++u) {
                PassList warm_up("smc warm-up");
                warm_up.set_tag(stage_tag(FrameStage::smc_vpls));
                smc_->add_update(context_, warm_up, gbuffer, view, smc_scene);
                warm_up.run(context_);
                append(out.timings, warm_up.timings());
                if (settings.smc_warmup_progress) settings.smc_warmup_progress(u + 1, updates);
            }
        }
        passes.set_tag(stage_tag(FrameStage::smc_vpls));
        smc_->add_update(context_, passes, gbuffer, view, smc_scene);
        // The frame's copy of the set and of its count: the next update changes both.
        const Buffer& from = smc_->vpls();
        generated.capacity = uint32_t(from.size() / sizeof(shaders::Vpl));
        generated.vpls = Buffer::create(context_, from.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::device,
                                        "smc frame vpls");
        generated.count_buffer = Buffer::create(context_, sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                MemoryUse::device, "smc frame vpl count");
        const BufferView vpls_from = from, vpls_to = generated.vpls;
        const BufferView count_from = smc_->counters(), count_to = generated.count_buffer;
        passes.add("smc vpl copy",
                   {Use::transfer_src(vpls_from), Use::transfer_src(count_from), Use::transfer_dst(vpls_to),
                    Use::transfer_dst(count_to)},
                   [vpls_from, vpls_to, count_from, count_to](VkCommandBuffer cmd) {
                       const VkBufferCopy vpls{0, 0, vpls_from.size};
                       vkCmdCopyBuffer(cmd, vpls_from.buffer, vpls_to.buffer, 1, &vpls);
                       const VkBufferCopy count{offsetof(shaders::SmcCounters, vpl_count), 0, sizeof(uint32_t)};
                       vkCmdCopyBuffer(cmd, count_from.buffer, count_to.buffer, 1, &count);
                   });
        if (updates > 1 && settings.smc_warmup_progress) settings.smc_warmup_progress(updates, updates);
        frame.after_run([this, &out] {
            out.smc = smc_->read_counts();
            if (out.smc->vpls == 0) {
                out.notes.push_back("SMC found no reflecting surface the camera sees indirectly: no VPLs");
            }
        });
        return generated;
    }
    if (source == VplSource::ir) {
        // Light paths from every emitter through the BVH.
        const VplSources& sources = vpl_sources();
        const stages::VplTracingOptions tracing{settings.vpl_paths, settings.vpl_bounces, settings.seed};
        auto& output = frame.hold(VplTracingOutput::create(context_, tracing));
        passes.set_tag(stage_tag(FrameStage::vpl_paths));
        stages::add_trace_vpls_passes(context_, passes, gpu_bvh(), sources, tracing, output);
        generated.capacity = output.capacity;
        generated.count_word = offsetof(shaders::VplCountBuffer, count) / sizeof(uint32_t);
        generated.vpls = std::move(output.vpls);  // the frame's scratch stays held until it ran
        generated.count_buffer = std::move(output.count);
        // After the frame (the VPLs are the cache's by then, frame_vpls): paths cut short are an error.
        frame.after_run([this] { checked_vpl_count(cache_.vpls.count_buffer, cache_.vpls.capacity); });
        return generated;
    }

    // BRSM: a reflective shadow map per punctual light, then the VPLs where the camera sees their light.
    if (scene_source_.lights.empty()) {
        throw Error(scene_source_.source.string() +
                    ": BRSM places VPLs from punctual lights' shadow maps, and the scene has none (its light "
                    "is emissive triangles): use `vpl_source` ir");
    }
    if (!scene_source_.emissive_triangles.empty()) {
        frame.after_run([&out] {
            out.notes.push_back("BRSM VPLs come from punctual lights only: the emissive triangles' light has no VPLs");
        });
    }
    stages::BrsmOptions options = settings.brsm;
    options.seed = settings.seed;
    // Shared with the after-run reads below: each light's buffers are read and freed after the
    // submission that placed its VPLs.
    auto output = std::make_shared<BrsmOutput>(
        BrsmOutput::create_for_lights(context_, scene_source_.lights, scene_.bounds(), options));
    passes.set_tag(stage_tag(FrameStage::brsm_vpls));
    stages::add_brsm_count_clear_pass(passes, *output);
    // Every light's shadow map and working buffers live until the frame has run, so that the frame
    // is one command buffer; a scene with many lights runs the frame so far whenever they would
    // pass kBrsmFrameBytes, which frees them (the thesis ch. 6, "Multiple Lights", places one light
    // at a time to need the memory of one).
    uint64_t held_bytes = 0;
    for (size_t i = 0; i < scene_source_.lights.size(); ++i) {
        const scene::Light& light = scene_source_.lights[i];
        if (output->lights[i].vpl_share == 0) continue;  // no power
        auto map = ShadowMap::create(context_, light, scene_.bounds(), settings.rsm_resolution);
        allocate_brsm_light_buffers(context_, map, output->lights[i]);
        const uint64_t bytes = brsm_light_bytes(map, output->lights[i]);
        if (held_bytes > 0 && held_bytes + bytes > kBrsmFrameBytes) {
            frame.submit(context_, out.timings);
            held_bytes = 0;
        }
        held_bytes += bytes;
        ShadowMap& held_map = frame.hold_until_submit(std::move(map));
        passes.set_tag(stage_tag(FrameStage::brsm_vpls));
        stages::add_shadow_map_pass(context_, passes, scene_, held_map, uint32_t(i));
        stages::add_brsm_light_passes(context_, passes, gbuffer, view, held_map, i, gpu_bvh().scene_scale, options,
                                      *output);
        frame.after_run([output, i, &out, name = light.name] {
            if (download_brsm_light_vpl_count(*output, i) == 0) {
                out.notes.push_back("light " + std::to_string(i) + (name.empty() ? "" : " '" + name + "'") +
                                    ": its shadow map holds no surface that reflects light, so it has no VPLs");
            }
            output->lights[i] = BrsmLightBuffers{0, output->lights[i].vpl_share};  // frees them
        });
    }
    generated.capacity = output->capacity;
    generated.vpls = std::move(output->vpls);
    generated.count_buffer = std::move(output->count);
    generated.count_word = offsetof(shaders::VplCountBuffer, count) / sizeof(uint32_t);
    return generated;
}

const VplSources& Renderer::vpl_sources() {
    if (!vpl_sources_) vpl_sources_ = upload_vpl_sources(context_, scene_source_);
    return *vpl_sources_;
}

const Renderer::GeneratedVpls& Renderer::frame_vpls(const FramePlan& plan, const stages::CameraView& view,
                                                    GbufferImages& gbuffer, const RenderSettings& settings,
                                                    FrameRecording& frame, RenderedImage& out) {
    if (plan.reuse_vpls) {
        out.notes.insert(out.notes.end(), cache_.vpl_notes.begin(), cache_.vpl_notes.end());
        out.reused_vpls = true;
        out.vpl_count = cache_.vpls.count;
        return cache_.vpls;
    }
    // The notes of making the VPLs, kept for the frames that reuse them: they are written after
    // the frame runs, between these two marks.
    auto first_note = std::make_shared<size_t>(0);
    frame.after_run([&out, first_note] { *first_note = out.notes.size(); });
    GeneratedVpls generated = generate_vpls(plan.vpl_source, view, gbuffer, settings, frame, out);
    cache_ = FrameCache{};
    cache_.vpl_key = plan.vpl_key;
    cache_.scene = version_;
    cache_.vpls = std::move(generated);
    frame.after_run([this, &out, first_note] {
        GeneratedVpls& vpls = cache_.vpls;
        const auto words = vpls.count_buffer.download<uint32_t>(vpls.count_word + 1);
        vpls.count = std::min(words[vpls.count_word], vpls.capacity);  // sources count attempts past their room
        out.vpl_count = vpls.count;
        cache_.vpl_notes.assign(out.notes.begin() + std::ptrdiff_t(*first_note), out.notes.end());
    });
    return cache_.vpls;
}

namespace {

// The camera and size a frame is seen with, exactly (BRSM VPLs depend on them).
std::string view_key_of(const stages::CameraView& view, uint32_t w, uint32_t h) {
    std::ostringstream key;
    key.precision(9);
    key << w << 'x' << h;
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) key << ' ' << view.view_projection[c][r];
    }
    key << " eye " << view.position.x << ' ' << view.position.y << ' ' << view.position.z;
    return key.str();
}

}  // namespace

void Renderer::denoise_indirect(const RenderSettings& settings, const stages::CameraView& view, GbufferImages& gbuffer,
                                Image& indirect, bool demodulated, FrameRecording& frame, RenderedImage& out) {
    if (!denoiser_ || denoiser_->width() != gbuffer.width() || denoiser_->height() != gbuffer.height()) {
        denoiser_ = Denoiser::create(context_, gbuffer.width(), gbuffer.height());
    }
    if (settings.frame == 0) denoiser_->reset();
    stages::DenoiseOptions options = settings.denoise_options;
    options.scene_scale = gpu_bvh().scene_scale;
    PassList& passes = frame.passes();
    passes.set_tag(stage_tag(FrameStage::denoise));
    stages::GbufferViews views = gbuffer;
    if (settings.denoise_motion != DenoiseMotion::follow) views.motion = {};  // the camera alone
    denoiser_->add_passes(context_, passes, settings.denoise, views, indirect, options, demodulated);
    denoiser_->end_frame(view.view_projection);  // the next frame's history: only bookkeeping on the host
    frame.after_run([this, &out, aovs = settings.read_back_aovs] {
        out.firefly_moved_fraction = denoiser_->firefly_moved_fraction();
        if (aovs) out.indirect_variance = denoiser_->variance();
    });
}

RenderedImage Renderer::render(const scene::Camera& camera, const RenderSettings& requested) {
    validate_gi_settings(requested);
    const RenderSettings settings = with_scene_relative_thresholds(requested, gpu_bvh().scene_scale);
    constexpr VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT;
    const uint32_t w = settings.width, h = settings.height;
    auto gbuffer = GbufferImages::create(context_, w, h);
    auto direct = Image::create(context_, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "direct radiance");
    // Also a colour attachment: flc splats into it with additive blending.
    auto indirect = Image::create(context_, w, h, VK_FORMAT_R32G32B32A32_SFLOAT,
                                  storage | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "indirect radiance");
    auto composed = Image::create(context_, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "radiance");
    auto display = Image::create(context_, w, h, VK_FORMAT_R8G8B8A8_UNORM, storage, "display");
    auto stats = Buffer::create(context_, stages::kTonemapStatsBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                MemoryUse::device, "tonemap stats");
    const stages::CameraView view = camera_view(camera, w, h);
    RenderedImage out;
    out.width = w;
    out.height = h;
    out.sst_sigma_max = settings.sst.sigma_max;
    // The plan decides every stage below; the passes recorded are exactly the stages it runs.
    // Frame 0 starts a new sequence: the denoiser's history is dropped.
    const bool denoise_history = settings.frame > 0 && denoiser_ && denoiser_->width() == w &&
                                 denoiser_->height() == h && denoiser_->has_history();
    FramePlan plan = plan_frame(scene_source_, settings, view_key_of(view, w, h),
                                {cache_.vpl_key, cache_.light_tree, cache_.sst, cache_.tree_key, denoise_history,
                                 cache_.scene, denoise_scene_, direct_tree_scene_},
                                version_);
    if (!pose_note_.empty()) plan.notes.push_back(std::exchange(pose_note_, {}));  // what update_pose did
    if (plan.drop_denoise_history) denoiser_->reset();
    if (plan.runs(FrameStage::denoise)) denoise_scene_ = version_;
    out.plan_summary = plan.summary();
    out.plan = plan;
    out.vpl_source = plan.vpl_source;
    for (const PlannedStage& s : plan.stages) {
        if (s.runs) out.stages_run.push_back(stage_name(s.stage));
    }

    // Direct light through the tree: rtslc's cut options, the block size the RTSLC paper sec. 4 uses.
    const bool tree_direct = plan.runs(FrameStage::direct_tree);
    stages::RtslcOptions tree_options;
    tree_options.samples_per_pixel = settings.direct_samples;
    tree_options.frame = settings.frame;
    tree_options.seed = settings.seed;
    tree_options.interleave = settings.direct_interleave;
    // Without interleaving the cut's slots are shared out by bound (rtslc_cut.comp's kShareOutSlots)
    // at one representative pixel per block: 4 x 4 blocks, not the RTSLC paper's 8 x 8, since on irregular
    // mesh lights 8 x 8 blocks spanning the ceiling and the wall gave the slots to the wrong lamps
    // (docs/measurements.md, *Many lights*). Interleaved sampling keeps 8 x 8 (its M divides 8).
    if (settings.direct_interleave <= 1) tree_options.block_size = 4;
    if (tree_direct) stages::validate_direct_light_tree(tree_options);  // before any work

    // The frame, G-buffer to compose, is one command buffer (frame_recording.hpp): no count or
    // counter is read back before it has run.
    FrameRecording frame("frame");
    PassList& direct_passes = frame.passes();
    direct_passes.set_tag(stage_tag(FrameStage::gbuffer));
    // Anti-aliasing: only the raster sees the sub-pixel offset (antialias.hpp).
    const stages::CameraView raster_view =
        settings.antialias ? jittered_view(view, subpixel_jitter(settings.frame), w, h) : view;
    stages::add_gbuffer_pass(context_, direct_passes, scene_, raster_view, gbuffer);
    direct_passes.set_tag(stage_tag(FrameStage::direct_light));
    // With the tree, the direct-light pass adds only the directional lights (they have no position).
    stages::add_direct_light_pass(context_, direct_passes, gbuffer, gpu_bvh(),
                                  tree_direct ? directional_lights_ : lights_, {view.position, settings.background},
                                  direct);
    if (plan.runs(FrameStage::direct_emissive)) {
        direct_passes.set_tag(stage_tag(FrameStage::direct_emissive));
        stages::add_direct_emissive_pass(context_, direct_passes, gbuffer, gpu_bvh(), emitters_,
                                         {view.position, settings.direct_samples, settings.seed}, direct);
    }
    std::optional<RtslcScratch> tree_scratch;
    std::optional<Buffer> tree_counters;
    std::optional<Image> tree_light, direct_total;
    if (tree_direct) {
        direct_passes.set_tag(stage_tag(FrameStage::direct_tree));
        const bool two_level = plan.direct_sampler == DirectSampler::tree2;
        if (plan.build_direct_tree) {
            // First use, or the lights or emitters moved (update_pose): both trees made anew.
            light_tree_.reset();
            two_level_light_tree_.reset();
            direct_tree_scene_ = version_;
        }
        if (two_level && !two_level_light_tree_) {
            // Built on the host and uploaded once, both levels (gpu_two_level_light_tree.hpp).
            two_level_light_tree_ = GpuTwoLevelLightTree::create(context_, scene_source_, emitters_);
        }
        if (!two_level && !light_tree_) {
            // Built in the first frame that samples through it, and again after lights moved.
            light_tree_ = GpuLightTree::create(context_, scene_source_, emitters_);
            light_tree_->add_build_passes(context_, direct_passes);
        }
        const stages::DirectLightTree tree = two_level ? stages::DirectLightTree(two_level_light_tree_->buffers())
                                                       : stages::DirectLightTree(light_tree_->buffers());
        tree_scratch = RtslcScratch::create(context_, w, h, tree_options);
        tree_counters = create_gi_counters(context_, "direct tree counters");
        if (tree_options.interleave > 1) {
            // Interleaved, the tree's light is reconstructed into an image of its own, then added.
            tree_light.emplace(Image::create(context_, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "tree light"));
            direct_total.emplace(
                Image::create(context_, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "direct radiance total"));
            stages::add_direct_light_tree_interleaved_passes(context_, direct_passes, gbuffer, gpu_bvh(), tree,
                                                             view.position, *tree_light, *tree_counters, tree_options,
                                                             *tree_scratch);
            stages::add_compose_pass(context_, direct_passes, direct, *tree_light, *direct_total);
        } else {
            stages::add_direct_light_tree_passes(context_, direct_passes, gbuffer, gpu_bvh(), tree, view.position,
                                                 direct, *tree_counters, tree_options, *tree_scratch);
        }
    }
    Image& direct_out = direct_total ? *direct_total : direct;
    direct_passes.set_tag(stage_tag(FrameStage::direct_light));  // the indirect image is cleared with it
    direct_passes.add("indirect clear", {Use::transfer_dst(indirect)}, [&indirect](VkCommandBuffer cmd) {
        const VkClearColorValue zero{};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, indirect.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &all);
    });
    out.direct_sampler = plan.direct_sampler;
    if (tree_direct) {
        frame.after_run([&out, &tree_counters] {
            out.direct_counts = read_gi_counters(*tree_counters);
            if (out.direct_counts.cut_short > 0) {
                throw Error("direct light tree: the driver ended " + std::to_string(out.direct_counts.cut_short) +
                            " invocations early (a loop iteration limit): the image would be wrong");
            }
            if (out.direct_counts.dropped_samples > 0) {
                out.notes.push_back(std::to_string(out.direct_counts.dropped_samples) + " direct-light samples in " +
                                    std::to_string(out.direct_counts.dropped_pixels) +
                                    " pixels were not finite and were left out");
            }
        });
    }

    if (settings.vpls_only) {
        const GeneratedVpls& generated = frame_vpls(plan, view, gbuffer, settings, frame, out);
        frame.submit(context_, out.timings);  // the VPLs themselves are this mode's output
        if (generated.count > 0) {
            for (const auto& v : generated.vpls.download<shaders::Vpl>(generated.count)) {
                out.vpls.push_back({{v.position.x, v.position.y, v.position.z},
                                    {v.normal.x, v.normal.y, v.normal.z},
                                    {v.flux.x, v.flux.y, v.flux.z}});
            }
        }
        out.gbuffer_position = gbuffer.position.download<float>();
    } else if (settings.method == GiMethod::flc) {
        render_flc(view, gbuffer, settings, indirect, frame, out);
    } else if (settings.method != GiMethod::none) {
        frame_vpls(plan, view, gbuffer, settings, frame, out);
        const bool demodulated = render_indirect(plan, view, gbuffer, settings, indirect, frame, out);
        if (plan.runs(FrameStage::denoise)) {
            denoise_indirect(settings, view, gbuffer, indirect, demodulated, frame, out);
        }
    }

    // Composed and read back first: the mean over jittered frames and the automatic exposure
    // are taken on the host, before the tone curve.
    frame.passes().set_tag(stage_tag(FrameStage::compose));
    stages::add_compose_pass(context_, frame.passes(), direct_out, indirect, composed);
    frame.submit(context_, out.timings);
    scene_.settle_motion();  // this pose is the next frame's previous one
    out.radiance = rgb_of(composed);
    out.direct = rgb_of(direct_out);
    out.indirect = rgb_of(indirect);
    if (settings.antialias) {
        const bool average_indirect = !plan.runs(FrameStage::denoise);  // the filter keeps its own mean
        composed.upload(accumulator_.add(settings.frame, view.view_projection, average_indirect, out.direct,
                                         out.indirect, out.radiance));
    }
    out.exposure = settings.auto_exposure ? auto_exposure(out.radiance).exposure : settings.exposure;
    PassList output_passes("output");
    output_passes.set_tag(stage_tag(FrameStage::tonemap));
    stages::add_tonemap_passes(context_, output_passes, composed, display, stats, out.exposure);
    output_passes.run(context_);
    append(out.timings, output_passes.timings());
    out.rgba8 = display.download<uint8_t>();
    out.non_finite_pixels = stats.download<uint32_t>(1)[0];
    if (settings.read_back_aovs) read_back_aovs(gbuffer, camera, out);
    return out;
}

}  // namespace vplkit
