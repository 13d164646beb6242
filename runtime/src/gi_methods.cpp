// The method table: every indirect-light method, a row each (gi_methods.hpp says who reads it).

#include "vplkit/gi_methods.hpp"

#include "gi_stage_options.hpp"
#include "vplkit/budget_error.hpp"
#include "vplkit/error.hpp"

#include <iterator>
#include <string>
#include <vector>

namespace vplkit {

namespace {

// Any positive similarity distance: the real one depends on the scene, and every positive one is valid.
void validate_sst(const RenderSettings& settings) {
    stages::validate(gi_stage_options(settings, 1.0f).sst);
}
void validate_rtslc(const RenderSettings& settings) {
    stages::validate(gi_stage_options(settings, 1.0f).rtslc);
}
void validate_hybrid(const RenderSettings& settings) {
    stages::validate(gi_stage_options(settings, 1.0f).hybrid);
}

// The thesis' comparison protocol (the thesis sec. 7.1): hybrid's cuts and blending, rtslc's traversal.
void lightcuts_traversal(RenderSettings& settings) {
    settings.hybrid_traversal = stages::HybridTraversal::lightcuts;
}

constexpr GiBenchCurve kSstCurves[] = {{"sst", "spp,denoise"}};
constexpr GiBenchCurve kRtslcCurves[] = {{"rtslc", "spp,block,resolution,interleave,denoise"}};
// The VPL-count sweep times the trees' build; hybrid's curve carries it for every method.
constexpr GiBenchCurve kHybridCurves[] = {
    {.name = "hybrid", .sweeps = "spp,block,resolution,mock,denoise,vpls", .equal_time_target = true},
    {.name = "hybrid-lightcuts", .sweeps = "spp", .variant = lightcuts_traversal}};
constexpr GiBenchCurve kFlcCurves[] = {{"flc", "navg"}};

// In GiMethod's order (gi_method indexes it).
constexpr GiMethodInfo kGiMethods[] = {
    {
        .method = GiMethod::none,
        .name = "direct",
        .summary = "direct light only",
        .stage = std::nullopt,
        .vpls = GiVpls::none,
        .no_tree = "direct light only",
    },
    {
        .method = GiMethod::exact,
        .name = "exact",
        .summary = "every VPL at every pixel with a shadow ray (the ground truth)",
        .stage = FrameStage::gi_exact,
        .ground_truth = true,
        .no_tree = "exact evaluates every VPL",
    },
    {
        .method = GiMethod::sst,
        .name = "sst",
        .summary = "stochastic substitute tree traversals from the root",
        .stage = FrameStage::gi_sst,
        .reads_sst = true,
        .samples = true,
        .validate = validate_sst,
        .bench = kSstCurves,
        .budget = true,
        .bias_floor = kSstBiasFloor,
    },
    {
        .method = GiMethod::rtslc,
        .name = "rtslc",
        .summary = "real-time stochastic lightcuts (a cut per block, traversals to leaves)",
        .stage = FrameStage::gi_rtslc,
        .reads_light_tree = true,
        .samples = true,
        .blocks = true,
        .interleaves = true,
        .validate = validate_rtslc,
        .bench = kRtslcCurves,
        .budget = true,
    },
    {
        .method = GiMethod::hybrid,
        .name = "hybrid",
        .summary = "the thesis method (shallow SST cuts per block, blended between blocks, traversals that stop "
                   "at flat clusters)",
        .stage = FrameStage::gi_hybrid,
        .reads_sst = true,
        .samples = true,
        .blocks = true,
        .chooses_traversal = true,
        .mock_cuts = true,
        .validate = validate_hybrid,
        .bench = kHybridCurves,
        .budget = true,
        .bias_floor = kHybridBiasFloor,
    },
    {
        .method = GiMethod::flc,
        .name = "flc",
        .summary = "forward light cuts (the FLC paper): a VPL per kept triangle (stochastic decimation, stratified), "
                   "splatted over its support; unshadowed, one bounce",
        .stage = FrameStage::gi_flc,
        .vpls = GiVpls::own,
        .no_tree = "flc splats every kept VPL over its bounded support",
        .validate = validate_flc_settings,
        .bench = kFlcCurves,
    },
};

constexpr bool in_enum_order() {
    for (size_t i = 0; i < std::size(kGiMethods); ++i) {
        if (size_t(kGiMethods[i].method) != i) return false;
    }
    return true;
}
static_assert(in_enum_order(), "kGiMethods lists the methods in GiMethod's order");

// "a, b or c".
std::string listed(const std::vector<std::string_view>& names) {
    std::string out;
    for (size_t i = 0; i < names.size(); ++i) {
        if (i > 0) out += i + 1 == names.size() ? " or " : ", ";
        out += names[i];
    }
    return out;
}

}  // namespace

std::span<const GiMethodInfo> gi_methods() {
    return kGiMethods;
}

const GiMethodInfo& gi_method(GiMethod method) {
    const size_t i = size_t(method);
    if (i >= std::size(kGiMethods)) throw Error("render: unknown indirect-light method " + std::to_string(i));
    return kGiMethods[i];
}

const GiMethodInfo* find_gi_method(std::string_view name) {
    for (const GiMethodInfo& m : kGiMethods) {
        if (m.name == name) return &m;
    }
    return nullptr;
}

const char* gi_method_name(GiMethod method) {
    return gi_method(method).name.data();  // every name is a string literal
}

std::string gi_method_names(bool GiMethodInfo::*trait) {
    std::vector<std::string_view> names;
    for (const GiMethodInfo& m : kGiMethods) {
        if (!trait || m.*trait) names.push_back(m.name);
    }
    return listed(names);
}

std::vector<GiMethod> gi_methods_with(bool GiMethodInfo::*trait) {
    std::vector<GiMethod> out;
    for (const GiMethodInfo& m : kGiMethods) {
        if (m.*trait) out.push_back(m.method);
    }
    return out;
}

std::string_view GiBenchCurveOf::quality_sweep() const {
    return curve->sweeps.substr(0, curve->sweeps.find(','));
}

bool GiBenchCurveOf::sweeps(std::string_view sweep) const {
    std::string_view rest = curve->sweeps;
    while (!rest.empty()) {
        const size_t comma = rest.find(',');
        if (rest.substr(0, comma) == sweep) return true;
        rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    }
    return false;
}

std::vector<GiBenchCurveOf> gi_bench_curves() {
    std::vector<GiBenchCurveOf> out;
    for (const GiMethodInfo& m : kGiMethods) {
        for (const GiBenchCurve& c : m.bench) out.push_back({&m, &c});
    }
    return out;
}

std::optional<GiBenchCurveOf> find_gi_bench_curve(std::string_view name) {
    for (const GiBenchCurveOf& c : gi_bench_curves()) {
        if (c.curve->name == name) return c;
    }
    return std::nullopt;
}

std::string gi_bench_curve_names() {
    std::string out;
    for (const GiBenchCurveOf& c : gi_bench_curves()) out += (out.empty() ? "" : ", ") + std::string(c.curve->name);
    return out;
}

}  // namespace vplkit
