// `vplkit sequence`: N frames along a camera path with render's options, written as PNG (PFM on
// request) with each frame's stage times; with --reference also the per-frame ground truth and
// the SMC paper's temporal metrics (|E|, |E'| on Reinhard-tonemapped indirect luminance) as CSV, a
// plot and a report.

#include "budget_option.hpp"
#include "camera_path.hpp"
#include "cli_checks.hpp"
#include "commands.hpp"
#include "plot_script.hpp"
#include "render_request.hpp"
#include "render_stats.hpp"
#include "stats_json.hpp"

#include "vplkit/cache_key.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/image_io.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/sequence_metrics.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace vplkit::cli {

namespace {

std::string camera_key(const scene::Camera& c) {
    std::ostringstream key;
    key.precision(9);
    key << c.position.x << ' ' << c.position.y << ' ' << c.position.z << ' ' << c.forward.x << ' ' << c.forward.y << ' '
        << c.forward.z << ' ' << c.up.x << ' ' << c.up.y << ' ' << c.up.z << ' ' << c.yfov << ' ' << c.znear << ' '
        << c.zfar;
    return key.str();
}

std::string lights_key(const scene::Scene& scene) {
    std::ostringstream key;
    key.precision(9);
    for (const scene::Light& l : scene.lights) {
        key << int(l.type) << ' ' << l.position.x << ' ' << l.position.y << ' ' << l.position.z << ' ' << l.direction.x
            << ' ' << l.direction.y << ' ' << l.direction.z << ' ' << l.color.x << ' ' << l.color.y << ' ' << l.color.z
            << ' ' << l.intensity << ';';
    }
    return key.str();
}

void write_text(const std::filesystem::path& path, const std::string& text) {
    const std::filesystem::path partial = path.string() + ".partial";
    {
        std::ofstream out(partial);
        out << text;
        if (!out) throw Error("cannot write " + path.string());
    }
    std::filesystem::rename(partial, path);
}

std::string frame_name(uint32_t frame, const char* extension) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%04u.%s", frame, extension);
    return name;
}

}  // namespace

