// Renderer::render_indirect: from the frame's VPLs to its indirect light by the chosen method,
// at full resolution or on a half-resolution G-buffer with joint bilateral upsampling.

#include "vplkit/renderer.hpp"

#include "frame_recording.hpp"

#include "gi_stage_options.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/exact_gi_render.hpp"
#include "vplkit/gi_counters_buffer.hpp"
#include "vplkit/hybrid_cuts.hpp"
#include "vplkit/image.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/rtslc_scratch.hpp"
#include "vplkit/stages/denoise.hpp"
#include "vplkit/upsample_counters.hpp"
#include "vplkit/stages/exact_gi.hpp"
#include "vplkit/stages/gbuffer.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/stages/hybrid_gi.hpp"
#include "vplkit/stages/rtslc.hpp"
#include "vplkit/stages/sst_gi.hpp"
#include "vplkit/vpl_trees.hpp"

#include <cmath>
#include <optional>
#include <string>

namespace vplkit {

const char* denoise_mode_name(DenoiseMode mode) {
    switch (mode) {
        case DenoiseMode::off:
            return "off";
        case DenoiseMode::temporal:
            return "temporal";
        case DenoiseMode::svgf:
            return "svgf";
    }
    return "?";
}

void validate_gi_settings(const RenderSettings& settings) {
    if (const auto check = gi_method(settings.method).validate) check(settings);
    if (settings.vpl_source == VplSource::smc) stages::validate(settings.smc);
    if (!std::isfinite(settings.sst.nu_min) || !std::isfinite(settings.sst.sigma_max) ||
        settings.sst.sigma_max < 0.0f) {
        throw Error("render: `sst.nu_min` must be finite and `sst.sigma_max` finite and >= 0");
    }
    if (settings.sigma_max_scene_fraction &&
        !(std::isfinite(*settings.sigma_max_scene_fraction) && *settings.sigma_max_scene_fraction >= 0.0f)) {
        throw Error("render: `sigma_max_scene_fraction` must be finite and >= 0");
    }
}

RenderSettings with_scene_relative_thresholds(RenderSettings settings, float scene_scale) {
    if (settings.sigma_max_scene_fraction) settings.sst.sigma_max = *settings.sigma_max_scene_fraction * scene_scale;
    return settings;
}

bool Renderer::render_indirect(const FramePlan& plan, const stages::CameraView& view, GbufferImages& gbuffer,
                               const RenderSettings& settings, Image& indirect, FrameRecording& frame,
                               RenderedImage& out) {
    const GeneratedVpls& vpls = cache_.vpls;
    const bool half = settings.half_resolution_gi;
    const uint32_t w = half ? stages::half_resolution(gbuffer.width()) : gbuffer.width();
    const uint32_t h = half ? stages::half_resolution(gbuffer.height()) : gbuffer.height();
    out.gi_width = w;
    out.gi_height = h;
    // The samplers read the count the GPU wrote: with none, the trees are all padding and the
    // light is black; the host learns of it after the frame.
    frame.after_run([this, &out] {
        if (cache_.vpls.count == 0) {
            out.notes.push_back("no VPLs were placed (no light reaches a reflecting surface): no indirect light");
        }
    });
    GiStageOptions options = gi_stage_options(settings, stages::kGiSimilarityDistanceFraction * gpu_bvh().scene_scale);
    options.sst.glossy.enabled = options.rtslc.glossy.enabled = options.hybrid.glossy.enabled = plan.glossy_branch;
    const stages::SstGiOptions& sst_options = options.sst;
    const stages::RtslcOptions& rtslc_options = options.rtslc;
    const stages::HybridOptions& hybrid_options = options.hybrid;
    PassList& passes = frame.passes();

    // The G-buffer and target the method works on (the plan's downsample and upsample stages).
    GbufferImages* half_gbuffer = nullptr;
    Image* half_indirect = nullptr;
    if (half) {
        half_gbuffer = &frame.hold(GbufferImages::create(context_, w, h));
        half_indirect = &frame.hold(Image::create(context_, w, h, VK_FORMAT_R32G32B32A32_SFLOAT,
                                                  VK_IMAGE_USAGE_STORAGE_BIT, "half indirect radiance"));
        passes.set_tag(stage_tag(FrameStage::gi_downsample));
        stages::add_gbuffer_downsample_pass(context_, passes, gbuffer, *half_gbuffer);
    }
    GbufferImages& gi_gbuffer = half ? *half_gbuffer : gbuffer;
    Image& gi_target = half ? *half_indirect : indirect;

    if (settings.method == GiMethod::exact) {
        // The reference gathers on the host's count, in chunks the host sizes (lavapipe's loop
        // limit): the frame so far runs first.
        frame.submit(context_, out.timings);
        stages::ExactGiOptions options;
        options.progress = settings.progress;
        options.min_distance_fraction = settings.exact_min_distance_fraction;
        const auto result =
            render_exact_gi(context_, gi_gbuffer, gpu_bvh(), vpls.vpls, vpls.count, view.position, gi_target, options);
        out.timings.push_back({"exact gi (" + std::to_string(result.dispatches) + " dispatches)", result.gpu_ms,
                               stage_tag(FrameStage::gi_exact)});
        out.exact_gi_wall_ms = result.wall_ms;
        out.dropped_pixels = result.counts.dropped_pixels;
    } else {
        if (plan.reuse_trees) {
            out.reused_trees = true;
        } else {
            // Only the trees the method reads (the plan's light tree and SST stages), over the
            // VPLs' capacity: the padding past the GPU's count sorts last and weighs nothing.
            VplTreeOptions tree_options;
            tree_options.sst = settings.sst;
            cache_.trees = VplTrees::create(context_, vpls.capacity, tree_options);
            cache_.tree_key = plan.tree_key;
            cache_.light_tree = plan.runs(FrameStage::light_tree);
            cache_.sst = plan.runs(FrameStage::sst);
            cache_.trees->add_build_passes(
                passes, vpls.vpls, vpls.gpu_count(), cache_.light_tree, cache_.sst,
                {stage_tag(FrameStage::vpl_sort), stage_tag(FrameStage::light_tree), stage_tag(FrameStage::sst)});
        }
        const VplTrees& trees = *cache_.trees;
        Buffer& counters = frame.hold(create_gi_counters(context_));
        if (const std::optional<FrameStage> stage = gi_method(settings.method).stage) {
            passes.set_tag(stage_tag(*stage));
        }
        switch (settings.method) {
            case GiMethod::sst:
                stages::add_sst_gi_pass(context_, passes, gi_gbuffer, gpu_bvh(), trees, view.position, gi_target,
                                        counters, sst_options);
                break;
            case GiMethod::rtslc: {
                auto& scratch = frame.hold(RtslcScratch::create(context_, w, h, rtslc_options));
                stages::add_rtslc_passes(context_, passes, gi_gbuffer, gpu_bvh(), trees, view.position, gi_target,
                                         counters, rtslc_options, scratch);
                break;
            }
            case GiMethod::hybrid: {
                auto& cuts = frame.hold(HybridCuts::create(context_, w, h, hybrid_options));
                stages::add_hybrid_gi_passes(context_, passes, gi_gbuffer, gpu_bvh(), trees, view.position, gi_target,
                                             counters, cuts, hybrid_options);
                break;
            }
            default:
                throw Error("render: no indirect-light method to run");
        }
        frame.after_run([&out, &counters, method = settings.method] {
            out.gi_counts = read_gi_counters(counters);
            out.dropped_pixels = out.gi_counts.dropped_pixels;
            if (out.gi_counts.cut_short > 0) {
                throw Error(std::string(gi_method_name(method)) + ": the driver ended " +
                            std::to_string(out.gi_counts.cut_short) +
                            " invocations early (a loop iteration limit): the image would be wrong; use fewer "
                            "samples per pixel");
            }
            if (out.gi_counts.dropped_samples > 0) {
                out.notes.push_back(std::to_string(out.gi_counts.dropped_samples) + " samples in " +
                                    std::to_string(out.gi_counts.dropped_pixels) +
                                    " pixels were not finite and were left out of the indirect light");
            }
        });
    }

    if (!half) return false;
    // Upsampling blurs what it is given: give it irradiance (radiance / albedo at the half
    // G-buffer), and multiply the full-resolution albedo back after it (or after the denoiser).
    const bool denoised = plan.runs(FrameStage::denoise);
    stages::DenoiseOptions modulation = settings.denoise_options;
    modulation.scene_scale = gpu_bvh().scene_scale;
    Image& half_irradiance = frame.hold(Image::create(context_, w, h, VK_FORMAT_R32G32B32A32_SFLOAT,
                                                      VK_IMAGE_USAGE_STORAGE_BIT, "half indirect irradiance"));
    Image* full_irradiance = nullptr;
    if (!denoised) {
        full_irradiance =
            &frame.hold(Image::create(context_, gbuffer.width(), gbuffer.height(), VK_FORMAT_R32G32B32A32_SFLOAT,
                                      VK_IMAGE_USAGE_STORAGE_BIT, "indirect irradiance"));
    }
    Buffer& counters = frame.hold(create_upsample_counters(context_));
    passes.set_tag(stage_tag(FrameStage::gi_upsample));
    stages::add_demodulate_pass(context_, passes, *half_indirect, half_gbuffer->albedo, half_gbuffer->position,
                                half_irradiance, modulation);
    Image& upsampled = denoised ? indirect : *full_irradiance;
    stages::add_upsample_passes(context_, passes, gbuffer, *half_gbuffer, half_irradiance, upsampled, counters,
                                stages::upsample_options_for_scene(gpu_bvh().scene_scale));
    if (!denoised) stages::add_remodulate_pass(context_, passes, upsampled, gbuffer.albedo, indirect, modulation);
    frame.after_run([&out, &counters] { out.upsample_counts = read_upsample_counters(counters); });
    return denoised;
}

}  // namespace vplkit
