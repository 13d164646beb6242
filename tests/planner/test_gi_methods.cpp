// The method table (runtime/include/vplkit/gi_methods.hpp) against what reads it: names that find
// their rows, a plan that runs each method's own stage and exactly the trees its row reads, a
// settings check that looks at the chosen method's options only, and bench curves that name
// their methods once.

#include "vplkit/gi_methods.hpp"

#include "vplkit/error.hpp"
#include "vplkit/planner.hpp"
#include "vplkit/scene.hpp"

#include <doctest/doctest.h>

#include <set>
#include <string>

#ifndef VPLKIT_SOURCE_DIR
#error "VPLKIT_SOURCE_DIR must be defined by the build"
#endif

namespace {

using vplkit::FrameStage;
using vplkit::GiMethod;
using vplkit::GiMethodInfo;
using vplkit::RenderSettings;

constexpr const char* kCornellPoint = VPLKIT_SOURCE_DIR "/scenes/cornell_point/cornell_point.gltf";

}  // namespace

TEST_CASE("gi methods: every row is found by its method and its name, in the enum's order") {
    std::set<std::string> names;
    size_t index = 0;
    for (const GiMethodInfo& m : vplkit::gi_methods()) {
        CAPTURE(m.name);
        CHECK(size_t(m.method) == index++);
        CHECK(names.insert(std::string(m.name)).second);
        CHECK(&vplkit::gi_method(m.method) == &m);
        CHECK(vplkit::find_gi_method(m.name) == &m);
        CHECK(std::string(vplkit::gi_method_name(m.method)) == m.name);
        CHECK(!m.summary.empty());
        // A method that builds no tree says why (the plan's reason); one that samples reads a tree.
        CHECK(m.samples == (m.reads_light_tree || m.reads_sst));
        CHECK(m.no_tree.empty() == m.samples);
        CHECK(m.stage.has_value() == (m.vpls != vplkit::GiVpls::none));
        // The budget weighs only methods that trade samples for time; only they have a bias floor.
        CHECK((!m.budget || m.samples));
        CHECK((m.bias_floor == 0.0 || m.budget));
    }
    CHECK(vplkit::find_gi_method("foo") == nullptr);
    CHECK(vplkit::find_gi_method("") == nullptr);
    CHECK(vplkit::gi_method_names() == "direct, exact, sst, rtslc, hybrid or flc");
    CHECK(vplkit::gi_method_names(&GiMethodInfo::blocks) == "rtslc or hybrid");
    CHECK(vplkit::gi_method_names(&GiMethodInfo::interleaves) == "rtslc");
    CHECK(vplkit::gi_method_names(&GiMethodInfo::budget) == "sst, rtslc or hybrid");
    CHECK(vplkit::gi_methods_with(&GiMethodInfo::budget) ==
          std::vector<vplkit::GiMethod>{vplkit::GiMethod::sst, vplkit::GiMethod::rtslc, vplkit::GiMethod::hybrid});
}

TEST_CASE("gi methods: a plan runs the method's own stage and exactly the trees its row reads") {
    const auto scene = vplkit::scene::load_gltf(kCornellPoint);
    for (const GiMethodInfo& m : vplkit::gi_methods()) {
        CAPTURE(m.name);
        RenderSettings settings;
        settings.method = m.method;
        const vplkit::FramePlan plan = vplkit::plan_frame(scene, settings, "view");
        for (const GiMethodInfo& other : vplkit::gi_methods()) {
            if (other.stage) CHECK(plan.runs(*other.stage) == (other.method == m.method));
        }
        CHECK(plan.runs(FrameStage::light_tree) == m.reads_light_tree);
        CHECK(plan.runs(FrameStage::sst) == m.reads_sst);
        CHECK(plan.runs(FrameStage::vpl_sort) == m.samples);
        const bool from_source =
            plan.runs(FrameStage::vpl_paths) || plan.runs(FrameStage::brsm_vpls) || plan.runs(FrameStage::smc_vpls);
        CHECK(from_source == (m.vpls == vplkit::GiVpls::source));
        settings.denoise = vplkit::DenoiseMode::svgf;
        CHECK(vplkit::plan_frame(scene, settings, "view").runs(FrameStage::denoise) ==
              (m.vpls != vplkit::GiVpls::none && !m.ground_truth));
    }
}

TEST_CASE("gi methods: the settings check looks at the chosen method's options only") {
    for (const GiMethodInfo& m : vplkit::gi_methods()) {
        CAPTURE(m.name);
        RenderSettings settings;
        settings.method = m.method;
        CHECK_NOTHROW(vplkit::validate_gi_settings(settings));
        settings.samples_per_pixel = 0;  // no sampling method takes it
        if (m.samples) {
            CHECK_THROWS_AS(vplkit::validate_gi_settings(settings), vplkit::Error);
        } else {
            CHECK_NOTHROW(vplkit::validate_gi_settings(settings));
        }
    }
}

TEST_CASE("gi methods: the bench's curves have names of their own and their quality knob first") {
    std::set<std::string> names;
    for (const vplkit::GiBenchCurveOf& c : vplkit::gi_bench_curves()) {
        CAPTURE(c.curve->name);
        CHECK(names.insert(std::string(c.curve->name)).second);
        CHECK(c.sweeps(c.quality_sweep()));
        CHECK((c.quality_sweep() == "spp") == c.method->samples);
        REQUIRE(vplkit::find_gi_bench_curve(c.curve->name).has_value());
        CHECK(vplkit::find_gi_bench_curve(c.curve->name)->curve == c.curve);
        // A curve's name is its method's, or a variant's: the method's name and a suffix.
        CHECK(std::string(c.curve->name).rfind(std::string(c.method->name), 0) == 0);
        CHECK((c.curve->name == c.method->name) == (c.curve->variant == nullptr));
    }
    CHECK_FALSE(vplkit::find_gi_bench_curve("foo").has_value());
    CHECK_FALSE(vplkit::find_gi_bench_curve("exact").has_value());  // the ground truth is no curve
    CHECK(vplkit::gi_bench_curve_names() == "sst, rtslc, hybrid, hybrid-lightcuts, flc");
    CHECK_FALSE(vplkit::find_gi_bench_curve("sst")->sweeps("sp"));
}
