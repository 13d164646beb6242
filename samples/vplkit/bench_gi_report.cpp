// What `vplkit bench gi` measured, written out: points.csv and points.json (every point), the
// plots (error vs frame time with the Pareto front, levels per traversal, block size, VPL count
// vs build time), the equal-time table with its images and x10 difference pictures, the
// upsampling and mock-cut tables, and report.md embedding them (thesis ch. 7's set).

#include "bench_gi.hpp"
#include "bench_timing.hpp"
#include "plot.hpp"

#include "vplkit/error.hpp"
#include "vplkit/gi_methods.hpp"
#include "vplkit/image_io.hpp"
#include "vplkit/image_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace vplkit::cli {

namespace {

// The bench's curves (the method table's, gi_methods.hpp) that take `sweep`; every curve without one.
std::vector<std::string> curves(std::string_view sweep = {}) {
    std::vector<std::string> out;
    for (const GiBenchCurveOf& c : gi_bench_curves()) {
        if (sweep.empty() || c.sweeps(sweep)) out.emplace_back(c.curve->name);
    }
    return out;
}

// The curve that sweeps the VPL count (the trees' build time), or "".
std::string vpl_count_curve() {
    const std::vector<std::string> with = curves("vpls");
    return with.empty() ? "" : with.front();
}

// The sweep of a curve's quality knob: samples per pixel, or flc's N_avg.
std::string quality_sweep(const std::string& curve) {
    return std::string(find_gi_bench_curve(curve)->quality_sweep());
}

std::string fixed(double v, int digits) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, v);
    return text;
}

