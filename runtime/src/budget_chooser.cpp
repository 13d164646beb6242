// The chooser over predicted times and errors (budget_chooser.hpp).

#include "vplkit/budget_chooser.hpp"

#include "vplkit/error.hpp"

#include <cmath>
#include <cstdio>

namespace vplkit {
namespace {

std::string number(double value, const char* format) {
    char text[64];
    std::snprintf(text, sizeof(text), format, value);
    return text;
}

// "method M, spp N, resolution R, denoise D, vpls V: predicted T ms, error E" (the block size is
// in the stats' fields, not in the line the issue set)
std::string describe(const BudgetCandidate& c) {
    return std::string("method ") + gi_method_name(c.config.method) + ", spp " + std::to_string(c.config.spp) +
           ", resolution " + gi_resolution_name(c.config.half_resolution) + ", denoise " +
           denoise_mode_name(c.config.denoise) + ", vpls " + std::to_string(c.config.vpls) + ": predicted " +
           number(c.predicted_ms, "%.1f") + " ms, error " + number(c.predicted_rmse, "%.4f");
}

bool better(const BudgetCandidate& a, const BudgetCandidate& b) {
    if (a.predicted_rmse != b.predicted_rmse) return a.predicted_rmse < b.predicted_rmse;
    return a.predicted_ms < b.predicted_ms;
}

bool cheaper(const BudgetCandidate& a, const BudgetCandidate& b) {
    if (a.predicted_ms != b.predicted_ms) return a.predicted_ms < b.predicted_ms;
    return a.predicted_rmse < b.predicted_rmse;
}

}  // namespace

std::string BudgetChoice::line() const {
    std::string text = "budget: " + describe(chosen);
    if (next_best) text += " (next best: " + describe(*next_best) + ")";
    if (over_budget) {
        text += "; the budget of " + number(budget_ms, "%.1f") +
                " ms is below the cheapest frame, so this is the cheapest frame";
    }
    return text;
}

BudgetStatsFields budget_stats_fields(const BudgetChoice& choice) {
    const BudgetCandidate& c = choice.chosen;
    BudgetStatsFields f;
    f.method = gi_method_name(c.config.method);
    f.spp = c.config.spp;
    f.gi_resolution = gi_resolution_name(c.config.half_resolution);
    f.denoise = denoise_mode_name(c.config.denoise);
    f.vpls = c.config.vpls;
    f.block_size = c.config.block_size;
    f.predicted_ms = c.predicted_ms;
    f.predicted_rmse = c.predicted_rmse;
    f.budget_ms = choice.budget_ms;
    f.over_budget = choice.over_budget;
    return f;
}

BudgetChoice choose_for_budget(std::span<const BudgetCandidate> candidates, double budget_ms) {
    if (!std::isfinite(budget_ms) || budget_ms <= 0.0) {
        throw Error("budget: the frame time budget must be a number of milliseconds > 0, not " +
                    number(budget_ms, "%g"));
    }
    if (candidates.empty()) throw Error("budget: no configuration to choose from");
    BudgetChoice choice;
    choice.budget_ms = budget_ms;
    const BudgetCandidate* best = nullptr;
    const BudgetCandidate* second = nullptr;
    for (const BudgetCandidate& c : candidates) {
        if (c.predicted_ms > budget_ms) continue;
        if (!best || better(c, *best)) {
            second = best;
            best = &c;
        } else if (!second || better(c, *second)) {
            second = &c;
        }
    }
    if (!best) {
        // Nothing fits: the cheapest, and the next cheapest beside it.
        choice.over_budget = true;
        for (const BudgetCandidate& c : candidates) {
            if (!best || cheaper(c, *best)) {
                second = best;
                best = &c;
            } else if (!second || cheaper(c, *second)) {
                second = &c;
            }
        }
    }
    choice.chosen = *best;
    if (second) choice.next_best = *second;
    return choice;
}

}  // namespace vplkit
