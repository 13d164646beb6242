// `vplkit bench direct --scene NAME`: what direct light's accuracy costs with the flat sampler
// (point and spot lights one by one, emitters from one power CDF) and with the light tree over
// all of them (stochastic lightcuts, direct_light_tree.hpp), one-level and two-level (a bottom tree
// per mesh light under a top tree, the RTSLC paper sec. 3.1), at 1..64 samples per pixel, against
// a converged reference (the flat sampler's mean over many frames: it is unbiased, as the tree
// is). Writes DIR/points.csv, a frame of each (PNG), DIR/report.md with the equal-time comparison
// and two plots (PNG, scripts/plot.py).

#include "bench_options.hpp"
#include "bench_timing.hpp"
#include "camera_flags.hpp"
#include "cli.hpp"
#include "cli_checks.hpp"
#include "commands.hpp"
#include "plot_script.hpp"
#include "scene_warnings.hpp"

#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image_io.hpp"
#include "vplkit/image_metrics.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/renderer.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/scene_setups.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
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

struct DirectPoint {
    DirectSampler sampler = DirectSampler::flat;
    uint32_t spp = 1;
    double direct_ms = 0.0;      // median over the timed frames of the direct-light passes' GPU time
    double relative_rmse = 0.0;  // mean over the timed frames, of the linear direct radiance
};

// The direct-light passes of a frame (not the G-buffer; the tree's one-time build is in the
// untimed first frame).
double direct_ms(const RenderedImage& image) {
    double ms = 0.0;
    for (const PassTiming& t : image.timings) {
        if (stage_owns_pass(FrameStage::direct_light, t) || stage_owns_pass(FrameStage::direct_emissive, t) ||
            stage_owns_pass(FrameStage::direct_tree, t)) {
            if (t.name != "indirect clear") ms += t.gpu_ms;
        }
    }
    return ms;
}

void progress(size_t done, size_t total, const std::string& what) {
    static const bool terminal = isatty(fileno(stderr));
    std::fprintf(stderr, terminal ? "\r[bench direct] %zu/%zu %-40s" : "[bench direct] %zu/%zu %s\n", done, total,
                 what.c_str());
    if (terminal && done == total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
}

// The flat sampler's relative RMSE at `ms`, interpolated log-log between the flat points around
// it; nothing when `ms` lies outside them.
std::optional<double> flat_rmse_at(const std::vector<DirectPoint>& points, double ms) {
    std::vector<const DirectPoint*> flat;
    for (const DirectPoint& p : points) {
        if (p.sampler == DirectSampler::flat) flat.push_back(&p);
    }
    std::sort(flat.begin(), flat.end(), [](auto* a, auto* b) { return a->direct_ms < b->direct_ms; });
    for (size_t i = 0; i + 1 < flat.size(); ++i) {
        const DirectPoint& a = *flat[i];
        const DirectPoint& b = *flat[i + 1];
        if (a.direct_ms <= ms && ms <= b.direct_ms && a.direct_ms > 0 && b.direct_ms > a.direct_ms) {
            const double t = std::log(ms / a.direct_ms) / std::log(b.direct_ms / a.direct_ms);
            return std::exp(std::log(a.relative_rmse) + t * (std::log(b.relative_rmse) - std::log(a.relative_rmse)));
        }
    }
    return std::nullopt;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
    const std::filesystem::path tmp = path.string() + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        if (!out) throw Error(path.string() + ": cannot write");
    }
    std::filesystem::rename(tmp, path);
}

}  // namespace