namespace {

// Sequence's own options (render's are a RenderOptions beside them).
struct SequenceOptions {
    std::optional<std::string> out, stats;
    std::string path = "orbit";
    uint32_t frames = 16;
    float orbit_degrees = 30.0f;
    bool pfm = false, fresh_vpls = false, reference = false;
    bool animate = false, loop = false;
    std::string pose = "auto";  // --pose: where moving vertices are posed
    float fps = 24.0f;
    uint32_t reference_paths = 16384;
    std::string cache = "out/sequence-cache";
    std::optional<double> budget_ms;  // --budget-ms: chosen for the first frame's view, re-planned on drift
};

int run_sequence(const CLI::App& command, const SequenceOptions& o, const RenderOptions& render_options) {
    const std::optional<std::string>& out_text = o.out;
    const std::string& path_arg = o.path;
    const uint32_t frames = o.frames;
    if (command.count("--orbit-degrees") && path_arg != "orbit") {
        throw UsageError("--orbit-degrees is for --path orbit");
    }
    if ((command.count("--fps") || o.loop) && !o.animate) throw UsageError("--fps and --loop need --animate");
    if (command.count("--pose") && !o.animate) throw UsageError("--pose needs --animate");
    // An animated scene is watched from a still camera unless a turn is asked for.
    const float orbit_degrees = o.animate && !command.count("--orbit-degrees") ? 0.0f : o.orbit_degrees;
    const bool pfm = o.pfm;
    const bool fresh_vpls = o.fresh_vpls;
    const bool reference = o.reference;
    if (command.count("--reference-paths") && !reference) throw UsageError("--reference-paths needs --reference");
    const uint32_t reference_paths = o.reference_paths;
    const std::filesystem::path cache = o.cache;
    const std::optional<std::string>& stats_path = o.stats;
    RenderRequest request = render_options.request();
    if (!out_text) throw UsageError("--out DIR is required");
    if (stats_path) {
        const std::filesystem::path stats_file = *stats_path;
        if (stats_file.extension() != ".json") {
            throw UsageError("--stats expects a .json file name, got '" + *stats_path + "'");
        }
        const std::filesystem::path folder = stats_file.parent_path().empty() ? "." : stats_file.parent_path();
        if (!std::filesystem::is_directory(folder)) {
            throw UsageError("--stats: the folder " + folder.string() + " does not exist");
        }
    }
    validate_render_request(request);
    filter_frames_by_default(request);
    RenderSettings& settings = request.settings;
    if (settings.vpls_only) throw UsageError("--vpls-only is for vplkit render");
    if (request.camera_flags.position && path_arg != "orbit") {
        throw UsageError(
            "--position and --target are for --path orbit (its start and centre): a keyframe file "
            "places the camera itself (--fov applies to both)");
    }
    if (fresh_vpls && settings.vpl_source == VplSource::smc) {
        throw UsageError("--fresh-vpls is for --vpl-source ir or brsm: an SMC set persists by design");
    }
    const uint32_t base_seed = settings.seed;
    if (reference && settings.method == GiMethod::none && !o.budget_ms) {
        throw UsageError("--reference compares indirect light: give an indirect-light --method");
    }
    std::optional<std::vector<CameraKey>> keys;
    if (path_arg != "orbit") {
        try {
            keys = read_camera_keys(path_arg);
        } catch (const Error& e) {
            throw UsageError(std::string("--path: ") + e.what());
        }
    }
    const std::filesystem::path out_dir = *out_text;
    std::filesystem::create_directories(out_dir);
    if (reference) std::filesystem::create_directories(cache);

    LoadedScene loaded = o.animate ? load_request_posable(request) : load_request_scene(request);
    const scene::Scene& scene = loaded.active();
    // --animate: frame f at start + f / fps; past the animations' end the pose holds (each channel
    // clamps to its keys), or with --loop it starts again from the start.
    const double start_time = request.time.value_or(0.0);
    double animation_end = start_time;
    for (const scene::Animation& a : scene.animations) {
        if (a.applied) animation_end = std::max(animation_end, a.end);
    }
    auto frame_time = [&](uint32_t f) {
        const double t = start_time + double(f) / o.fps;
        const double span = animation_end - start_time;
        return o.loop && span > 0.0 ? start_time + std::fmod(t - start_time, span) : t;
    };
    if (o.animate) {
        std::printf("animation: %.3f s to %.3f s at %g frames per second, %s\n", start_time, animation_end, o.fps,
                    o.loop ? "looping" : "holding the last pose after the end");
    }
    // --up (an orbit's only: it needs --position): the orbit turns about it and keeps it up.
    const glm::vec3 up = request.camera_flags.up.value_or(glm::vec3(0.0f, 1.0f, 0.0f));
    const std::vector<scene::Camera> path = keys ? keyframe_path(*keys, scene.camera(), frames)
                                                 : orbit_path(scene.camera(), loaded.target, orbit_degrees, frames, up);

    auto context = Context::create(request.context);
    std::printf("device: %s (%s)\n", context->info().name.c_str(), context->info().type_name.c_str());
    std::printf("scene: %s, %ux%u, %u frames along %s\n", loaded.described.c_str(), settings.width, settings.height,
                frames,
                keys                    ? path_arg.c_str()
                : orbit_degrees == 0.0f ? "a still camera"
                                        : "an orbit");
    Renderer renderer(*context, scene);
    std::optional<Renderer> reference_renderer;
    RenderSettings reference_settings = settings;
    reference_settings.method = GiMethod::exact;
    reference_settings.vpl_source = VplSource::ir;
    reference_settings.vpl_paths = reference_paths;
    reference_settings.seed = settings.seed + 1000003;  // another VPL set than the one measured
    reference_settings.half_resolution_gi = false;
    reference_settings.denoise = DenoiseMode::off;
    if (reference) reference_renderer.emplace(*context, scene);
    // --budget-ms: calibrated from the first frame's view; re-planned when the measured times drift.
    std::optional<BudgetPlan> budget;
    nlohmann::ordered_json replans = nlohmann::ordered_json::array();
    if (o.budget_ms) {
        budget.emplace(plan_budget(renderer, context->info(), scene, path.front(), settings, *o.budget_ms,
                                   loaded.described + (request.time ? " at t " + std::to_string(*request.time) : ""),
                                   budget_fixed_by_options(command, settings)));
        settings = apply_budget_config(settings, budget->choice.chosen.config, budget->vpl_source);
    }

    const bool terminal = isatty(fileno(stderr));
    settings.smc_warmup_progress = [terminal](uint32_t done, uint32_t total) {
        if (terminal || done == total || done % 10 == 0) {
            std::fprintf(stderr, terminal ? "\r[sequence] smc warm-up %u/%u" : "[sequence] smc warm-up %u/%u\n", done,
                         total);
            if (terminal && done == total) std::fprintf(stderr, "\n");
            std::fflush(stderr);
        }
    };

    std::string times = "frame,stage,gpu_ms\n";
    std::string metrics_csv = "frame,mean_abs_error,mean_abs_error_change\n";
    TemporalErrorMeter meter;
    // The metrics' Reinhard curve takes --exposure's scale (1 unless given), not the automatic one.
    const float metrics_exposure = settings.auto_exposure ? 1.0f : settings.exposure;
    // --stats: each frame's passes, plan and counters.
    std::vector<std::vector<PassTiming>> frame_timings;
    PlanLog plans;
    nlohmann::ordered_json frame_stats = nlohmann::ordered_json::array();
    const auto start = std::chrono::steady_clock::now();
    for (uint32_t f = 0; f < frames; ++f) {
        settings.frame = f;
        if (o.animate && f > 0) {
            // Only what moved is uploaded; the plan says what was made again and why.
            const PosePath pose_path = o.pose == "gpu"    ? PosePath::gpu
                                       : o.pose == "host" ? PosePath::host
                                                          : PosePath::automatic;
            const PoseUpdate update = renderer.pose(*loaded.posable, frame_time(f), pose_path);
            if (reference_renderer) {
                renderer.read_pose_back(*loaded.posable);  // a GPU pose's vertices, for the reference's upload
                reference_renderer->update_pose({update.geometry, update.lights, false});
            }
            std::printf("frame %u: t = %.3f s: %s\n", f + 1, frame_time(f), update.summary.c_str());
        }
        if (fresh_vpls) settings.seed = base_seed + f;
        const RenderedImage image = renderer.render(path[f], settings);
        if (f == 0 && settings.auto_exposure) {
            // The first frame's automatic exposure for the whole sequence: no flicker between frames.
            settings.auto_exposure = false;
            settings.exposure = image.exposure;
            std::printf("exposure %.3g (automatic, from the first frame, kept for all)\n", image.exposure);
        }
        if (image.non_finite_pixels > 0) {
            throw Error("sequence: frame " + std::to_string(f) + " has " + std::to_string(image.non_finite_pixels) +
                        " NaN or infinite pixels (a bug: please report it)");
        }
        write_png(out_dir / frame_name(f, "png"), image.width, image.height, image.rgba8);
        if (pfm) write_pfm(out_dir / frame_name(f, "pfm"), image.width, image.height, image.radiance);
        std::map<std::string, double> by_stage;
        std::vector<std::string> order;
        double total = 0.0;
        for (const PassTiming& t : image.timings) {
            if (!by_stage.count(t.name)) order.push_back(t.name);
            by_stage[t.name] += t.gpu_ms;
            total += t.gpu_ms;
        }
        for (const std::string& name : order) {
            char line[256];
            std::snprintf(line, sizeof(line), "%u,%s,%.4f\n", f, name.c_str(), by_stage[name]);
            times += line;
        }
        std::string status = ", " + std::to_string(image.vpl_count) + " VPLs";
        if (image.smc) {
            status += " (smc: " + std::to_string(image.smc->invalid) + " invalid, " + std::to_string(image.smc->moved) +
                      " moved in)";
        }
        if (reference) {
            std::ostringstream key;
            key << "sequence reference v1\n"
                << loaded.described << "\n"
                << camera_key(path[f]) << "\n"
                << "time " << (o.animate ? frame_time(f) : start_time) << "\n"
                << lights_key(scene) << "\n"
                << settings.width << 'x' << settings.height << " paths " << reference_paths << " bounces "
                << settings.vpl_bounces << " seed " << reference_settings.seed << " brdf "
                << (request.lambertian ? "lambert" : "gltf") << "\n";
            const std::filesystem::path cached = cache / ("reference_" + fnv1a_hex(key.str()) + ".pfm");
            std::vector<float> truth;
            if (std::filesystem::exists(cached)) {
                PfmImage r = read_pfm(cached);
                if (r.width != image.width || r.height != image.height) {
                    throw Error(cached.string() + ": a cached reference of another size");
                }
                truth = std::move(r.rgb);
            } else {
                std::fprintf(stderr, "[sequence] frame %u/%u: reference (exact gather)...\n", f + 1, frames);
                const RenderedImage r = reference_renderer->render(path[f], reference_settings);
                truth = r.indirect;
                write_pfm(cached, r.width, r.height, truth);
                write_text(cached.string() + ".key", key.str());
            }
            meter.add_frame(reinhard_luminance(image.indirect, metrics_exposure),
                            reinhard_luminance(truth, metrics_exposure));
            const TemporalError& m = meter.result();
            char line[128];
            std::snprintf(line, sizeof(line), "%u,%.6f,%s\n", f, m.mean_abs_error.back(),
                          f == 0 ? "" : std::to_string(m.mean_abs_error_change.back()).c_str());
            metrics_csv += line;
            status += ", |E| " + std::to_string(m.mean_abs_error.back());
            if (f > 0) status += ", |E'| " + std::to_string(m.mean_abs_error_change.back());
        }
        frame_timings.push_back(image.timings);
        plans.add(f, image.plan);
        frame_stats.push_back(
            {{"frame_index", f}, {"gpu_ms", json_number(total)}, {"counters", counters_stats(image, settings)}});
        if (image.plan.runs(FrameStage::denoise))
            frame_stats.back()["firefly_moved_fraction"] = json_number(image.firefly_moved_fraction);
        if (reference) {
            frame_stats.back()["mean_abs_error"] = json_number(meter.result().mean_abs_error.back());
            if (f > 0)
                frame_stats.back()["mean_abs_error_change"] = json_number(meter.result().mean_abs_error_change.back());
        }
        if (budget && budget->drift.record(total)) {
            // The device runs slower or faster than calibrated (load, reuse on a still camera):
            // the candidates' times scaled by what was measured, and the choice made again.
            replan_for_budget(*budget);
            settings = apply_budget_config(settings, budget->choice.chosen.config, budget->vpl_source);
            std::printf("frame %u: measured times %.2fx the calibration's: re-planned: %s\n", f + 1,
                        budget->drift.scale(), budget->choice.line().c_str());
            nlohmann::ordered_json replan = budget_stats_json(budget->choice);
            replan["after_frame"] = f;
            replan["scale"] = json_number(budget->drift.scale());
            replans.push_back(replan);
        }
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "[sequence] frame %u/%u: %.1f ms GPU%s (%.0f s so far)\n", f + 1, frames, total,
                     status.c_str(), elapsed);
    }
    write_text(out_dir / "stage_times.csv", times);
    if (stats_path) {
        nlohmann::ordered_json stats = stats_header("sequence");
        stats["device"] = device_stats(context->info());
        stats["scene"] = {{"name", loaded.described},
                          {"triangles", scene.triangle_count()},
                          {"lights", scene.lights.size()},
                          {"emissive_triangles", scene.emissive_triangles.size()}};
        stats["settings"] = {{"method", gi_method_name(settings.method)},
                             {"denoise", denoise_mode_name(settings.denoise)},
                             {"path", keys ? path_arg : "orbit"},
                             {"fresh_vpls", fresh_vpls}};
        stats["width"] = settings.width;
        stats["height"] = settings.height;
        stats["frames"] = frames;
        stats["out"] = out_dir.string();
        stats["plans"] = plans.json();
        stats.update(timing_stats(frame_timings));
        if (budget) {
            // The last choice; each re-plan after the frame whose window drifted.
            stats["budget"] = budget_stats_json(budget->choice);
            stats["budget"]["replans"] = replans;
        }
        if (reference) {
            stats["average_mean_abs_error"] = json_number(meter.result().average_error());
            stats["average_mean_abs_error_change"] = json_number(meter.result().average_error_change());
        }
        stats["per_frame"] = frame_stats;
        write_json_file(*stats_path, stats);
        std::printf("wrote %s\n", stats_path->c_str());
    }
    std::printf("wrote %u frames and stage_times.csv to %s\n", frames, out_dir.string().c_str());
    if (!reference) return 0;

