// The cost model's fit (budget_fit.hpp, budget_cost.hpp) on synthetic timings made from known
// coefficients: the fit gives them back, a feature never varied is dropped instead of guessed,
// and a frame's prediction sums the stages its plan runs.

#include "vplkit/budget_cost.hpp"
#include "vplkit/budget_fit.hpp"

#include "vplkit/error.hpp"
#include "vplkit/planner.hpp"

#include <doctest/doctest.h>

#include <vector>

namespace {

using vplkit::CostPoint;
using vplkit::FrameStage;

const uint32_t kGiHybrid = vplkit::stage_tag(FrameStage::gi_hybrid);
const uint32_t kSort = vplkit::stage_tag(FrameStage::vpl_sort);
const uint32_t kGbuffer = vplkit::stage_tag(FrameStage::gbuffer);

// The calibration's kind of points: two sizes, two spp, two block sizes, two VPL budgets, half resolution.
std::vector<CostPoint> calibration_points() {
    std::vector<CostPoint> points;
    for (double pixels : {320.0 * 180.0, 160.0 * 90.0}) {
        for (double spp : {4.0, 16.0}) {
            for (double block : {4.0, 8.0}) {
                for (double vpls : {1024.0, 4096.0}) {
                    points.push_back({pixels, pixels, spp, block, vpls});
                    points.push_back({pixels, pixels / 4.0, spp, block, vpls});
                }
            }
        }
    }
    return points;
}

// Known models: gi hybrid 0.5 + 2e-5 px + 3e-6 px spp + 1e-4 px spp / block^2; sort 0.2 + 1e-3 vpls;
// G-buffer 0.1 + 4e-6 px.
double hybrid_ms(const CostPoint& p) {
    return 0.5 + 2e-5 * p.gi_pixels + 3e-6 * p.gi_pixels * p.spp +
           1e-4 * p.gi_pixels * p.spp / (p.block_size * p.block_size);
}
double sort_ms(const CostPoint& p) {
    return 0.2 + 1e-3 * p.vpls;
}
double gbuffer_ms(const CostPoint& p) {
    return 0.1 + 4e-6 * p.pixels;
}

}  // namespace

TEST_CASE("budget: the cost model's fit recovers known coefficients from synthetic timings") {
    vplkit::CostModel model;
    for (const CostPoint& p : calibration_points()) {
        model.add_sample(kGiHybrid, p, hybrid_ms(p));
        model.add_sample(kSort, p, sort_ms(p));
        model.add_sample(kGbuffer, p, gbuffer_ms(p));
    }
    model.fit();
    const std::vector<double> expected_hybrid{0.5, 2e-5, 3e-6, 1e-4};
    const auto& hybrid = model.coefficients().at(kGiHybrid);
    REQUIRE(hybrid.size() == expected_hybrid.size());
    for (size_t i = 0; i < hybrid.size(); ++i) {
        CAPTURE(i);
        CHECK(hybrid[i] == doctest::Approx(expected_hybrid[i]).epsilon(1e-6));
    }
    CHECK(model.coefficients().at(kSort)[0] == doctest::Approx(0.2).epsilon(1e-6));
    CHECK(model.coefficients().at(kSort)[1] == doctest::Approx(1e-3).epsilon(1e-6));
    CHECK(model.coefficients().at(kGbuffer)[1] == doctest::Approx(4e-6).epsilon(1e-6));
    // A point never timed: 1280x720, 64 spp, block 16, 65536 VPLs.
    const CostPoint far{1280.0 * 720.0, 1280.0 * 720.0, 64.0, 16.0, 65536.0};
    CHECK(model.predict_stage(kGiHybrid, far) == doctest::Approx(hybrid_ms(far)).epsilon(1e-6));
    CHECK(model.predict_stage(kSort, far) == doctest::Approx(sort_ms(far)).epsilon(1e-6));
}

TEST_CASE("budget: noisy timings give coefficients near the true ones") {
    // +-5% multiplicative noise, alternating: between the points timed the fit stays within 5%.
    vplkit::CostModel model;
    int sign = 1;
    for (const CostPoint& p : calibration_points()) {
        model.add_sample(kGiHybrid, p, hybrid_ms(p) * (1.0 + 0.05 * sign));
        sign = -sign;
    }
    model.fit();
    const CostPoint p{240.0 * 135.0, 240.0 * 135.0, 8.0, 6.0, 2048.0};
    CHECK(model.predict_stage(kGiHybrid, p) == doctest::Approx(hybrid_ms(p)).epsilon(0.05));
}

TEST_CASE("budget: a feature the calibration never varied gets coefficient 0, the rest still fit") {
    // One block size only: the per-cut-node feature is proportional to the per-sample one.
    std::vector<double> features;
    std::vector<double> times;
    for (double px : {1000.0, 4000.0}) {
        for (double spp : {4.0, 16.0}) {
            const double samples = px * spp;
            features.insert(features.end(), {1.0, px, samples, samples / 64.0});
            times.push_back(1.0 + 0.01 * px + 0.002 * samples);
        }
    }
    const std::vector<double> c = vplkit::fit_linear(features, 4, times);
    CHECK(c[0] == doctest::Approx(1.0));
    CHECK(c[1] == doctest::Approx(0.01));
    CHECK(c[2] == doctest::Approx(0.002));
    CHECK(c[3] == 0.0);
    CHECK_THROWS_AS(vplkit::fit_linear(features, 3, times), vplkit::Error);
}

TEST_CASE("budget: a frame's predicted time sums the stages its plan runs, and names one never timed") {
    vplkit::CostModel model;
    model.set_coefficients(0, {0.5, 0.0});
    model.set_coefficients(kGbuffer, {1.0, 0.0});
    model.set_coefficients(kSort, {2.0, 0.0});
    vplkit::FramePlan plan;
    plan.stages = {{FrameStage::gbuffer, true, "r"}, {FrameStage::vpl_sort, false, "r"}};
    CHECK(*model.predict_frame(plan, CostPoint{}) == doctest::Approx(1.5));
    plan.stages[1].runs = true;
    CHECK(*model.predict_frame(plan, CostPoint{}) == doctest::Approx(3.5));
    plan.stages.push_back({FrameStage::gi_hybrid, true, "r"});
    std::string missing;
    CHECK(!model.predict_frame(plan, CostPoint{}, &missing));
    CHECK(missing == vplkit::stage_name(FrameStage::gi_hybrid));
    CHECK_THROWS_AS(model.set_coefficients(kGiHybrid, {1.0}), vplkit::Error);
}

TEST_CASE("budget: a slope that noisy timings make negative is left out and the rest refitted") {
    // Time falls with the VPLs in the samples (noise), rises with the pixels: the VPL slope is
    // set to 0 and the pixel slope fitted without it.
    std::vector<double> features;
    std::vector<double> times;
    for (double px : {1000.0, 4000.0}) {
        for (double vpls : {1024.0, 4096.0}) {
            features.insert(features.end(), {1.0, px, vpls});
            times.push_back(10.0 + 0.01 * px - 0.001 * vpls);
        }
    }
    const std::vector<double> free = vplkit::fit_linear(features, 3, times);
    CHECK(free[2] == doctest::Approx(-0.001));
    const std::vector<double> c = vplkit::fit_linear_nonnegative_slopes(features, 3, times);
    CHECK(c[2] == 0.0);
    CHECK(c[1] == doctest::Approx(0.01));
    CHECK(c[0] == doctest::Approx(10.0 - 0.001 * (1024.0 + 4096.0) / 2.0));
}
