#pragma once
// The indirect-light methods, a row each (the table is in runtime/src/gi_methods.cpp): the one
// place that names a method and says what it reads, which settings it takes, what it counts and
// how the bench sweeps it. The planner (which trees and which stage), the renderer (the stage's
// tag, the settings' check), the CLI (--method, the options a method takes, what it prints),
// `vplkit bench gi` (its curves) and the budget (which methods it weighs, their block sizes and
// bias) read the rows; a new method adds its row and its stage.

#include "vplkit/planner.hpp"
#include "vplkit/render_settings.hpp"

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace vplkit {

// Where a method's VPLs come from.
enum class GiVpls {
    none,    // no indirect light: no VPLs
    source,  // the frame's VPL source (`vpl_source`: ir, brsm or smc), shared by every such method
    own,     // it places its own (its own stage, as flc's `flc vpls`); `vpl_source` does not apply
};

// One curve of `vplkit bench gi`: a method as it is, or a variant of it (hybrid-lightcuts).
struct GiBenchCurve {
    std::string_view name;  // the curve's name in the bench's points and report
    // The knobs swept, comma-separated, the quality knob first (spp or navg); `vplkit bench gi`
    // defines each sweep's points.
    std::string_view sweeps;
    void (*variant)(RenderSettings&) = nullptr;  // the variant's settings over the method's, or none
    // Its quality sweep's 8 spp point (4 with --quick) is the bench's equal-time target frame
    // time, unless --target-ms is given: one curve's (the thesis method's).
    bool equal_time_target = false;
};

struct GiMethodInfo {
    GiMethod method;
    std::string_view name;            // `method`'s value: --method's, the plan's, the bench's
    std::string_view summary;         // what it does, a phrase (--method's help)
    std::optional<FrameStage> stage;  // the plan's stage of its indirect light; none: direct light only
    GiVpls vpls = GiVpls::source;
    bool reads_light_tree = false;  // the light tree over the VPLs (FrameStage::light_tree)
    bool reads_sst = false;         // the SST (FrameStage::sst), and so `sst.nu_min`, `sst.sigma_max`
    // Samples the VPL trees: takes `samples_per_pixel` and `glossy_branch`, draws new numbers each
    // `frame`, and counts its traversals (RenderedImage::gi_counts).
    bool samples = false;
    bool blocks = false;             // a cut per `block_size` block
    bool interleaves = false;        // `interleave`: interleaved sampling over sub-blocks
    bool chooses_traversal = false;  // `hybrid_traversal`
    bool mock_cuts = false;          // `mock_cuts`, and counts GiCounts::mock_cut_pixels
    // Every VPL at every pixel: the ground truth, so nothing to denoise; takes
    // `exact_min_distance_fraction`; counts its dropped pixels and its host wall clock.
    bool ground_truth = false;
    std::string_view no_tree;  // why it builds no tree, when it reads none: "exact evaluates every VPL"
    // Throws vplkit::Error naming its first bad setting; null: nothing of its own to check.
    void (*validate)(const RenderSettings&) = nullptr;
    std::span<const GiBenchCurve> bench;  // its curves in `vplkit bench gi`; none: not benched
    // The budget chooser weighs it (BudgetSpace's methods, budget_calibration.hpp): it trades
    // samples for time with a noise the frame shows.
    bool budget = false;
    // The error the budget's model adds beside the noise (budget_error.hpp): the bias left at any
    // spp, 0 for an unbiased method.
    double bias_floor = 0.0;
};

// Every method, in the enum's order (direct light only first).
std::span<const GiMethodInfo> gi_methods();
const GiMethodInfo& gi_method(GiMethod method);
// The method of that name, or null.
const GiMethodInfo* find_gi_method(std::string_view name);

// The names of the methods with `trait` (every method without one) as a list:
// "sst, rtslc or hybrid".
std::string gi_method_names(bool GiMethodInfo::*trait = nullptr);
// The methods with `trait`, in the table's order.
std::vector<GiMethod> gi_methods_with(bool GiMethodInfo::*trait);

// A bench curve and its method.
struct GiBenchCurveOf {
    const GiMethodInfo* method = nullptr;
    const GiBenchCurve* curve = nullptr;
    // The curve's quality knob: its first sweep ("spp", "navg").
    std::string_view quality_sweep() const;
    bool sweeps(std::string_view sweep) const;  // the curve takes this sweep
};
// Every method's bench curves, in the table's order.
std::vector<GiBenchCurveOf> gi_bench_curves();
// The curve of that name, or nothing.
std::optional<GiBenchCurveOf> find_gi_bench_curve(std::string_view name);
// The curves' names as a comma-separated list: "sst, rtslc, hybrid, hybrid-lightcuts, flc".
std::string gi_bench_curve_names();

}  // namespace vplkit
