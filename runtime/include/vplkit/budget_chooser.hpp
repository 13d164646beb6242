#pragma once
// The budget chooser: of configurations with a predicted time and error each, the one with the
// least predicted error whose time is within the budget; when none is, the cheapest, said so.

#include "vplkit/budget_config.hpp"

#include <optional>
#include <span>
#include <string>

namespace vplkit {

struct BudgetCandidate {
    BudgetConfig config;
    double predicted_ms = 0.0;
    double predicted_rmse = 0.0;
};

struct BudgetChoice {
    double budget_ms = 0.0;
    BudgetCandidate chosen;
    // Within the budget: the next least error within it. Over the budget: the next cheapest.
    std::optional<BudgetCandidate> next_best;
    bool over_budget = false;  // no candidate fits: `chosen` is the cheapest

    // "budget: method M, spp N, resolution R, denoise D, vpls V: predicted T ms, error E (next
    // best: ...)", and over the budget a second sentence saying the budget is below the cheapest frame.
    std::string line() const;
};

// What a stats file holds under "budget" (the keys, and block_size, budget_ms, over_budget).
struct BudgetStatsFields {
    std::string method;  // "hybrid"
    uint32_t spp = 0;
    std::string gi_resolution;  // "full", "half"
    std::string denoise;        // "off", "svgf"
    uint32_t vpls = 0;
    uint32_t block_size = 0;
    double predicted_ms = 0.0;
    double predicted_rmse = 0.0;
    double budget_ms = 0.0;
    bool over_budget = false;
};
BudgetStatsFields budget_stats_fields(const BudgetChoice& choice);

// Throws vplkit::Error when there is no candidate or the budget is not a finite number > 0.
// Ties in error go to the faster configuration.
BudgetChoice choose_for_budget(std::span<const BudgetCandidate> candidates, double budget_ms);

}  // namespace vplkit
