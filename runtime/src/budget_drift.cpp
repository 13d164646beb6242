// The budget's drift detector (budget_drift.hpp).

#include "vplkit/budget_drift.hpp"

#include "vplkit/error.hpp"

#include <algorithm>
#include <cmath>

namespace vplkit {

BudgetDrift::BudgetDrift(double tolerance, uint32_t window) : tolerance_(tolerance), window_(window) {
    if (!(tolerance > 1.0) || !std::isfinite(tolerance)) throw Error("budget drift: the tolerance must be > 1");
    if (window == 0) throw Error("budget drift: the window must hold at least one frame");
}

void BudgetDrift::start(double predicted_ms) {
    predicted_ms_ = predicted_ms;
    ratios_.clear();
}

bool BudgetDrift::record(double measured_ms) {
    // A prediction of 0 (or a measurement that is not a time) says nothing about the scale.
    if (!(predicted_ms_ > 0.0) || !std::isfinite(measured_ms) || measured_ms < 0.0) return false;
    ratios_.push_back(measured_ms / predicted_ms_);
    if (ratios_.size() > window_) ratios_.erase(ratios_.begin());
    if (ratios_.size() < window_) return false;
    std::vector<double> sorted = ratios_;
    std::sort(sorted.begin(), sorted.end());
    const size_t n = sorted.size();
    const double median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    if (median <= tolerance_ && median >= 1.0 / tolerance_) return false;
    scale_ *= median;
    ratios_.clear();
    return true;
}

std::vector<BudgetCandidate> scaled_candidates(std::span<const BudgetCandidate> candidates, double scale) {
    std::vector<BudgetCandidate> out(candidates.begin(), candidates.end());
    for (BudgetCandidate& c : out) c.predicted_ms *= scale;
    return out;
}

}  // namespace vplkit
