// The budget chooser (budget_chooser.hpp) on a synthetic table of predicted times and errors.

#include "vplkit/budget_chooser.hpp"
#include "vplkit/budget_fixed.hpp"

#include "vplkit/error.hpp"

#include <doctest/doctest.h>

#include <limits>
#include <vector>

namespace {

using vplkit::BudgetCandidate;
using vplkit::BudgetConfig;
using vplkit::DenoiseMode;
using vplkit::GiMethod;

// A table where neither the fastest nor the most accurate is the answer for the middle budgets:
// time grows with spp, error falls; half resolution is cheaper with a floor; svgf has its own floor.
std::vector<BudgetCandidate> table() {
    std::vector<BudgetCandidate> t;
    for (GiMethod m : {GiMethod::rtslc, GiMethod::hybrid}) {
        for (uint32_t spp : {1u, 4u, 16u}) {
            for (bool half : {false, true}) {
                for (DenoiseMode d : {DenoiseMode::off, DenoiseMode::svgf}) {
                    const double per_sample = m == GiMethod::hybrid ? 1.5 : 1.0;
                    double ms = 10.0 + per_sample * spp * (half ? 2.5 : 10.0) + (d == DenoiseMode::svgf ? 6.0 : 0.0);
                    double noise = (m == GiMethod::hybrid ? 0.08 : 0.1) / std::sqrt(double(spp)) * (half ? 0.8 : 1.0);
                    if (d == DenoiseMode::svgf) noise = 0.03 + 0.25 * noise;
                    const double floor = half ? 0.02 : 0.0;
                    t.push_back({BudgetConfig{m, spp, half, d, 4096, 8}, ms, std::sqrt(noise * noise + floor * floor)});
                }
            }
        }
    }
    return t;
}

// The brute-force answer: the least error within the budget.
const BudgetCandidate* optimum(const std::vector<BudgetCandidate>& t, double budget) {
    const BudgetCandidate* best = nullptr;
    for (const auto& c : t) {
        if (c.predicted_ms <= budget && (!best || c.predicted_rmse < best->predicted_rmse)) best = &c;
    }
    return best;
}

bool same(const BudgetConfig& a, const BudgetConfig& b) {
    return a.method == b.method && a.spp == b.spp && a.half_resolution == b.half_resolution && a.denoise == b.denoise &&
           a.vpls == b.vpls && a.block_size == b.block_size;
}

}  // namespace

TEST_CASE("budget: the chooser picks the least predicted error within the budget") {
    const auto t = table();
    int distinct_answers = 0;
    BudgetConfig last{};
    for (double budget : {15.0, 20.0, 30.0, 45.0, 60.0, 100.0, 200.0, 300.0}) {
        CAPTURE(budget);
        const vplkit::BudgetChoice choice = vplkit::choose_for_budget(t, budget);
        const BudgetCandidate* best = optimum(t, budget);
        REQUIRE(best);
        CHECK(!choice.over_budget);
        CHECK(same(choice.chosen.config, best->config));
        CHECK(choice.chosen.predicted_ms <= budget);
        REQUIRE(choice.next_best);
        CHECK(choice.next_best->predicted_ms <= budget);
        CHECK(choice.next_best->predicted_rmse >= choice.chosen.predicted_rmse);
        if (!same(choice.chosen.config, last)) ++distinct_answers;
        last = choice.chosen.config;
    }
    // The table makes the answer move with the budget (else the test would prove little).
    CHECK(distinct_answers >= 4);
}

TEST_CASE("budget: the chooser's line and stats fields") {
    const std::vector<BudgetCandidate> t{
        {BudgetConfig{GiMethod::hybrid, 8, true, DenoiseMode::svgf, 4096, 8}, 42.25, 0.0312},
        {BudgetConfig{GiMethod::rtslc, 16, false, DenoiseMode::off, 1024, 4}, 48.0, 0.0400},
        {BudgetConfig{GiMethod::sst, 64, false, DenoiseMode::off, 4096, 8}, 90.0, 0.0100},
    };
    const auto choice = vplkit::choose_for_budget(t, 50.0);
    CHECK(choice.line() ==
          "budget: method hybrid, spp 8, resolution half, denoise svgf, vpls 4096: predicted 42.2 ms, error 0.0312 "
          "(next best: method rtslc, spp 16, resolution full, denoise off, vpls 1024: predicted 48.0 ms, error "
          "0.0400)");
    const auto f = vplkit::budget_stats_fields(choice);
    CHECK(f.method == "hybrid");
    CHECK(f.spp == 8);
    CHECK(f.gi_resolution == "half");
    CHECK(f.denoise == "svgf");
    CHECK(f.vpls == 4096);
    CHECK(f.block_size == 8);
    CHECK(f.predicted_ms == 42.25);
    CHECK(f.predicted_rmse == 0.0312);
    CHECK(!f.over_budget);
}

