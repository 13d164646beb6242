// `vplkit bench gi --scene NAME` (also `vplkit bench --scene NAME`): every indirect-light method's
// quality knobs swept on one standard set-up, each point rendered several frames and compared
// with the exact ground truth (cached on disk); bench_gi_report.cpp writes the results.

#include "bench_gi.hpp"
#include "bench_gi_budget.hpp"
#include "bench_gi_measure.hpp"
#include "bench_gi_truth.hpp"
#include "bench_options.hpp"
#include "camera_flags.hpp"
#include "cli.hpp"
#include "cli_checks.hpp"
#include "render_request.hpp"
#include "commands.hpp"
#include "scene_warnings.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/image_io.hpp"
#include "vplkit/image_metrics.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_lights.hpp"
#include "vplkit/scene_setups.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#ifndef VPLKIT_SETUPS_FILE
#error "VPLKIT_SETUPS_FILE (the repository's scenes/setups.txt) must be defined by the build"
#endif

namespace vplkit::cli {

namespace {

// The points of the curves' sweeps (gi_methods.hpp says which curve takes which), sweep by sweep,
// in the order they run.
std::vector<BenchPoint> plan_points(bool quick, unsigned vpl_budget, const std::vector<GiBenchCurveOf>& curves) {
    std::vector<BenchPoint> points;
    auto add = [&](std::string method, std::string sweep, unsigned spp, unsigned block, unsigned interleave, bool half,
                   bool mock, unsigned vpls) {
        BenchPoint p;
        p.method = std::move(method);
        p.sweep = std::move(sweep);
        p.spp = spp;
        p.block = block;
        p.interleave = interleave;
        p.half = half;
        p.mock_cuts = mock;
        p.vpls = vpls;
        points.push_back(p);
    };
    const std::vector<unsigned> spps =
        quick ? std::vector<unsigned>{1, 4} : std::vector<unsigned>{1, 2, 4, 8, 16, 32, 64};
    const std::vector<unsigned> blocks =
        quick ? std::vector<unsigned>{4, 8} : std::vector<unsigned>{1, 2, 4, 8, 16, 32};
    const std::vector<unsigned> some = quick ? std::vector<unsigned>{4} : std::vector<unsigned>{4, 8, 16, 32};
    // Every curve that takes `sweep`, by name.
    auto taking = [&](const char* sweep) {
        std::vector<std::string> names;
        for (const GiBenchCurveOf& c : curves) {
            if (c.sweeps(sweep)) names.emplace_back(c.curve->name);
        }
        return names;
    };
    for (const std::string& m : taking("spp")) {
        for (unsigned spp : spps) add(m, "spp", spp, 8, 1, false, true, vpl_budget);
    }
    for (const std::string& m : taking("block")) {
        for (unsigned k : blocks) {
            if (k != 8) add(m, "block", 8, k, 1, false, true, vpl_budget);
        }
    }
    for (const std::string& m : taking("resolution")) {
        for (unsigned spp : some) add(m, "resolution", spp, 8, 1, true, true, vpl_budget);
    }
    for (const std::string& m : taking("interleave")) {
        for (unsigned spp : some) add(m, "interleave", spp, 8, 2, false, true, vpl_budget);
    }
    for (const std::string& m : taking("mock")) {
        for (unsigned spp : some) add(m, "mock", spp, 8, 1, false, false, vpl_budget);
    }
    // The denoised curves: svgf over the point's frames, its passes in the frame time.
    for (const std::string& m : taking("denoise")) {
        for (unsigned spp : some) {
            add(m, "denoise", spp, 8, 1, false, true, vpl_budget);
            points.back().denoised = true;
        }
    }
    const std::vector<unsigned> counts =
        quick ? std::vector<unsigned>{vpl_budget * 4} : std::vector<unsigned>{1024, 16384, 65536, 262144, 1048576};
    for (const std::string& m : taking("vpls")) {
        for (unsigned n : counts) {
            if (n != vpl_budget) add(m, "vpls", 8, 8, 1, false, true, n);
        }
    }
    // flc (the FLC paper) places its own VPLs: its curve sweeps N_avg (eq. 1), the paper's 64..1024.
    const std::vector<float> navgs =
        quick ? std::vector<float>{32, 128} : std::vector<float>{32, 64, 128, 256, 512, 1024};
    for (const std::string& m : taking("navg")) {
        for (float navg : navgs) {
            add(m, "navg", 0, 0, 1, false, true, 0);
            points.back().flc_navg = navg;
        }
    }
    return points;
}

class Progress {
public:
    explicit Progress(size_t total) : total_(total), terminal_(isatty(fileno(stderr))) {}
    void show(size_t done, const std::string& what) {
        const int width = 30;
        const int filled = total_ == 0 ? width : int(width * done / total_);
        if (terminal_) {
            std::fprintf(stderr, "\r[bench] [%s%s] %zu/%zu %-40s", std::string(filled, '#').c_str(),
                         std::string(width - filled, '.').c_str(), done, total_, what.c_str());
            if (done == total_) std::fprintf(stderr, "\n");
        } else {
            std::fprintf(stderr, "[bench] %zu/%zu %s\n", done, total_, what.c_str());
        }
        std::fflush(stderr);
    }

private:
    size_t total_;
    bool terminal_;
};

// The curve of a name the bench gave its point (every point's name is a curve's).
GiBenchCurveOf curve_of(const std::string& name) {
    const std::optional<GiBenchCurveOf> curve = find_gi_bench_curve(name);
    if (!curve) throw Error("bench: no method or bench curve is named '" + name + "'");
    return *curve;
}

// The sweeps a run can be limited to (--sweeps), by plan_points' names.
const std::vector<std::string> kSweeps = {"spp",  "block", "resolution", "interleave",
                                          "mock", "vpls",  "denoise",    "navg"};

std::vector<std::string> curve_names() {
    std::vector<std::string> names;
    for (const GiBenchCurveOf& c : gi_bench_curves()) names.emplace_back(c.curve->name);
    return names;
}

// --methods LIST: those curves, in the table's order; every curve when not given.
std::vector<GiBenchCurveOf> chosen_curves(const std::optional<std::string>& text) {
    if (!text) return gi_bench_curves();
    const std::vector<std::string> names = split_names(*text);
    std::vector<GiBenchCurveOf> out;
    for (const GiBenchCurveOf& c : gi_bench_curves()) {
        if (std::find(names.begin(), names.end(), c.curve->name) != names.end()) out.push_back(c);
    }
    return out;
}

struct BenchGiOptions : BenchSceneOptions {
    bool no_budget_check = false;
    std::optional<uint32_t> vpls, camera, target_ms;
    std::optional<std::string> vpl_source, sweeps, methods;
    uint32_t seed = 0;
    std::string cache = "out/bench-cache";
    std::vector<std::string> suns, points;
};

const BenchDefaults& gi_defaults() {
    static const BenchDefaults d{"out/bench",
                                 48,
                                 27,
                                 320,
                                 180,
                                 1280,
                                 720,
                                 1,
                                 "frames per point (default 3, 2 with --quick; the first is not timed when F > 1)",
                                 "a smoke test: 48x27 (unless sized), 256 VPLs, 128^2 shadow maps, a few points, 2 "
                                 "frames"};
    return d;
}

}  // namespace

std::vector<float> unit_rgb(const std::vector<uint8_t>& rgba) {
    std::vector<float> rgb;
    rgb.reserve(rgba.size() / 4 * 3);
    for (size_t i = 0; i + 3 < rgba.size(); i += 4) {
        for (int c = 0; c < 3; ++c) rgb.push_back(rgba[i + c] / 255.0f);
    }
    return rgb;
}

std::string BenchPoint::label() const {
    if (sweep == "navg") {
        char text[32];
        std::snprintf(text, sizeof text, " navg %g", flc_navg);
        return method + text;
    }
    std::string s = method + " " + std::to_string(spp) + " spp";
    if (curve_of(method).method->blocks) s += " k" + std::to_string(block);
    if (interleave > 1) s += " m" + std::to_string(interleave);
    if (half) s += " half";
    if (!mock_cuts) s += " no-mock";
    if (denoised) s += " svgf";
    if (sweep == "vpls" || sweep == "budget") s += " " + std::to_string(vpls) + " vpls";
    if (sweep == "budget") s += " (budget)";
    return s;
}

namespace {

int run_bench_gi(const BenchGiOptions& o) {
    if (o.scene.empty()) throw UsageError("bench gi needs --scene NAME");
    check_camera_flags(o.camera_flags);
    const std::string& scene_name = o.scene;
    const bool quick = o.quick;
    const uint32_t frames = o.frames.value_or(quick ? 2 : 3);
    const std::optional<std::string>& source = o.vpl_source;
    const uint32_t vpl_budget = o.vpls.value_or(quick ? 256 : 4096);
    const uint32_t seed = o.seed;
    const double target_ms = o.target_ms.value_or(0);
    // --scene takes a set-up name or a .gltf/.glb file, as render does; a file brings its own
    // camera (--camera N) and lights, plus --sun and --point.
    const bool is_file = names_scene_file(scene_name);
    const std::optional<uint32_t>& camera = o.camera;
    const CameraFlags& camera_flags = o.camera_flags;
    std::vector<scene::Light> extra_lights;
    for (const std::string& spec : o.suns) extra_lights.push_back(scene::parse_sun(spec));
    for (const std::string& spec : o.points) extra_lights.push_back(scene::parse_point(spec));
    const std::string out_name = bench_scene_name(scene_name);
    const std::filesystem::path out = bench_out_folder(o, gi_defaults());
    const std::filesystem::path cache = o.cache;
    // --sweeps spp,resolution,...: only those sweeps (a shorter run, e.g. scripts/gpu_report.sh).
    const std::vector<std::string> sweeps = o.sweeps ? split_names(*o.sweeps) : std::vector<std::string>{};
    const std::vector<GiBenchCurveOf> curves = chosen_curves(o.methods);

    scene::Setup setup;
    scene::Scene scene;
    scene::LoadOptions load_options;
    load_options.camera = camera;
    if (is_file) {
        setup.name = out_name;
        setup.scene = std::filesystem::absolute(scene_name);
        scene = scene::load_gltf(setup.scene, load_options);
    } else {
        setup = scene::load_setups(VPLKIT_SETUPS_FILE).find(scene_name);
        scene = scene::load_setup_scene(setup, load_options);
    }
    scene.lights.insert(scene.lights.end(), extra_lights.begin(), extra_lights.end());
    apply_camera_flags(camera_flags, scene, scene.bounds.center());  // the exact frames' cache key has the camera
    report_scene_warnings(scene, o.strict);
    std::filesystem::create_directories(out / "images");
    std::filesystem::create_directories(cache);

    auto context = Context::create(o.context);
    const DeviceInfo& device = context->info();
    std::printf("device: %s (%s): %s\n", device.name.c_str(), device.type_name.c_str(), device.reason.c_str());
    RenderSettings base;
    const BenchSize size = bench_frame_size(o, gi_defaults(), device);
    base.width = size.width;
    base.height = size.height;
    base.seed = seed;
    base.vpl_source = source ? (*source == "brsm" ? VplSource::brsm : VplSource::ir)
                             : (scene.lights.empty() ? VplSource::ir : VplSource::brsm);
    base.vpl_paths = vpl_budget;
    base.brsm.vpl_count = vpl_budget;
    base.reuse_static_work = false;        // every timed frame places its VPLs and builds its tree
    if (quick) base.rsm_resolution = 128;  // BRSM's shadow maps dominate a tiny frame otherwise
    Renderer renderer(*context, scene);

    BenchRun run;
    run.scene = setup.name;
    run.device = device.name + " (" + device.type_name + ")";
    run.width = base.width;
    run.height = base.height;
    run.vpl_source = base.vpl_source == VplSource::brsm ? "brsm" : "ir";
    run.vpl_budget = vpl_budget;
    run.seed = seed;
    std::printf("scene: %s, %ux%u, %s VPLs (budget %u), %u frames per point\n", setup.name.c_str(), base.width,
                base.height, run.vpl_source.c_str(), vpl_budget, frames);

    const GroundTruth truth = bench_ground_truth(renderer, setup, scene, base, cache);
    run.exact_cached = truth.cached;
    run.exact_wall_ms = truth.wall_ms;
    std::filesystem::copy_file(truth.png, out / "images" / "exact.png",
                               std::filesystem::copy_options::overwrite_existing);
    run.exact_image = "images/exact.png";

    std::vector<BenchPoint> points = plan_points(quick, vpl_budget, curves);
    if (!sweeps.empty()) {
        std::erase_if(points, [&](const BenchPoint& p) {
            return std::find(sweeps.begin(), sweeps.end(), p.sweep) == sweeps.end();
        });
    }
    Progress progress(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
        BenchPoint& p = points[i];
        progress.show(i, p.label());
        RenderSettings s = base;
        const GiBenchCurveOf curve = curve_of(p.method);
        s.method = curve.method->method;
        s.samples_per_pixel = p.spp;
        s.block_size = p.block;
        s.interleave = p.interleave;
        s.half_resolution_gi = p.half;
        s.mock_cuts = p.mock_cuts;
        s.denoise = p.denoised ? DenoiseMode::svgf : DenoiseMode::off;
        if (curve.curve->variant) curve.curve->variant(s);
        if (p.sweep == "navg") s.flc_vpls_per_point = p.flc_navg;
        // Light paths leave up to one VPL per bounce: aim the path count at the VPL count.
        s.vpl_paths =
            base.vpl_source == VplSource::ir && p.sweep == "vpls" ? std::max(1u, p.vpls / base.vpl_bounces) : p.vpls;
        s.brsm.vpl_count = p.vpls;
        std::string failure;
        if (!measure_bench_point(renderer, scene.camera(), s, frames, truth.rgb, truth.radiance, out, p, failure)) {
            std::fprintf(stderr, "\n[bench] %s skipped: %s\n", p.label().c_str(), failure.c_str());
            run.skipped.push_back(p.label() + ": " + failure);
        }
    }
    progress.show(points.size(), "done");

    points.erase(std::remove_if(points.begin(), points.end(), [](const BenchPoint& p) { return p.frames == 0; }),
                 points.end());
    run.points = std::move(points);
    if (!o.no_budget_check) {
        BudgetCheckInputs check;
        check.base = &base;
        check.frames = frames;
        check.fractions =
            quick ? std::vector<double>{0.25, 0.5, 0.75} : std::vector<double>{0.1, 0.25, 0.4, 0.5, 0.6, 0.75, 0.9};
        check.truth_rgb = &truth.rgb;
        check.truth_radiance = &truth.radiance;
        check.out = out;
        check.cache_dir = cache / "budget";
        check.scene_id = setup.name + " (" + setup.scene.string() + ")";
        check_budget_chooser(renderer, device, scene, check, run);
    }
    run.target_ms = target_ms;
    if (run.target_ms <= 0) {
        for (const BenchPoint& p : run.points) {
            if (curve_of(p.method).curve->equal_time_target && p.sweep == "spp" && p.spp == (quick ? 4u : 8u)) {
                run.target_ms = p.frame_ms;
            }
        }
    }
    write_bench_report(out, run);
    // The headline on the terminal: each method's best error within the target frame time.
    std::printf("best RMSE within %.0f ms (the equal-time target):\n", run.target_ms);
    for (const GiBenchCurveOf& curve : curves) {
        const std::string m(curve.curve->name);
        const BenchPoint* best = nullptr;
        for (const BenchPoint& p : run.points) {
            if (p.method == m && p.sweep != "vpls" && p.frame_ms <= run.target_ms && (!best || p.rmse < best->rmse))
                best = &p;
        }
        if (best) {
            std::printf("  %-16s %.4f  (%s, %.1f ms)\n", m.c_str(), best->rmse, best->label().c_str(), best->frame_ms);
        } else {
            std::printf("  %-16s no point within the target\n", m.c_str());
        }
    }
    if (!run.budget_note.empty()) print_budget_check(run);
    std::printf("wrote %s (points.csv, points.json, plots, images)\n", (out / "report.md").string().c_str());
    return 0;
}

}  // namespace

void add_bench_gi(CLI::App& bench, Runners& runners) {
    CLI::App* gi = add_command(
        bench, "gi", "accuracy against time of every indirect-light method on a scene (--scene NAME)",
        "What every indirect-light method's accuracy costs on a standard set-up. Renders the exact ground truth "
        "once (cached in --cache, keyed by scene, camera, lights, size, VPL set and seed), then sweeps each "
        "method's knob. spp: samples per pixel 1..64 (sst, rtslc, hybrid, and hybrid-lightcuts: hybrid's cuts with "
        "rtslc's traversal, the thesis' sec. 7.1 protocol); block: cut block size 1..32 (rtslc, hybrid); "
        "resolution: GI at half resolution; interleave: interleaved sampling (rtslc); mock: mock cuts on/off "
        "(hybrid); vpls: the VPL count 1k..1M (build times); denoise: the methods with svgf; navg: flc's VPLs per "
        "point. Every point: F frames, per-stage GPU times (median and spread of frames 2..F), RMSE and SSIM of "
        "the tonemapped frame against the ground truth, relMSE of the linear radiance. Writes DIR/points.csv, "
        "points.json, plots, equal-time images with x10 difference pictures, and DIR/report.md.");
    auto o = std::make_shared<BenchGiOptions>();
    add_bench_scene_options(*gi, *o,
                            "required: a standard set-up (scenes/setups.txt) or a .gltf/.glb file, with its own camera "
                            "(--camera N) and lights plus --sun and --point, as render takes them");
    whole_number(gi->add_option_function<uint32_t>(
                     "--camera", [o](uint32_t v) { o->camera = v; }, "the file's camera N"),
                 "N", 0, 1u << 20);
    add_light_options(*gi, o->suns, o->points);
    add_bench_output_options(*gi, *o, gi_defaults());
    one_of(gi->add_option_function<std::string>(
               "--vpl-source", [o](const std::string& v) { o->vpl_source = v; },
               "default brsm when the scene has punctual lights, else ir"),
           {"ir", "brsm"});
    whole_number(gi->add_option_function<uint32_t>(
                     "--vpls", [o](uint32_t v) { o->vpls = v; }, "the VPL budget (default 4096, 256 with --quick)"),
                 "N", 1, 1u << 20);
    whole_number(gi->add_option("--seed", o->seed, "seed of the stochastic stages")->capture_default_str(), "S", 0,
                 UINT32_MAX);
    whole_number(gi->add_option_function<uint32_t>(
                     "--target-ms", [o](uint32_t v) { o->target_ms = v; },
                     "the equal-time target frame time (default: hybrid's at 8 spp, 4 with --quick)"),
                 "T", 1, 1u << 30);
    gi->add_option("--cache", o->cache, "where ground truths are kept")->capture_default_str()->option_text("DIR");
    name_list(gi->add_option_function<std::string>(
                  "--sweeps", [o](const std::string& v) { o->sweeps = v; },
                  "only these sweeps, comma-separated (default: all)"),
              kSweeps);
    name_list(gi->add_option_function<std::string>(
                  "--methods", [o](const std::string& v) { o->methods = v; },
                  "only these methods' curves, comma-separated (default: all)"),
              curve_names());
    gi->add_flag("--no-budget-check", o->no_budget_check,
                 "skip the check of --budget-ms's chooser (a calibration of about 30 frames, cached in --cache, then "
                 "the choice for budgets across the time range of the points in its space, each measured like a "
                 "point against the best measured within the budget)");
    runners.push_back({gi, [o] { return run_bench_gi(*o); }});
}

}  // namespace vplkit::cli
