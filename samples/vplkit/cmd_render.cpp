// `vplkit render`: one frame of a scene (a standard set-up's name or a glTF file) with direct
// light, written as PNG (and linear PFM on request), with the device and per-stage GPU times.

#include "budget_option.hpp"
#include "cli.hpp"
#include "cli_checks.hpp"
#include "commands.hpp"
#include "frame_exr.hpp"
#include "render_report.hpp"
#include "render_request.hpp"
#include "render_stats.hpp"
#include "scene_warnings.hpp"
#include "setting_flags.hpp"
#include "stats_json.hpp"
#include "vpl_view.hpp"

#include "vplkit/auto_exposure.hpp"
#include "vplkit/budget.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/image_io.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_setups.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/stages/flc.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

namespace vplkit::cli {

namespace {

// Fails before any rendering when a file could not be written there.
void check_output(const std::string& option, const std::filesystem::path& path,
                  std::initializer_list<std::string> extensions) {
    if (std::find(extensions.begin(), extensions.end(), path.extension().string()) == extensions.end()) {
        std::string names;
        for (const std::string& e : extensions) names += (names.empty() ? "" : " or ") + e;
        throw UsageError(option + " expects a " + names + " file name, got '" + path.string() + "'");
    }
    const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
    if (!std::filesystem::is_directory(folder)) {
        throw UsageError(option + ": the folder " + folder.string() + " does not exist");
    }
    // Found now rather than after a long render (the writers fail cleanly either way).
    if (std::filesystem::is_directory(path)) throw UsageError(option + ": " + path.string() + " is a folder");
    if (::access(folder.c_str(), W_OK) != 0) {
        throw UsageError(option + ": the folder " + folder.string() + " is not writable");
    }
}

}  // namespace

namespace {

// Render's own options: the outputs and the frames.
struct RenderOutputs {
    std::string out = "vplkit.png";
    std::optional<std::string> out_hdr, out_direct, out_indirect, stats;
    uint32_t frames = 1;
    bool no_antialias = false;
    std::optional<double> budget_ms;  // --budget-ms: the kit chooses the method and its knobs
};

// --NAME FILE into `into` (unset when not given).
void add_file_option(CLI::App& command, const std::string& name, std::optional<std::string>& into,
                     const std::string& value_name, const std::string& help) {
    command
        .add_option_function<std::string>(
            name, [&into](const std::string& v) { into = v; }, help)
        ->option_text(value_name)
        ->group("outputs");
}

void add_render_outputs(CLI::App& command, RenderOutputs& o) {
    command
        .add_option("--out", o.out,
                    "the tonemapped image, PNG; a .exr name writes the layered EXR of --out-hdr instead")
        ->capture_default_str()
        ->option_text("FILE.png|.exr")
        ->group("outputs");
    add_file_option(command, "--out-hdr", o.out_hdr, "FILE.pfm|.exr",
                    "also the linear radiance, PFM; or a layered OpenEXR file (.exr) of every layer the frame "
                    "has: beauty, direct, indirect (with an indirect-light method), albedo, normal (world space), "
                    "depth (along the camera's axis, in scene units, inf where no surface was drawn) and variance "
                    "(with --denoise: the indirect light's luminance variance); channels beauty.R ... depth.Z, "
                    "normal.X, variance.Y; radiance, depth, variance 32-bit floats (a sun-lit pixel can pass "
                    "half's 65504), albedo and normal 16-bit");
    add_file_option(command, "--out-direct", o.out_direct, "FILE.pfm", "also the linear direct light, PFM");
    add_file_option(command, "--out-indirect", o.out_indirect, "FILE.pfm", "also the linear indirect light, PFM");
    add_file_option(command, "--stats", o.stats, "FILE.json",
                    "also a JSON file: the device (lavapipe or not), the plans (each stage kept or left out and "
                    "why), GPU times (frame_ms: the median frame's sum over every pass; per stage and per pass), "
                    "the counters printed, the firefly share; a number that is not finite is written as null");
    whole_number(command
                     .add_option("--frames", o.frames,
                                 "render the frame F times and print each stage's median time over frames 2..F "
                                 "(the first pays for shader compiles); the image is the mean of the F frames on "
                                 "the static camera, each with new samples and its G-buffer at a sub-pixel "
                                 "offset (anti-aliasing; with --denoise the filter accumulates the indirect "
                                 "light itself)")
                     ->capture_default_str(),
                 "F", 1, 1000)
        ->group("outputs");
    command.add_flag("--no-antialias", o.no_antialias, "with --frames: every frame at the pixel centres")
        ->group("outputs");
    add_budget_option(command, o.budget_ms, "")->group("outputs");
}

int render_or_plan(const CLI::App& command, const RenderOptions& options, const RenderOutputs& outputs,
                   bool plan_only) {
    RenderRequest request = options.request();
    RenderSettings& settings = request.settings;
    const ContextOptions& context_options = request.context;
    const std::filesystem::path out = outputs.out;
    const auto& out_hdr = outputs.out_hdr;
    const auto& out_direct = outputs.out_direct;
    const auto& out_indirect = outputs.out_indirect;
    const uint32_t frames = outputs.frames;
    // Several frames on the static camera: jittered and averaged (antialias.hpp) unless asked not to.
    settings.antialias = !outputs.no_antialias && frames > 1 && !settings.vpls_only;
    const auto& stats_path = outputs.stats;
    if (settings.vpls_only && (out_hdr || out_direct || out_indirect)) {
        throw UsageError(
            "--vpls-only writes only --out (the VPL view); drop --out-hdr, --out-direct and --out-indirect");
    }
    validate_render_request(request);
    check_output("--out", out, {".png", ".exr"});
    if (out_hdr) check_output("--out-hdr", *out_hdr, {".pfm", ".exr"});
    if (out_direct) check_output("--out-direct", *out_direct, {".pfm"});
    if (out_indirect) check_output("--out-indirect", *out_indirect, {".pfm"});
    if (stats_path) check_output("--stats", *stats_path, {".json"});
    const auto is_exr = [](const std::filesystem::path& path) { return path.extension() == ".exr"; };
    if (settings.vpls_only && is_exr(out)) throw UsageError("--vpls-only draws the VPLs into a PNG: give --out a .png");
    // The EXR's albedo, normal, depth and variance layers come from the G-buffer and the denoiser.
    settings.read_back_aovs = is_exr(out) || (out_hdr && is_exr(*out_hdr));

    LoadedScene loaded = load_request_scene(request);
    const scene::Scene& scene = loaded.scene;
    const std::string& described = loaded.described;
    const double load_ms = loaded.load_ms;

    if (plan_only) {
        // No device work: the plan is a function of the scene and the settings.
        std::printf("scene: %s: %zu triangles, %zu materials, %zu lights, %zu emissive triangles\n", described.c_str(),
                    scene.triangle_count(), scene.materials.size(), scene.lights.size(),
                    scene.emissive_triangles.size());
        std::printf("method: %s, %ux%u\n", gi_method_name(settings.method), settings.width, settings.height);
        const FramePlan plan = plan_frame(scene, settings, "");
        std::printf("%s\n%s", plan.summary().c_str(), with_flags(plan.describe()).c_str());
        return 0;
    }
    auto context = Context::create(context_options);
    const DeviceInfo& device = context->info();
    std::printf("device: %s (%s): %s\n", device.name.c_str(), device.type_name.c_str(), device.reason.c_str());
    std::printf("scene: %s: %zu triangles, %zu materials, %zu lights, %zu emissive triangles (loaded in %.0f ms)\n",
                described.c_str(), scene.triangle_count(), scene.materials.size(), scene.lights.size(),
                scene.emissive_triangles.size(), load_ms);

    Renderer renderer(*context, scene);
    std::printf("bvh: %zu nodes, depth %u, built in %.0f ms\n", renderer.bvh().nodes.size(), renderer.bvh().depth,
                renderer.bvh_build_ms());
    // --budget-ms: times and noise measured here (or read from the cache), then the choice.
    std::optional<BudgetPlan> budget;
    if (outputs.budget_ms) {
        budget.emplace(plan_budget(renderer, device, scene, scene.camera(), settings, *outputs.budget_ms,
                                   described + (request.time ? " at t " + std::to_string(*request.time) : ""),
                                   budget_fixed_by_options(command, settings)));
        settings = budget->settings;
    }
    const GiMethodInfo& method = gi_method(settings.method);  // the budget's, when it chose
    const bool terminal = isatty(fileno(stderr));
    settings.progress = [terminal](uint32_t done, uint32_t total) {
        if (terminal) {
            std::fprintf(stderr, "\r[exact gi] %u/%u VPLs", done, total);
            if (done == total) std::fprintf(stderr, "\r%40s\r", "");
        } else if (done == total || done % 1024 < 32) {
            std::fprintf(stderr, "[exact gi] %u/%u VPLs\n", done, total);
        }
        std::fflush(stderr);
    };
    settings.smc_warmup_progress = [terminal](uint32_t done, uint32_t total) {
        if (terminal) {
            std::fprintf(stderr, "\r[smc warm-up] %u/%u updates", done, total);
            if (done == total) std::fprintf(stderr, "\r%40s\r", "");
        } else if (done == total || done % 10 == 0) {
            std::fprintf(stderr, "[smc warm-up] %u/%u updates\n", done, total);
        }
        std::fflush(stderr);
    };
    // Several frames: the first pays for lavapipe's shader compiles at first dispatch (and a
    // GPU's warm-up); the times printed are each stage's median over the frames after it.
    std::vector<FramePlan> frame_plans;
    std::vector<std::vector<PassTiming>> frame_timings;  // for --stats
    PlanLog plans;
    RenderedImage image;
    for (uint32_t frame = 0; frame < frames; ++frame) {
        if (frames > 1) std::fprintf(stderr, "[render] frame %u/%u\n", frame + 1, frames);
        // Accumulating: every frame draws new samples (the frame counter) over the same VPLs, and
        // with anti-aliasing its G-buffer moves by its sub-pixel offset.
        if (settings.denoise != DenoiseMode::off || settings.antialias) settings.frame = frame;
        image = renderer.render(scene.camera(), settings);
        frame_plans.push_back(image.plan);
        frame_timings.push_back(image.timings);
        plans.add(frame, image.plan);
    }
    for (const std::string& line : plan_lines(frame_plans)) std::printf("%s\n", line.c_str());
    for (const std::string& note : image.notes) std::printf("note: %s\n", with_flags(note).c_str());
    const bool made_vpls = settings.method != GiMethod::none || settings.vpls_only;
    if (settings.method == GiMethod::flc && !settings.vpls_only) {
        std::printf("indirect: %u flc VPLs (%u levels, mu %g, N_avg %g), splatted unshadowed\n", image.vpl_count,
                    settings.flc_levels, settings.flc_mu, settings.flc_vpls_per_point);
    } else if (made_vpls && image.vpl_source == VplSource::brsm) {
        std::printf(
            "%s: %u VPLs by BRSM from %zu lights' %u^2 shadow maps (%u samples per texel, defensive share %.2f)\n",
            settings.vpls_only ? "vpls" : "indirect", image.vpl_count, scene.lights.size(), settings.rsm_resolution,
            settings.brsm.samples_per_texel, settings.brsm.defensive_fraction);
    } else if (made_vpls && image.vpl_source == VplSource::smc && image.smc) {
        const vplkit::SmcCounts& c = *image.smc;
        std::printf(
            "%s: %u VPLs by SMC (budget %u, %u bounces); this frame: %u invalid (%u revalidated), %u candidates, "
            "M_strong %u, M_min %u, %u removed, %u moved in\n",
            settings.vpls_only ? "vpls" : "indirect", image.vpl_count, settings.smc.budget, settings.smc.bounces,
            c.invalid, c.revalidated, c.candidates, c.strong, c.min_moves, c.removed, c.moved);
    } else if (made_vpls) {
        std::printf("%s: %u VPLs from %u light paths x %u bounces\n", settings.vpls_only ? "vpls" : "indirect",
                    image.vpl_count, settings.vpl_paths, settings.vpl_bounces);
    }
    if (method.ground_truth && image.dropped_pixels > 0) {
        std::printf("warning: %u pixels had a non-finite VPL contribution left out\n", image.dropped_pixels);
    }
    if (method.samples && !settings.vpls_only && image.vpl_count > 0) {
        const stages::GiCounts& c = image.gi_counts;
        std::printf("%s: %u spp", gi_method_name(settings.method), settings.samples_per_pixel);
        if (method.blocks) std::printf(", %ux%u blocks", settings.block_size, settings.block_size);
        if (settings.interleave > 1) std::printf(", %ux%u interleaved", settings.interleave, settings.interleave);
        if (settings.hybrid_traversal == stages::HybridTraversal::lightcuts) std::printf(", rtslc's traversal");
        if (method.reads_sst) std::printf(", nu_min %.2f, sigma_max %.3g", settings.sst.nu_min, image.sst_sigma_max);
        std::printf("; %.2f tree levels per traversal (%u traversals), %u dead branches", c.levels_per_traversal(),
                    c.traversals, c.dead_branches);
        if (method.mock_cuts) std::printf(", %u mock-cut pixels", c.mock_cut_pixels);
        std::printf("\n");
    }
    if (settings.half_resolution_gi && !settings.vpls_only) {
        std::printf("gi at %ux%u, upsampled: %u pixels took the nearest sample (no similar one), %u got none\n",
                    image.gi_width, image.gi_height, image.upsample_counts.fallback_pixels,
                    image.upsample_counts.empty_pixels);
    }
    if (settings.denoise != DenoiseMode::off && !settings.vpls_only && !method.ground_truth) {
        std::printf(
            "denoise %s over %u frame(s); firefly clamp (mean + %.1f sigma) moved %.4f%% of the accumulated "
            "indirect irradiance's luminance onto the outliers' neighbours in the last (none removed)\n",
            denoise_mode_name(settings.denoise), frames, settings.denoise_options.firefly_k_sigma,
            100.0 * image.firefly_moved_fraction);
    }
    if (image.non_finite_pixels > 0) {
        throw Error("render: " + std::to_string(image.non_finite_pixels) +
                    " pixels came out NaN or infinite; no image written (this is a bug: please report it)");
    }

    std::fputs(stage_table(frame_timings, image.width, image.height).c_str(), stdout);
    if (method.ground_truth && !settings.vpls_only) {
        std::printf("exact gi by the host's wall clock: %.3f ms\n", image.exact_gi_wall_ms);
    }

    std::vector<std::string> written;
    const auto wrote = [&written](const std::filesystem::path& path) {
        std::printf("wrote %s\n", path.string().c_str());
        written.push_back(path.string());
    };
    const auto write_stats = [&] {
        if (!stats_path) return;
        nlohmann::ordered_json stats = stats_header("render");
        stats["device"] = device_stats(device);
        stats["scene"] = {{"name", described},
                          {"triangles", scene.triangle_count()},
                          {"materials", scene.materials.size()},
                          {"lights", scene.lights.size()},
                          {"emissive_triangles", scene.emissive_triangles.size()},
                          {"load_ms", json_number(load_ms)},
                          {"bvh_build_ms", json_number(renderer.bvh_build_ms())}};
        stats["settings"] = {{"method", gi_method_name(settings.method)},
                             {"denoise", denoise_mode_name(settings.denoise)},
                             {"exposure", json_number(image.exposure)},
                             {"seed", settings.seed}};
        stats["width"] = image.width;
        stats["height"] = image.height;
        stats["frames"] = frames;
        stats["plans"] = plans.json();
        stats.update(timing_stats(frame_timings));
        if (budget) stats["budget"] = budget_stats_json(budget->choice);
        stats["counters"] = counters_stats(image, settings);
        // Null when the denoiser did not run (no firefly clamp).
        stats["firefly_moved_fraction"] =
            image.plan.runs(FrameStage::denoise) ? json_number(image.firefly_moved_fraction) : nullptr;
        stats["outputs"] = written;
        write_json_file(*stats_path, stats);
        std::printf("wrote %s\n", stats_path->c_str());
    };
    if (settings.antialias) {
        std::printf("anti-aliasing: the mean of %u frames, each G-buffer at a Halton(2,3) sub-pixel offset%s\n", frames,
                    settings.denoise != DenoiseMode::off && !method.ground_truth
                        ? " (the indirect light: the filter's own accumulation)"
                        : "");
    }
    if (!settings.vpls_only && settings.auto_exposure) {
        std::printf(
            "exposure %.3g (automatic: the lit pixels' %.0fth luminance percentile to %.1f before the tone "
            "curve; --exposure E fixes it; HDR outputs are not scaled)\n",
            image.exposure, 100.0 * kAutoExposurePercentile, kAutoExposureTarget);
    } else if (!settings.vpls_only) {
        std::printf("exposure %.3g (--exposure)\n", image.exposure);
    }
    if (settings.vpls_only) {
        if (image.vpl_count == 0) {
            throw Error("render: no VPLs were placed (no light reaches a reflecting surface); no image written");
        }
        const stages::CameraView view = vplkit::camera_view(scene.camera(), image.width, image.height);
        const VplView drawn = draw_vpl_view(image, view.view_projection, view.position);
        std::printf("vpl view: %u VPLs seen by the camera, %u hidden behind nearer surfaces, %u off screen\n",
                    drawn.visible, drawn.hidden, drawn.off_screen);
        write_png(out, image.width, image.height, drawn.rgba8);
        wrote(out);
        write_stats();
        return 0;
    }
    if (is_exr(out)) {
        write_frame_exr(out, image, settings);
    } else {
        write_png(out, image.width, image.height, image.rgba8);
    }
    wrote(out);
    if (out_hdr && is_exr(*out_hdr)) {
        write_frame_exr(*out_hdr, image, settings);
        wrote(*out_hdr);
    } else if (out_hdr) {
        write_pfm(*out_hdr, image.width, image.height, image.radiance);
        wrote(*out_hdr);
    }
    if (out_direct) {
        write_pfm(*out_direct, image.width, image.height, image.direct);
        wrote(*out_direct);
    }
    if (out_indirect) {
        write_pfm(*out_indirect, image.width, image.height, image.indirect);
        wrote(*out_indirect);
    }
    write_stats();
    return 0;
}

}  // namespace

void add_render(CLI::App& vplkit, Runners& runners) {
    CLI::App* render = add_command(
        vplkit, "render", "render a scene (set-up name or glTF file) to a PNG, with per-stage GPU times",
        "Renders one frame (G-buffer; direct light from punctual lights and emissive triangles with BVH shadow "
        "rays; indirect light by the chosen method; tone mapping) and prints the device used, the plan (the stages "
        "run and why) and the GPU time of every stage.");
    auto options = std::make_shared<RenderOptions>(*render);
    auto outputs = std::make_shared<RenderOutputs>();
    add_render_outputs(*render, *outputs);
    runners.push_back(
        {render, [render, options, outputs] { return render_or_plan(*render, *options, *outputs, false); }});
}

void add_plan(CLI::App& vplkit, Runners& runners) {
    CLI::App* plan = add_command(
        vplkit, "plan", "the stages a frame of a scene would run and why (render's options; no device work)",
        "Prints the stages a frame with these options would run, and for every stage kept or left out the reason "
        "(the effects planner, runtime/include/vplkit/planner.hpp). Reads the scene; no device work. `vplkit "
        "render` prints the plan's one-line summary. The scene's warnings (what the file states that vplkit skips "
        "or approximates) are printed first; --strict fails on them.");
    auto options = std::make_shared<RenderOptions>(*plan);
    runners.push_back({plan, [plan, options] { return render_or_plan(*plan, *options, RenderOutputs{}, true); }});
}

}  // namespace vplkit::cli