namespace {

struct BenchDirectOptions : BenchSceneOptions {
    std::optional<uint32_t> reference_frames;
};

const BenchDefaults& direct_defaults() {
    static const BenchDefaults d{"out/bench-direct",
                                 32,
                                 32,
                                 128,
                                 128,
                                 512,
                                 512,
                                 2,
                                 "frames per point (default 3, 2 with --quick; the first is not timed)",
                                 "a smoke test: 32x32, 1 and 4 spp, 2 frames, a 2-frame reference of 16 spp"};
    return d;
}

int run_bench_direct(const BenchDirectOptions& o) {
    if (o.scene.empty()) throw UsageError("bench direct needs --scene NAME");
    check_camera_flags(o.camera_flags);
    const std::string& scene_name = o.scene;
    const bool quick = o.quick;
    const uint32_t frames = o.frames.value_or(quick ? 2 : 3);
    const uint32_t reference_frames = o.reference_frames.value_or(quick ? 2 : 16);
    const bool is_file = names_scene_file(scene_name);
    const std::string out_name = bench_scene_name(scene_name);
    const std::filesystem::path out = bench_out_folder(o, direct_defaults());

    scene::Setup setup;
    scene::Scene scene;
    if (is_file) {
        setup.name = out_name;
        scene = scene::load_gltf(std::filesystem::absolute(scene_name));
    } else {
        setup = scene::load_setups(VPLKIT_SETUPS_FILE).find(scene_name);
        scene = scene::load_setup_scene(setup, {});
    }
    apply_camera_flags(o.camera_flags, scene, scene.bounds.center());
    report_scene_warnings(scene, o.strict);

    auto context = Context::create(o.context);
    const DeviceInfo& device = context->info();
    std::printf("device: %s (%s): %s\n", device.name.c_str(), device.type_name.c_str(), device.reason.c_str());
    RenderSettings base;
    const BenchSize size = bench_frame_size(o, direct_defaults(), device);
    base.width = size.width;
    base.height = size.height;
    Renderer renderer(*context, scene);
    const uint32_t pixels = base.width * base.height;
    std::filesystem::create_directories(out);
    std::printf("scene: %s, %ux%u, %u emissive triangles, %zu punctual lights, %u frames per point\n",
                setup.name.c_str(), base.width, base.height, renderer.emitter_count(), scene.lights.size(), frames);

    const std::vector<uint32_t> spps =
        quick ? std::vector<uint32_t>{1, 4} : std::vector<uint32_t>{1, 2, 4, 8, 16, 32, 64};
    const uint32_t picture_spp = quick ? 4 : 16;  // the frames written as pictures
    const std::vector<DirectSampler> samplers = {DirectSampler::flat, DirectSampler::tree, DirectSampler::tree2};
    const size_t total = reference_frames + samplers.size() * spps.size() * frames;
    size_t done = 0;

    // The reference: the flat sampler's mean over reference_frames frames of 64 samples each.
    std::vector<double> sum(size_t(pixels) * 3, 0.0);
    RenderSettings reference_settings = base;
    reference_settings.direct_sampler = DirectSampler::flat;
    reference_settings.direct_samples = quick ? 16 : 256;
    for (uint32_t f = 0; f < reference_frames; ++f) {
        reference_settings.seed = 100000 + f;
        const RenderedImage image = renderer.render(scene.camera(), reference_settings);
        for (size_t i = 0; i < sum.size(); ++i) sum[i] += image.direct[i];
        progress(++done, total, "reference");
    }
    std::vector<float> reference(sum.size());
    for (size_t i = 0; i < sum.size(); ++i) reference[i] = float(sum[i] / reference_frames);

    std::vector<DirectPoint> points;
    for (DirectSampler sampler : samplers) {
        for (uint32_t spp : spps) {
            RenderSettings settings = base;
            settings.direct_sampler = sampler;
            settings.direct_samples = spp;
            DirectPoint point;
            point.sampler = sampler;
            point.spp = spp;
            std::vector<double> times, errors;
            for (uint32_t f = 0; f < frames; ++f) {
                settings.seed = f;
                settings.frame = f;
                const RenderedImage image = renderer.render(scene.camera(), settings);
                if (f > 0) times.push_back(direct_ms(image));
                errors.push_back(relative_rmse(image.direct, reference));
                if (spp == picture_spp && f == 0) {
                    write_png(out / (std::string(direct_sampler_name(sampler)) + "_spp.png"), image.width, image.height,
                              image.rgba8);
                }
                progress(++done, total, std::string(direct_sampler_name(sampler)) + " " + std::to_string(spp) + " spp");
            }
            point.direct_ms = median_of(times);
            double e = 0.0;
            for (double x : errors) e += x;
            point.relative_rmse = e / errors.size();
            points.push_back(point);
            std::printf("%-5s %3u spp  %9.2f ms  relative RMSE %.4f\n", direct_sampler_name(sampler), spp,
                        point.direct_ms, point.relative_rmse);
        }
    }

    // points.csv
    std::ostringstream csv;
    csv << "scene,device,width,height,sampler,spp,direct_ms,relative_rmse\n";
    for (const DirectPoint& p : points) {
        csv << csv_field(setup.name) << ',' << csv_field(device.name) << ',' << base.width << ',' << base.height << ','
            << direct_sampler_name(p.sampler) << ',' << p.spp << ',' << p.direct_ms << ',' << p.relative_rmse << '\n';
    }
    write_text(out / "points.csv", csv.str());

    // report.md
    std::ostringstream md;
    md << "# Direct light: flat sampler vs one- and two-level light trees (" << setup.name << ")\n\n"
       << "Device: " << device.name << " (" << device.type_name << "). " << base.width << "x" << base.height << ", "
       << renderer.emitter_count() << " emissive triangles, " << scene.lights.size() << " punctual lights. "
       << "Reference: the flat sampler's mean over " << reference_frames << " frames of "
       << reference_settings.direct_samples << " samples per pixel. Error: relative RMSE of the linear direct "
       << "radiance (RMSE over all pixels and channels / the reference's mean), mean over " << frames
       << " frames; time: median GPU time of the direct-light passes over frames 2.." << frames
       << " (the light tree's one-time build is not in it). Command: `vplkit bench direct --scene " << scene_name
       << (quick ? " --quick" : "") << "`.\n\n"
       << "![relative RMSE vs time](rmse_vs_time.png)\n\n![relative RMSE vs spp](rmse_vs_spp.png)\n\n"
       << "| sampler | spp | direct ms | relative RMSE | flat's RMSE at the same time | tree(2) / flat |\n"
       << "| --- | --- | --- | --- | --- | --- |\n";
    char line[256];
    for (const DirectPoint& p : points) {
        std::string equal = "", ratio = "";
        if (p.sampler != DirectSampler::flat) {
            if (auto flat = flat_rmse_at(points, p.direct_ms)) {
                std::snprintf(line, sizeof line, "%.4f", *flat);
                equal = line;
                std::snprintf(line, sizeof line, "%.2f", p.relative_rmse / *flat);
                ratio = line;
            } else {
                equal = "outside the flat points' times";
            }
        }
        std::snprintf(line, sizeof line, "| %s | %u | %.2f | %.4f | %s | %s |\n", direct_sampler_name(p.sampler), p.spp,
                      p.direct_ms, p.relative_rmse, equal.c_str(), ratio.c_str());
        md << line;
    }
    md << "\n"
       << picture_spp
       << " samples per pixel, flat, tree and tree2: ![flat](flat_spp.png) ![tree](tree_spp.png) "
          "![tree2](tree2_spp.png)\n";
    write_text(out / "report.md", md.str());
    std::printf("wrote %s\n", (out / "report.md").string().c_str());
    draw_plots("bench-direct", out);  // rmse_vs_time.png, rmse_vs_spp.png from points.csv
    return 0;
}

}  // namespace