std::string json_string(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

std::vector<const BenchPoint*> select(const BenchRun& run, const std::string& method, const std::string& sweep) {
    std::vector<const BenchPoint*> out;
    for (const BenchPoint& p : run.points) {
        if (p.method == method && p.sweep == sweep) out.push_back(&p);
    }
    return out;
}

// The spp sweep's point at `spp`, or null.
const BenchPoint* base_point(const BenchRun& run, const std::string& method, unsigned spp) {
    for (const BenchPoint* p : select(run, method, "spp")) {
        if (p->spp == spp) return p;
    }
    return nullptr;
}

// The points of the accuracy-vs-time comparison: every point at the run's VPL budget.
bool comparable(const BenchPoint& p) {
    return p.sweep != "vpls";
}

// Points no other point beats in both frame time and RMSE.
std::vector<const BenchPoint*> pareto_front(const BenchRun& run) {
    std::vector<const BenchPoint*> front;
    for (const BenchPoint& p : run.points) {
        if (!comparable(p)) continue;
        bool dominated = false;
        for (const BenchPoint& q : run.points) {
            if (&q == &p || !comparable(q)) continue;
            if (q.frame_ms <= p.frame_ms && q.rmse <= p.rmse && (q.frame_ms < p.frame_ms || q.rmse < p.rmse)) {
                dominated = true;
                break;
            }
        }
        if (!dominated) front.push_back(&p);
    }
    std::sort(front.begin(), front.end(),
              [](const BenchPoint* a, const BenchPoint* b) { return a->frame_ms < b->frame_ms; });
    return front;
}

void write_file(const std::filesystem::path& path, const std::string& text) {
    write_csv(path.string(), text);
}

std::string csv(const BenchRun& run) {
    std::ostringstream s;
    s << "scene,device,width,height,method,sweep,spp,block,interleave,half,mock_cuts,vpls,frames,frame_ms,frame_min_ms,"
         "frame_max_ms,gi_ms,trees_ms,vpls_ms,rmse,ssim,relmse,levels_per_traversal,mock_cut_pixels,dropped_samples,"
         "image,flc_navg\n";
    s.precision(9);
    for (const BenchPoint& p : run.points) {
        s << run.scene << ",\"" << run.device << "\"," << run.width << ',' << run.height << ',' << p.method << ','
          << p.sweep << ',' << p.spp << ',' << p.block << ',' << p.interleave << ',' << (p.half ? 1 : 0) << ','
          << (p.mock_cuts ? 1 : 0) << ',' << p.vpls << ',' << p.frames << ',' << p.frame_ms << ',' << p.frame_min_ms
          << ',' << p.frame_max_ms << ',' << p.gi_ms << ',' << p.trees_ms << ',' << p.vpls_ms << ',' << p.rmse << ','
          << p.ssim << ',' << p.relmse << ',' << p.levels_per_traversal << ',' << p.mock_cut_pixels << ','
          << p.dropped_samples << ',' << p.image << ',' << p.flc_navg << '\n';
    }
    return s.str();
}

std::string json(const BenchRun& run) {
    std::ostringstream s;
    s.precision(9);
    s << "{\n  \"scene\": " << json_string(run.scene) << ",\n  \"device\": " << json_string(run.device)
      << ",\n  \"width\": " << run.width << ",\n  \"height\": " << run.height
      << ",\n  \"vpl_source\": " << json_string(run.vpl_source) << ",\n  \"vpl_budget\": " << run.vpl_budget
      << ",\n  \"seed\": " << run.seed << ",\n  \"exact_wall_ms\": " << run.exact_wall_ms
      << ",\n  \"exact_cached\": " << (run.exact_cached ? "true" : "false")
      << ",\n  \"relmse_epsilon\": " << kRelativeMseEpsilon << ",\n  \"target_ms\": " << run.target_ms
      << ",\n  \"points\": [\n";
    for (size_t i = 0; i < run.points.size(); ++i) {
        const BenchPoint& p = run.points[i];
        s << "    {\"method\": " << json_string(p.method) << ", \"sweep\": " << json_string(p.sweep)
          << ", \"spp\": " << p.spp << ", \"block\": " << p.block << ", \"interleave\": " << p.interleave
          << ", \"half\": " << (p.half ? "true" : "false") << ", \"mock_cuts\": " << (p.mock_cuts ? "true" : "false")
          << ", \"vpls\": " << p.vpls << ", \"frames\": " << p.frames << ", \"frame_ms\": " << p.frame_ms
          << ", \"frame_min_ms\": " << p.frame_min_ms << ", \"frame_max_ms\": " << p.frame_max_ms
          << ", \"gi_ms\": " << p.gi_ms << ", \"trees_ms\": " << p.trees_ms << ", \"vpls_ms\": " << p.vpls_ms
          << ", \"rmse\": " << p.rmse << ", \"ssim\": " << p.ssim << ", \"relmse\": " << p.relmse
          << ", \"levels_per_traversal\": " << p.levels_per_traversal << ", \"mock_cut_pixels\": " << p.mock_cut_pixels
          << ", \"dropped_samples\": " << p.dropped_samples << ", \"image\": " << json_string(p.image)
          << ", \"flc_navg\": " << p.flc_navg << ", \"stages\": [";
        for (size_t k = 0; k < p.stages.size(); ++k) {
            const BenchPoint::StageTime& t = p.stages[k];
            s << (k ? ", " : "") << "{\"name\": " << json_string(t.name) << ", \"median_ms\": " << t.median_ms
              << ", \"min_ms\": " << t.min_ms << ", \"max_ms\": " << t.max_ms << "}";
        }
        s << "]}" << (i + 1 < run.points.size() ? ",\n" : "\n");
    }
    s << "  ]\n}\n";
    return s.str();
}

// Each method's point closest to the target frame time (among its spp sweep and its half-res,
// block and interleave variants: every comparable point of that method).
std::vector<const BenchPoint*> equal_time(const BenchRun& run) {
    std::vector<const BenchPoint*> out;
    for (const std::string& m : curves()) {
        const BenchPoint* best = nullptr;
        for (const BenchPoint& p : run.points) {
            if (p.method != m || !comparable(p)) continue;
            if (!best || std::abs(p.frame_ms - run.target_ms) < std::abs(best->frame_ms - run.target_ms)) best = &p;
        }
        if (best) out.push_back(best);
    }
    return out;
}

void write_plots(const std::filesystem::path& folder, const BenchRun& run) {
    // Thesis Fig. 7.3: RMSE vs time, every spp and half-resolution point, the Pareto front (of
    // all comparable points, by frame time) ringed. Once against the frame time, once against
    // the GI and tree time alone: the part that differs between methods (the VPLs are the same).
    for (bool gi_only : {false, true}) {
        PlotSpec plot;
        plot.title = run.scene + ": RMSE vs " + (gi_only ? "GI + tree time" : "frame time") + " (" +
                     std::to_string(run.width) + "x" + std::to_string(run.height) + ")";
        plot.x_label = gi_only ? "GI + trees (ms, GPU)" : "frame time (ms, GPU)";
        plot.y_label = "RMSE (tonemapped)";
        plot.log_x = true;
        plot.log_y = true;
        if (!gi_only) plot.highlight_label = "Pareto front";
        const auto front = pareto_front(run);
        for (const std::string& m : curves()) {
            for (const std::string sweep : {"quality", "resolution", "denoise"}) {
                Series series;
                series.name = m + (sweep == "resolution" ? " (half res)" : sweep == "denoise" ? " (svgf)" : "");
                for (const BenchPoint* p : select(run, m, sweep == "quality" ? quality_sweep(m) : sweep)) {
                    series.x.push_back(gi_only ? p->gi_ms + p->trees_ms : p->frame_ms);
                    series.y.push_back(p->rmse);
                    if (!gi_only && std::find(front.begin(), front.end(), p) != front.end()) {
                        plot.highlight.push_back({plot.series.size(), series.x.size() - 1});
                    }
                }
                if (!series.x.empty()) plot.series.push_back(series);
            }
        }
        write_plot_png(folder / (gi_only ? "rmse_vs_gi_time.png" : "rmse_vs_time.png"), plot);
    }
    // Fig. 7.2: tree levels per traversal vs samples per pixel.
    {
        PlotSpec plot;
        plot.title = run.scene + ": tree levels per traversal";
        plot.x_label = "samples per pixel";
        plot.y_label = "levels per traversal";
        plot.log_x = true;
        for (const std::string& m : curves()) {
            if (!find_gi_bench_curve(m)->method->samples) continue;  // no tree traversals
            Series series;
            series.name = m;
            for (const BenchPoint* p : select(run, m, "spp")) {
                series.x.push_back(p->spp);
                series.y.push_back(p->levels_per_traversal);
            }
            plot.series.push_back(series);
        }
        write_plot_png(folder / "levels.png", plot);
    }
    // Fig. 7.5: block size vs RMSE and vs GI time (8 spp).
    for (bool time : {false, true}) {
        PlotSpec plot;
        plot.title = run.scene + (time ? ": cut block size vs GI time (8 spp)" : ": cut block size vs RMSE (8 spp)");
        plot.x_label = "block size k (pixels)";
        plot.y_label = time ? "GI time (ms, GPU)" : "RMSE (tonemapped)";
        plot.log_x = true;
        for (const std::string& m : curves("block")) {
            std::vector<const BenchPoint*> points = select(run, m, "block");
            if (const BenchPoint* p = base_point(run, m, 8)) points.push_back(p);
            std::sort(points.begin(), points.end(),
                      [](const BenchPoint* a, const BenchPoint* b) { return a->block < b->block; });
            Series series;
            series.name = m;
            for (const BenchPoint* p : points) {
                series.x.push_back(p->block);
                series.y.push_back(time ? p->gi_ms : p->rmse);
            }
            plot.series.push_back(series);
        }
        write_plot_png(folder / (time ? "block_size_time.png" : "block_size_rmse.png"), plot);
    }
    // VPL count vs build time (hybrid, 8 spp): VPL generation and the trees.
    {
        PlotSpec plot;
        plot.title = run.scene + ": VPL count vs build time";
        plot.x_label = "VPLs";
        plot.y_label = "GPU time (ms)";
        plot.log_x = true;
        plot.log_y = true;
        const std::string m = vpl_count_curve();
        std::vector<const BenchPoint*> points = select(run, m, "vpls");
        if (const BenchPoint* p = base_point(run, m, 8)) points.push_back(p);
        std::sort(points.begin(), points.end(),
                  [](const BenchPoint* a, const BenchPoint* b) { return a->vpls < b->vpls; });
        Series trees{"trees (keys, sort, leaves, light tree, SST)"}, vpls{"VPL generation"}, gi{m + " GI, 8 spp"};
        for (const BenchPoint* p : points) {
            for (Series* s : {&trees, &vpls, &gi}) s->x.push_back(p->vpls);
            trees.y.push_back(p->trees_ms);
            vpls.y.push_back(p->vpls_ms);
            gi.y.push_back(p->gi_ms);
        }
        plot.series = {trees, vpls, gi};
        write_plot_png(folder / "vpl_count_build_time.png", plot);
    }
}

// The equal-time images: each method's frame and |frame - exact| x 10.
void write_equal_time_images(const std::filesystem::path& folder, const BenchRun& run,
                             const std::vector<const BenchPoint*>& points) {
    const std::vector<float> exact_rgb = unit_rgb(read_png(folder / run.exact_image).rgba);
    for (const BenchPoint* p : points) {
        const PngImage image = read_png(folder / p->image);
        const auto diff = difference_image_rgba8(unit_rgb(image.rgba), exact_rgb, image.width, image.height, 10.0f);
        write_png(folder / ("images/equal_time_" + p->method + "_diff.png"), image.width, image.height, diff);
    }
}

std::string row(const BenchPoint& p) {
    return "| " + p.label() + " | " + fixed(p.frame_ms, 1) + " (" + fixed(p.frame_min_ms, 1) + "-" +
           fixed(p.frame_max_ms, 1) + ") | " + fixed(p.gi_ms, 1) + " | " + fixed(p.rmse, 4) + " | " + fixed(p.ssim, 4) +
           " | " + fixed(p.relmse, 4) + " | " + fixed(p.levels_per_traversal, 2) + " |\n";
}

const char* const kTableHead =
    "| point | frame ms (min-max) | GI ms | RMSE | SSIM | relMSE | levels |\n| --- | --- | --- | --- | --- | --- | --- "
    "|\n";

}  // namespace

