// Re-planning when measured frame times drift from the prediction (budget_drift.hpp).

#include "vplkit/budget_drift.hpp"

#include "vplkit/error.hpp"

#include <doctest/doctest.h>

#include <vector>

namespace {

using vplkit::BudgetCandidate;
using vplkit::BudgetConfig;
using vplkit::DenoiseMode;
using vplkit::GiMethod;

// More spp: more time, less error.
std::vector<BudgetCandidate> table() {
    std::vector<BudgetCandidate> t;
    for (uint32_t spp : {1u, 2u, 4u, 8u, 16u}) {
        t.push_back(
            {BudgetConfig{GiMethod::rtslc, spp, false, DenoiseMode::off, 4096, 8}, 5.0 + 5.0 * spp, 0.1 / double(spp)});
    }
    return t;
}

}  // namespace

TEST_CASE("budget: a device running slower than calibrated re-plans to a cheaper configuration") {
    const auto t = table();
    const double budget = 50.0;
    auto choice = vplkit::choose_for_budget(t, budget);
    CHECK(choice.chosen.config.spp == 8);  // 45 ms
    vplkit::BudgetDrift drift;
    drift.start(choice.chosen.predicted_ms);
    // 1.4x slower than predicted: the fifth frame fills the window and re-plans.
    for (int i = 0; i < 4; ++i) CHECK(!drift.record(63.0));
    CHECK(drift.record(63.0));
    CHECK(drift.scale() == doctest::Approx(1.4));
    choice = vplkit::choose_for_budget(vplkit::scaled_candidates(t, drift.scale()), budget);
    CHECK(choice.chosen.config.spp == 4);  // 25 ms x 1.4 = 35 ms; 8 spp would take 63
    drift.start(choice.chosen.predicted_ms);
    // Now as predicted, within the tolerance: no more re-plans.
    for (int i = 0; i < 10; ++i) CHECK(!drift.record(choice.chosen.predicted_ms * 1.05));
}

TEST_CASE("budget: one slow frame re-plans nothing, a faster device re-plans upwards") {
    vplkit::BudgetDrift drift(1.15, 5);
    drift.start(20.0);
    const double frames[] = {20.0, 80.0, 21.0, 19.0, 20.0, 20.0, 20.0};
    for (double ms : frames) CHECK(!drift.record(ms));
    CHECK(drift.scale() == 1.0);
    drift.start(20.0);
    bool replanned = false;
    for (int i = 0; i < 5; ++i) replanned = drift.record(10.0);
    CHECK(replanned);
    CHECK(drift.scale() == doctest::Approx(0.5));
    const auto choice = vplkit::choose_for_budget(vplkit::scaled_candidates(table(), drift.scale()), 50.0);
    CHECK(choice.chosen.config.spp == 16);  // 85 ms x 0.5
    CHECK_THROWS_AS(vplkit::BudgetDrift(1.0, 5), vplkit::Error);
    CHECK_THROWS_AS(vplkit::BudgetDrift(1.2, 0), vplkit::Error);
}