    write_text(out_dir / "metrics.csv", metrics_csv);
    const TemporalError& m = meter.result();
    const char* source = settings.vpl_source == VplSource::smc    ? "smc"
                         : settings.vpl_source == VplSource::brsm ? "brsm"
                         : settings.vpl_source == VplSource::ir   ? "ir"
                                                                  : "auto";
    std::ostringstream report;
    report << "# Sequence: " << loaded.described << "\n\n"
           << frames << " frames, " << settings.width << "x" << settings.height << ", "
           << (keys ? "keyframes " + path_arg
                    : "orbit of " + std::to_string(int(std::lround(orbit_degrees))) + " degrees")
           << "; method " << gi_method_name(settings.method) << ", VPL source " << source << ", device "
           << context->info().name << ".\n\n"
           << "Reference per frame: exact gather over instant-radiosity VPLs from " << reference_paths
           << " light paths (" << settings.vpl_bounces << " bounces). Metrics (the SMC paper sec. 5.2) on the "
           << "Reinhard-tonemapped luminance L / (1 + L) of the indirect light:\n\n"
           << "| average \\|E\\| | average \\|E'\\| |\n| --- | --- |\n"
           << "| " << m.average_error() << " | " << m.average_error_change() << " |\n\n"
           << "![metrics](metrics.png)\n\nPer frame: `metrics.csv`; stage times: `stage_times.csv`.\n";
    write_text(out_dir / "report.md", report.str());
    std::printf("average |E| %.5f, average |E'| %.5f\n", m.average_error(), m.average_error_change());
    std::printf("wrote metrics.csv and report.md to %s\n", out_dir.string().c_str());
    // metrics.png from metrics.csv, titled with the scene's short name: a set-up's, or a file's stem.
    const std::string scene_name = request.scene_arg.empty() ? loaded.described.substr(0, loaded.described.find(" ("))
                                                             : std::filesystem::path(request.scene_arg).stem().string();
    draw_plots("sequence", out_dir, {"--scene", scene_name});
    return 0;
}

}  // namespace

