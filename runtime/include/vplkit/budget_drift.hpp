#pragma once
// Re-planning a budget while frames run (a sequence, a viewer): the measured frame times drift
// from the calibrated prediction (the machine's load, what the camera sees, VPLs and trees reused
// on a still camera). BudgetDrift follows measured / predicted over the last few frames; when
// its median leaves [1 / tolerance, tolerance] the device is taken to run that much slower or
// faster than calibrated, and the caller chooses again over the candidates' times scaled by
// scale() (scaled_candidates). A median, so one slow frame (a shader compile) re-plans nothing.
//
//   BudgetDrift drift;
//   auto choice = choose_for_budget(candidates, B);
//   drift.start(choice.chosen.predicted_ms);
//   per frame: if (drift.record(frame_ms)) {
//       choice = choose_for_budget(scaled_candidates(candidates, drift.scale()), B);
//       drift.start(choice.chosen.predicted_ms);
//   }

#include "vplkit/budget_chooser.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace vplkit {

class BudgetDrift {
public:
    // Throws vplkit::Error unless tolerance > 1 and window >= 1.
    explicit BudgetDrift(double tolerance = 1.15, uint32_t window = 5);

    // A new choice: its predicted time (already scaled by scale()); the window starts empty.
    void start(double predicted_ms);
    // One frame's measured time. True when the window is full and its median ratio is past the
    // tolerance: scale() then holds the new scale and the caller should choose again.
    bool record(double measured_ms);

    // Measured over calibrated time: 1 until a drift was seen, then the product of the drifts.
    double scale() const { return scale_; }

private:
    double tolerance_;
    uint32_t window_;
    double predicted_ms_ = 0.0;
    std::vector<double> ratios_;
    double scale_ = 1.0;
};

// The candidates with their predicted times multiplied by `scale`.
std::vector<BudgetCandidate> scaled_candidates(std::span<const BudgetCandidate> candidates, double scale);

}  // namespace vplkit
