// What `vplkit bench gi` measured, written out: points.csv and points.json (every point, the
// curves and the Pareto front), the equal-time table with its images and x10 difference
// pictures, the upsampling and mock-cut tables, report.md embedding them (thesis ch. 7's set),
// and the plots scripts/plot.py draws from points.json (error vs frame time with the Pareto
// front, levels per traversal, block size, VPL count vs build time).

#include "bench_gi.hpp"
#include "bench_gi_budget.hpp"
#include "bench_timing.hpp"
#include "plot_script.hpp"
#include "stats_json.hpp"

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

// Points no other point beats in both frame time and RMSE; with a method, among its own points
// only (that method's front: the best it reaches at each frame time).
std::vector<const BenchPoint*> pareto_front(const BenchRun& run, const std::string& method = "") {
    const auto counted = [&](const BenchPoint& p) { return comparable(p) && (method.empty() || p.method == method); };
    std::vector<const BenchPoint*> front;
    for (const BenchPoint& p : run.points) {
        if (!counted(p)) continue;
        bool dominated = false;
        for (const BenchPoint& q : run.points) {
            if (&q == &p || !counted(q)) continue;
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

// "label (frame ms, RMSE); ..." of a front.
std::string front_text(const std::vector<const BenchPoint*>& front) {
    std::string text;
    for (const BenchPoint* p : front) {
        text +=
            (text.empty() ? "" : "; ") + p->label() + " (" + fixed(p->frame_ms, 1) + " ms, " + fixed(p->rmse, 4) + ")";
    }
    return text;
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
        s << csv_field(run.scene) << ',' << csv_field(run.device) << ',' << run.width << ',' << run.height << ','
          << p.method << ',' << p.sweep << ',' << p.spp << ',' << p.block << ',' << p.interleave << ','
          << (p.half ? 1 : 0) << ',' << (p.mock_cuts ? 1 : 0) << ',' << p.vpls << ',' << p.frames << ',' << p.frame_ms
          << ',' << p.frame_min_ms << ',' << p.frame_max_ms << ',' << p.gi_ms << ',' << p.trees_ms << ',' << p.vpls_ms
          << ',' << p.rmse << ',' << p.ssim << ',' << p.relmse << ',' << p.levels_per_traversal << ','
          << p.mock_cut_pixels << ',' << p.dropped_samples << ',' << csv_field(p.image) << ',' << p.flc_navg << '\n';
    }
    return s.str();
}

// points.json: the run, every point, the curves (which sweeps each takes, which traverse the
// trees) and the Pareto front as indices into the points, so that the plots (scripts/plot.py)
// need no knowledge of the method table and ring the front report.md lists.
nlohmann::json points_json(const BenchRun& run) {
    using nlohmann::json;
    json points = json::array();
    for (const BenchPoint& p : run.points) {
        json stages = json::array();
        for (const BenchPoint::StageTime& t : p.stages) {
            stages.push_back({{"name", t.name},
                              {"median_ms", json_number(t.median_ms)},
                              {"min_ms", json_number(t.min_ms)},
                              {"max_ms", json_number(t.max_ms)}});
        }
        points.push_back({{"method", p.method},
                          {"sweep", p.sweep},
                          {"label", p.label()},
                          {"spp", p.spp},
                          {"block", p.block},
                          {"interleave", p.interleave},
                          {"half", p.half},
                          {"mock_cuts", p.mock_cuts},
                          {"denoised", p.denoised},
                          {"vpls", p.vpls},
                          {"frames", p.frames},
                          {"frame_ms", json_number(p.frame_ms)},
                          {"frame_min_ms", json_number(p.frame_min_ms)},
                          {"frame_max_ms", json_number(p.frame_max_ms)},
                          {"gi_ms", json_number(p.gi_ms)},
                          {"trees_ms", json_number(p.trees_ms)},
                          {"vpls_ms", json_number(p.vpls_ms)},
                          {"rmse", json_number(p.rmse)},
                          {"ssim", json_number(p.ssim)},
                          {"relmse", json_number(p.relmse)},
                          {"levels_per_traversal", json_number(p.levels_per_traversal)},
                          {"mock_cut_pixels", p.mock_cut_pixels},
                          {"dropped_samples", p.dropped_samples},
                          {"image", p.image},
                          {"flc_navg", json_number(p.flc_navg)},
                          {"stages", stages}});
    }
    json curve_list = json::array();
    for (const GiBenchCurveOf& c : gi_bench_curves()) {
        json sweeps = json::array();
        std::string_view rest = c.curve->sweeps;
        while (!rest.empty()) {
            const size_t comma = rest.find(',');
            sweeps.push_back(std::string(rest.substr(0, comma)));
            rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
        }
        curve_list.push_back({{"name", std::string(c.curve->name)},
                              {"quality_sweep", std::string(c.quality_sweep())},
                              {"sweeps", sweeps},
                              {"samples", c.method->samples}});
    }
    json front = json::array();
    for (const BenchPoint* p : pareto_front(run)) front.push_back(p - run.points.data());
    json method_fronts = json::object();
    for (const std::string& m : curves()) {
        json indices = json::array();
        for (const BenchPoint* p : pareto_front(run, m)) indices.push_back(p - run.points.data());
        if (!indices.empty()) method_fronts[m] = indices;
    }
    return {{"scene", run.scene},
            {"device", run.device},
            {"width", run.width},
            {"height", run.height},
            {"vpl_source", run.vpl_source},
            {"vpl_budget", run.vpl_budget},
            {"seed", run.seed},
            {"exact_wall_ms", json_number(run.exact_wall_ms)},
            {"exact_cached", run.exact_cached},
            {"relmse_epsilon", json_number(kRelativeMseEpsilon)},
            {"target_ms", json_number(run.target_ms)},
            {"curves", curve_list},
            {"vpl_count_curve", vpl_count_curve()},
            {"pareto_front", front},
            {"method_fronts", method_fronts},
            {"points", points},
            {"budget_note", run.budget_note},
            {"budget_check", budget_check_json(run)}};
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
    write_json_file(folder / "points.json", points_json(run));
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
       << "(forward light cuts, the FLC paper: its own VPLs, one per kept triangle, splatted unshadowed; its points "
          "sweep "
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
       << "![RMSE vs GI time](rmse_vs_gi_time.png)\n\nThe Pareto front by frame time (ringed): "
       << front_text(pareto_front(run)) << ".\n\nEach method's own front (the staircase in its colour):\n\n";
    for (const std::string& m : curves()) {
        const std::vector<const BenchPoint*> front = pareto_front(run, m);
        if (!front.empty()) md << "- " << m << ": " << front_text(front) << "\n";
    }
    md << "\n" << kTableHead;
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
    if (!run.budget_note.empty()) md << budget_check_markdown(run);
    md << "\nEvery point: points.csv, points.json; every frame: images/.\n";
    write_file(folder / "report.md", md.str());
    // Last: the data and the report are on disk whatever the plotting does.
    draw_plots("bench-gi", folder);
}

}  // namespace vplkit::cli