void add_sequence(CLI::App& vplkit, Runners& runners) {
    CLI::App* sequence = add_command(
        vplkit, "sequence",
        "frames along a camera path (orbit or keyframes); --reference: temporal error |E|, |E'| vs exact",
        "Renders N frames along a camera path and writes DIR/frame_NNNN.png (and .pfm with --pfm, linear "
        "radiance) and DIR/stage_times.csv (each frame's GPU time per stage). A renderer lives for the whole "
        "sequence, so --vpl-source smc carries its VPLs from frame to frame. Takes render's options; --position "
        "X,Y,Z --target X,Y,Z place an orbit's first frame and its centre, --up the axis it turns about and "
        "its frames' up (default +Y; keyframes keep +Y up), --fov is every frame's (keyframes too).");
    auto o = std::make_shared<SequenceOptions>();
    sequence
        ->add_option_function<std::string>(
            "--out", [o](const std::string& v) { o->out = v; }, "required: the folder the frames are written to")
        ->option_text("DIR")
        ->group("sequence");
    sequence
        ->add_option("--path", o->path,
                     "orbit: about the set-up's target (a file's: its bounds' centre), turning --orbit-degrees over "
                     "the sequence; or a keyframe file, one key per line: TIME PX PY PZ TX TY TZ (position, "
                     "target), interpolated")
        ->capture_default_str()
        ->option_text("orbit|FILE")
        ->group("sequence");
    whole_number(sequence->add_option("--frames", o->frames, "frames")->capture_default_str(), "N", 1, 100000)
        ->group("sequence");
    number(sequence->add_option("--orbit-degrees", o->orbit_degrees, "--path orbit: the turn over the sequence")
               ->capture_default_str(),
           "D", NumberRange::any())
        ->group("sequence");
    sequence
        ->add_flag("--animate", o->animate,
                   "play the glTF file's animations (--scene FILE.gltf): frame f posed at --time (default 0) + f / "
                   "--fps without reading the file again, only what moved uploaded (the BVH refitted on the GPU); "
                   "the camera stays still unless --orbit-degrees turns it")
        ->group("sequence");
    number(
        sequence->add_option("--fps", o->fps, "--animate: frames per second of animation time")->capture_default_str(),
        "F", NumberRange::above(0.0))
        ->group("sequence");
    one_of(sequence
               ->add_option("--pose", o->pose,
                            "--animate: where skinned and morphed vertices are posed: gpu (a compute pass, then "
                            "read back), host, or auto (the GPU from 2048 moving vertices, where the file allows)")
               ->capture_default_str(),
           {"auto", "gpu", "host"})
        ->group("sequence");
    sequence
        ->add_flag("--loop", o->loop,
                   "--animate: start the animations again after their end (default: hold the last pose)")
        ->group("sequence");
    sequence->add_flag("--pfm", o->pfm, "also each frame's linear radiance, DIR/frame_NNNN.pfm")->group("sequence");
    sequence
        ->add_flag("--fresh-vpls", o->fresh_vpls,
                   "ir, brsm: new VPLs every frame (seed + frame), as the SMC paper's comparison draws them; without "
                   "it they follow --seed, the same light paths every frame")
        ->group("sequence");
    sequence
        ->add_flag("--reference", o->reference,
                   "also the per-frame reference: the exact gather (--method exact) over instant-radiosity VPLs from "
                   "--reference-paths light paths with the same bounces, cached in --cache by scene, camera, size "
                   "and VPL set; and the SMC paper's metrics on the Reinhard-tonemapped luminance of the indirect "
                   "light: |E| (mean absolute error) and |E'| (mean absolute change of the per-pixel error between "
                   "frames, eq. 10) in DIR/metrics.csv, DIR/metrics.png and DIR/report.md")
        ->group("sequence");
    whole_number(sequence->add_option("--reference-paths", o->reference_paths, "with --reference: its light paths")
                     ->capture_default_str(),
                 "P", 1, 1u << 22)
        ->group("sequence");
    sequence->add_option("--cache", o->cache, "where the references are kept")
        ->capture_default_str()
        ->option_text("DIR")
        ->group("sequence");
    sequence
        ->add_option_function<std::string>(
            "--stats", [o](const std::string& v) { o->stats = v; },
            "also a JSON file: the device, the plans (each stage kept or left out and why, per run of frames "
            "alike), GPU times (frame_ms: the median frame's sum over every pass; per stage and pass), each "
            "frame's counters (and metrics with --reference); a number that is not finite is written as null")
        ->option_text("FILE.json")
        ->group("sequence");
    add_budget_option(*sequence, o->budget_ms,
                      "; chosen for the first frame's view, and chosen again (printed) when the median of the last "
                      "5 frames' measured GPU time leaves 1/1.15..1.15 of the prediction")
        ->group("sequence");
    auto render_options = std::make_shared<RenderOptions>(*sequence);
    // Sequences are what the filter is for.
    sequence->get_option("--denoise")->default_str("svgf for a sampled method, off for direct and exact");
    runners.push_back(
        {sequence, [sequence, o, render_options] { return run_sequence(*sequence, *o, *render_options); }});
}

}  // namespace vplkit::cli
