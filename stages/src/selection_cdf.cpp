#include "vplkit/stages/selection_cdf.hpp"

#include "vplkit/error.hpp"

#include <cmath>
#include <string>

namespace vplkit::stages {

std::vector<float> selection_cdf(const std::vector<double>& weights) {
    double sum = 0.0;
    uint64_t positive = 0;
    for (double w : weights) {
        if (!std::isfinite(w) || w < 0.0) {
            throw Error("emitter selection: a weight is negative or not finite (" + std::to_string(w) + ")");
        }
        sum += w;
        positive += w > 0.0;
    }
    if (!(sum > 0.0)) throw Error("emitter selection: every weight is 0");
    if (positive > kSelectionSteps) {
        throw Error("emitter selection: " + std::to_string(positive) + " emitters with power, at most " +
                    std::to_string(kSelectionSteps) + " can each get a share");
    }
    // One step per positive weight, the other steps shared by the running sum's floor, so the
    // shares add up to exactly 2^24 and each is within one step of its weight's share of them.
    const double shared = double(kSelectionSteps - positive);
    std::vector<float> cdf;
    cdf.reserve(weights.size());
    double running = 0.0;
    uint64_t ones = 0, previous_shared = 0;
    for (double w : weights) {
        running += w;
        ones += w > 0.0;
        // The last positive weight takes every remaining step (running / sum may round below 1).
        const uint64_t now_shared =
            ones == positive ? uint64_t(shared) : uint64_t(std::floor(shared * (running / sum)));
        const uint64_t steps = ones + (w > 0.0 ? now_shared : previous_shared);
        if (w > 0.0) previous_shared = now_shared;
        cdf.push_back(float(double(steps) / double(kSelectionSteps)));
    }
    return cdf;
}

}  // namespace vplkit::stages