void write_bench_report(const std::filesystem::path& folder, const BenchRun& run) {
    for (const BenchPoint& p : run.points) {
        for (double v : {p.frame_ms, p.gi_ms, p.rmse, p.ssim, p.relmse, p.levels_per_traversal}) {
            if (!std::isfinite(v)) throw Error("bench: a non-finite number at " + p.label() + ": no report written");
        }
    }
    write_file(folder / "points.csv", csv(run));
    write_file(folder / "points.json", json(run));
    write_plots(folder, run);
    const auto same_time = equal_time(run);
    write_equal_time_images(folder, run, same_time);

    std::ostringstream md;
    md << "# vplkit bench: " << run.scene << "\n\n"
       << "Device: " << run.device << ". Image " << run.width << "x" << run.height << ", " << run.vpl_source
       << " VPLs (budget " << run.vpl_budget << "), seed " << run.seed << ". Ground truth: `exact`, every VPL at every "
       << "pixel with a shadow ray"
       << (run.exact_cached ? " (from the cache)" : ", " + fixed(run.exact_wall_ms / 1000.0, 1) + " s")
       << ". Times are GPU timestamps, the median of the timed frames (min-max in brackets); RMSE and SSIM "
       << "(11x11 Gaussian windows, L = 1) are of the tonemapped frames (sRGB / 255), relMSE of the linear radiance "
       << "(epsilon " << kRelativeMseEpsilon << ").\n\n"
       << "Methods: `sst` (root traversals of the substitute tree), `rtslc` (standalone stochastic lightcuts: "
       << "its own cuts per block, traversals to leaves), `hybrid` (the thesis' blended shallow cuts and early-stop "
       << "substitute traversals), `hybrid-lightcuts` (hybrid's cuts and blending with rtslc's traversal to a "
       << "leaf: the thesis' sec. 7.1 protocol, where rtslc and hybrid differ only in the traversal), `flc` "
       << "(forward light cuts, seed 002: its own VPLs, one per kept triangle, splatted unshadowed; its points sweep "
       << "N_avg, the VPLs per point).\n\n";

    md << "## Equal time (thesis Fig. 7.1)\n\nEach method at the point whose frame time is closest to "
       << fixed(run.target_ms, 1) << " ms.\n\n"
       << kTableHead;
    for (const BenchPoint* p : same_time) md << row(*p);
    md << "\n| exact | ";
    for (const BenchPoint* p : same_time) md << p->method << " | " << p->method << " x10 difference | ";
    md << "\n| --- |";
    for (size_t i = 0; i < same_time.size(); ++i) md << " --- | --- |";
    md << "\n| ![exact](" << run.exact_image << ") | ";
    for (const BenchPoint* p : same_time) {
        md << "![" << p->label() << "](" << p->image << ") | ![difference](images/equal_time_" << p->method
           << "_diff.png) | ";
    }
    md << "\n\nPer-stage GPU time of these points (ms, median of the timed frames, min-max):\n\n| stage |";
    for (const BenchPoint* p : same_time) md << " " << p->label() << " |";
    md << "\n| --- |";
    for (size_t i = 0; i < same_time.size(); ++i) md << " --- |";
    std::vector<std::string> stage_names;
    for (const BenchPoint* p : same_time) {
        for (const auto& t : p->stages) {
            if (std::find(stage_names.begin(), stage_names.end(), t.name) == stage_names.end())
                stage_names.push_back(t.name);
        }
    }
    for (const std::string& name : stage_names) {
        md << "\n| " << name << " |";
        for (const BenchPoint* p : same_time) {
            const auto it =
                std::find_if(p->stages.begin(), p->stages.end(), [&](const auto& t) { return t.name == name; });
            md << " "
               << (it == p->stages.end()
                       ? std::string("-")
                       : fixed(it->median_ms, 2) + " (" + fixed(it->min_ms, 2) + "-" + fixed(it->max_ms, 2) + ")")
               << " |";
        }
    }
    md << "\n\n## RMSE vs frame time (Fig. 7.3)\n\n![RMSE vs frame time](rmse_vs_time.png)\n\n"
       << "![RMSE vs GI time](rmse_vs_gi_time.png)\n\nThe Pareto front by frame time (ringed): ";
    for (const BenchPoint* p : pareto_front(run))
        md << p->label() << " (" << fixed(p->frame_ms, 1) << " ms, " << fixed(p->rmse, 4) << "); ";
    md << "\n\n" << kTableHead;
    for (const std::string& m : curves()) {
        for (const BenchPoint* p : select(run, m, quality_sweep(m))) md << row(*p);
    }
    md << "\n## Tree levels per traversal (Fig. 7.2)\n\n![levels](levels.png)\n\n"
       << "## Cut block size (Fig. 7.5)\n\n![block size vs RMSE](block_size_rmse.png) ![block size vs "
          "time](block_size_time.png)\n\n"
       << kTableHead;
    for (const std::string& m : curves("block")) {
        for (const BenchPoint* p : select(run, m, "block")) md << row(*p);
    }
    md << "\n## Mock cuts (ch. 7.3)\n\nHybrid with the mock cut where no neighbouring block is alike, against root "
       << "traversals there instead (mock-cut pixels: where no block was alike).\n\n"
       << "| spp | mock cuts: RMSE | frame ms | root traversals: RMSE | frame ms | pixels |\n| --- | --- | --- | --- | "
          "--- | --- |\n";
    for (const std::string& m : curves("mock")) {
        for (const BenchPoint* p : select(run, m, "mock")) {
            if (const BenchPoint* with = base_point(run, m, p->spp)) {
                md << "| " << p->spp << " | " << fixed(with->rmse, 4) << " | " << fixed(with->frame_ms, 1) << " | "
                   << fixed(p->rmse, 4) << " | " << fixed(p->frame_ms, 1) << " | " << with->mock_cut_pixels << " |\n";
            }
        }
    }
    md << "\n## Upsampling (table 7.2)\n\nGI at full resolution against half resolution with joint bilateral "
          "upsampling.\n\n"
       << "| method | spp | full: RMSE | GI ms | half: RMSE | GI ms |\n| --- | --- | --- | --- | --- | --- |\n";
    for (const std::string& m : curves("resolution")) {
        for (const BenchPoint* p : select(run, m, "resolution")) {
            if (const BenchPoint* full = base_point(run, m, p->spp)) {
                md << "| " << m << " | " << p->spp << " | " << fixed(full->rmse, 4) << " | " << fixed(full->gi_ms, 1)
                   << " | " << fixed(p->rmse, 4) << " | " << fixed(p->gi_ms, 1) << " |\n";
            }
        }
    }
    md << "\n## Denoised (svgf)\n\nEach point's frames accumulated on the static camera and filtered "
          "(`--denoise svgf`); the RMSE is the last frame's, the frame time includes the filter's passes.\n\n"
       << kTableHead;
    for (const std::string& m : curves()) {
        for (const BenchPoint* p : select(run, m, "denoise")) md << row(*p);
    }
    md << "\n## Interleaved sampling (rtslc, 2 x 2)\n\n" << kTableHead;
    for (const std::string& m : curves("interleave")) {
        for (const BenchPoint* p : select(run, m, "interleave")) md << row(*p);
    }
    md << "\n## VPL count vs build time\n\n![VPL count vs build time](vpl_count_build_time.png)\n\n"
       << "| VPLs | VPL generation ms | trees ms | " << vpl_count_curve()
       << " GI ms (8 spp) |\n| --- | --- | --- | --- |\n";
    std::vector<const BenchPoint*> counts = select(run, vpl_count_curve(), "vpls");
    if (const BenchPoint* p = base_point(run, vpl_count_curve(), 8)) counts.push_back(p);
    std::sort(counts.begin(), counts.end(), [](const BenchPoint* a, const BenchPoint* b) { return a->vpls < b->vpls; });
    for (const BenchPoint* p : counts) {
        md << "| " << p->vpls << " | " << fixed(p->vpls_ms, 1) << " | " << fixed(p->trees_ms, 1) << " | "
           << fixed(p->gi_ms, 1) << " |\n";
    }
    if (!run.skipped.empty()) {
        md << "\n## Skipped points\n\n";
        for (const std::string& s : run.skipped) md << "- " << s << "\n";
    }
    md << "\nEvery point: points.csv, points.json; every frame: images/.\n";
    write_file(folder / "report.md", md.str());
}

}  // namespace vplkit::cli
