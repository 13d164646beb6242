#pragma once
// `vplkit bench gi` (bench --scene NAME): what every indirect-light method's accuracy costs.
// cmd_bench_gi.cpp measures the points (ground truth cached on disk, each method's knobs swept,
// several frames per point); bench_gi_report.cpp writes what was measured: CSV, JSON, PNG plots,
// the equal-time table and images, and a Markdown report that embeds them.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace vplkit::cli {

// One measured configuration.
struct BenchPoint {
    std::string method;  // the bench curve's name (the method table's, gi_methods.hpp): "hybrid-lightcuts"
    std::string sweep;   // which knob this point varies: spp, block, resolution, interleave, mock, vpls, navg (flc)
    unsigned spp = 0;
    unsigned block = 0;       // rtslc, hybrid
    unsigned interleave = 1;  // rtslc
    bool half = false;        // GI at half resolution
    bool mock_cuts = true;    // hybrid
    unsigned vpls = 0;        // VPLs placed
    bool denoised = false;    // --denoise svgf, accumulated over the point's frames (static camera)
    float flc_navg = 0;       // flc: N_avg, its quality knob (eq. 1)

    // Times (GPU timestamps), median over the timed frames, and the spread (min, max).
    double frame_ms = 0, frame_min_ms = 0, frame_max_ms = 0;  // every pass of the frame
    double gi_ms = 0;     // the method's sampling passes (with down/upsampling at half resolution)
    double trees_ms = 0;  // keys, sort, leaves, light tree, SST
    double vpls_ms = 0;   // VPL generation (shadow maps, BRSM or light paths)
    unsigned frames = 0;  // timed frames
    struct StageTime {
        std::string name;  // a pass name (passes of one name in a frame summed)
        double median_ms = 0, min_ms = 0, max_ms = 0;
    };
    std::vector<StageTime> stages;  // every stage of the frame, in pass order

    // Error against the ground truth: RMSE and SSIM of the tonemapped frames (sRGB / 255, L = 1),
    // relMSE of the linear radiance (mean (t - r)^2 / (r^2 + eps), eps kRelativeMseEpsilon).
    double rmse = 0, ssim = 0, relmse = 0;
    double levels_per_traversal = 0;
    unsigned mock_cut_pixels = 0;
    unsigned dropped_samples = 0;
    std::string image;          // the frame, relative to the output folder
    std::string label() const;  // e.g. "hybrid 8 spp k8 half"
};

// The budget chooser checked (bench_gi_budget.hpp): for a budget B, what `--budget-ms B` chose,
// that choice measured like a point, and the best measured point within B.
struct BudgetCheckRow {
    double scale = 1;      // the model's times x scale (1: as calibrated; else the drift's correction)
    double fraction = 0;   // of the comparable points' time range: B = min + fraction (max - min)
    double budget_ms = 0;  // B
    std::string chosen;    // "rtslc 64 spp k8 half svgf, 1024 vpls"
    double predicted_ms = 0, predicted_rmse = 0;
    bool over_budget = false;  // the model predicted no configuration within B
    double measured_ms = 0, measured_rmse = 0;
    std::string best;  // the best measured point within B ("" when none is)
    double best_ms = 0, best_rmse = 0;
};

struct BenchRun {
    std::string scene;   // set-up name
    std::string device;  // name and type
    unsigned width = 0, height = 0;
    std::string vpl_source;  // ir, brsm
    unsigned vpl_budget = 0;
    unsigned seed = 0;
    double exact_wall_ms = 0;  // ground truth: host wall clock (0 when it came from the cache)
    bool exact_cached = false;
    std::string exact_image;  // relative to the output folder
    std::vector<BenchPoint> points;
    double target_ms = 0;              // the equal-time target (frame time)
    std::vector<std::string> skipped;  // points the device could not run, with the reason
    std::vector<BudgetCheckRow> budget_check;
    std::string budget_note;  // how the model was made, its time scale on this run; or why no check ran
};

// A tonemapped RGBA8 frame as RGB values in [0, 1] (sRGB codes / 255): what the metrics compare.
std::vector<float> unit_rgb(const std::vector<uint8_t>& rgba);

// Writes points.csv, points.json, the plots, equal-time images with x10 difference pictures and
// report.md into `folder`. `exact_rgba` is the ground truth's tonemapped frame.
void write_bench_report(const std::filesystem::path& folder, const BenchRun& run);

}  // namespace vplkit::cli