void add_bench_direct(CLI::App& bench, Runners& runners) {
    CLI::App* direct = add_command(
        bench, "direct", "the flat and the tree direct-light samplers on a scene, RMSE against time (--scene NAME)",
        "Direct light's accuracy against its cost: the flat sampler (point and spot lights one by one, emitters "
        "drawn by power) and the light tree over all of them (stochastic lightcuts), each at 1..64 samples per "
        "pixel, against a reference (the flat sampler's mean over R frames of 256 samples). Every point: F frames; "
        "error = relative RMSE of the linear direct radiance, time = median GPU time of the direct-light passes "
        "over frames 2..F. Writes DIR/points.csv, plots, a frame of each sampler and DIR/report.md with the tree / "
        "flat RMSE ratio at equal time.");
    auto o = std::make_shared<BenchDirectOptions>();
    add_bench_scene_options(*direct, *o, "required: a standard set-up (scenes/setups.txt) or a .gltf/.glb file");
    add_bench_output_options(*direct, *o, direct_defaults());
    whole_number(direct->add_option_function<uint32_t>(
                     "--reference-frames", [o](uint32_t v) { o->reference_frames = v; },
                     "frames averaged for the reference (default 16, 2 with --quick)"),
                 "R", 1, 100000);
    runners.push_back({direct, [o] { return run_bench_direct(*o); }});
}

}  // namespace vplkit::cli
