#include "vplkit/sequence_metrics.hpp"

#include "vplkit/error.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace vplkit {

std::vector<double> reinhard_luminance(std::span<const float> rgb, double exposure) {
    if (rgb.size() % 3 != 0) throw Error("reinhard luminance: the image is not RGB (size not a multiple of 3)");
    std::vector<double> out(rgb.size() / 3);
    for (size_t p = 0; p < out.size(); ++p) {
        const double y = exposure * (0.2126 * double(rgb[3 * p]) + 0.7152 * double(rgb[3 * p + 1]) +
                                     0.0722 * double(rgb[3 * p + 2]));
        if (!std::isfinite(y) || y < 0.0) {
            throw Error("reinhard luminance: pixel " + std::to_string(p) + " has luminance " + std::to_string(y) +
                        " (NaN, infinite or negative)");
        }
        out[p] = y / (1.0 + y);
    }
    return out;
}

namespace {

double average(const std::vector<double>& values, size_t from) {
    if (values.size() <= from) return std::numeric_limits<double>::quiet_NaN();
    double sum = 0.0;
    for (size_t i = from; i < values.size(); ++i) sum += values[i];
    return sum / double(values.size() - from);
}

}  // namespace

double TemporalError::average_error() const {
    return average(mean_abs_error, 0);
}

double TemporalError::average_error_change() const {
    return average(mean_abs_error_change, 1);
}

void TemporalErrorMeter::add_frame(std::span<const double> test, std::span<const double> reference) {
    if (test.size() != reference.size() || test.empty()) {
        throw Error("temporal error: a frame and its reference differ in size, or are empty");
    }
    if (!previous_.empty() && previous_.size() != test.size()) {
        throw Error("temporal error: the frame size changed within the sequence");
    }
    std::vector<double> error(test.size());
    double sum = 0.0, change = 0.0;
    for (size_t p = 0; p < test.size(); ++p) {
        error[p] = test[p] - reference[p];
        sum += std::abs(error[p]);
        if (!previous_.empty()) change += std::abs(error[p] - previous_[p]);  // eq. 10, dt = 1 frame
    }
    const double n = double(test.size());
    result_.mean_abs_error.push_back(sum / n);
    result_.mean_abs_error_change.push_back(previous_.empty() ? std::numeric_limits<double>::quiet_NaN() : change / n);
    previous_ = std::move(error);
}

}  // namespace vplkit