TEST_CASE("budget: a budget below the cheapest frame gives the cheapest frame and says so") {
    const auto t = table();
    const auto choice = vplkit::choose_for_budget(t, 5.0);
    CHECK(choice.over_budget);
    double cheapest = std::numeric_limits<double>::infinity();
    for (const auto& c : t) cheapest = std::min(cheapest, c.predicted_ms);
    CHECK(choice.chosen.predicted_ms == cheapest);
    REQUIRE(choice.next_best);
    CHECK(choice.next_best->predicted_ms >= cheapest);
    CHECK(choice.line().find("the budget of 5.0 ms is below the cheapest frame, so this is the cheapest frame") !=
          std::string::npos);
    CHECK(vplkit::budget_stats_fields(choice).over_budget);
    // A budget that fits says nothing of the kind.
    CHECK(vplkit::choose_for_budget(t, 1000.0).line().find("below the cheapest") == std::string::npos);
}

TEST_CASE("budget: the chooser refuses no candidates and budgets that are not a positive number") {
    const auto t = table();
    CHECK_THROWS_WITH_AS(vplkit::choose_for_budget(t, 0.0), doctest::Contains("> 0"), vplkit::Error);
    CHECK_THROWS_AS(vplkit::choose_for_budget(t, -3.0), vplkit::Error);
    CHECK_THROWS_AS(vplkit::choose_for_budget(t, std::numeric_limits<double>::quiet_NaN()), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::choose_for_budget(std::vector<BudgetCandidate>{}, 10.0),
                         doctest::Contains("no configuration"), vplkit::Error);
}

TEST_CASE("budget: knobs the user fixed are kept and the chooser varies the rest") {
    const auto t = table();
    // The method fixed is the one the unconstrained choice does not take (else keeping it would prove nothing).
    const double budget = 60.0;
    const GiMethod free = vplkit::choose_for_budget(t, budget).chosen.config.method;
    const GiMethod other = free == GiMethod::rtslc ? GiMethod::hybrid : GiMethod::rtslc;
    vplkit::BudgetFixed fixed;
    fixed.method = other;
    const auto kept = vplkit::candidates_keeping(t, fixed);
    const auto choice = vplkit::choose_for_budget(kept, budget);
    CHECK(choice.chosen.config.method == other);
    // ... and the best configuration of that method within the budget, by brute force.
    const BudgetCandidate* best = optimum(kept, budget);
    REQUIRE(best);
    CHECK(same(choice.chosen.config, best->config));
    REQUIRE(choice.next_best);
    CHECK(choice.next_best->config.method == other);

    // Two fixed knobs: the chooser still picks the spp and the resolution.
    fixed.method = GiMethod::rtslc;
    fixed.denoise = DenoiseMode::svgf;
    for (double b : {30.0, 60.0, 300.0}) {
        const auto c = vplkit::choose_for_budget(vplkit::candidates_keeping(t, fixed), b);
        CHECK(c.chosen.config.method == GiMethod::rtslc);
        CHECK(c.chosen.config.denoise == DenoiseMode::svgf);
    }
    CHECK(vplkit::describe_budget_fixed(fixed) == "method rtslc, denoise svgf");
    CHECK(vplkit::describe_budget_fixed({}).empty());
}

TEST_CASE("budget: the space narrowed to the fixed knobs") {
    vplkit::BudgetSpace space;
    space.vpls = {1024, 4096};
    space.block_sizes = {4, 8};
    vplkit::BudgetFixed fixed;
    fixed.spp = 8;
    fixed.half_resolution = true;
    fixed.vpls = 4096;
    const auto narrow = vplkit::narrow_budget_space(space, fixed);
    CHECK(narrow.methods.size() == 3);  // not fixed: all three
    CHECK(narrow.spp == std::vector<uint32_t>{8});
    CHECK(narrow.half_resolution == std::vector<bool>{true});
    CHECK(narrow.denoise.size() == 2);
    CHECK(narrow.vpls == std::vector<uint32_t>{4096});
    CHECK(narrow.block_sizes == std::vector<uint32_t>{4, 8});
    // sst has no block size to keep.
    fixed = {};
    fixed.block_size = 4;
    CHECK(vplkit::keeps_fixed(BudgetConfig{GiMethod::sst, 8, false, DenoiseMode::off, 4096, 8}, fixed));
    CHECK(!vplkit::keeps_fixed(BudgetConfig{GiMethod::rtslc, 8, false, DenoiseMode::off, 4096, 8}, fixed));
}
