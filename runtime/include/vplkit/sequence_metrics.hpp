#pragma once
// The temporal error metrics of the SMC paper (sec. 5.2, Table 1) for a sequence of frames against a
// per-frame reference, on Reinhard-tonemapped luminance (the paper measures "after applying the
// Reinhard tone mapping operator", its [38]: L_d = L / (1 + L), the global operator):
//   E_p(t)  = T(L_p(t)) - T(R_p(t))                    the signed error of pixel p in frame t
//   |E|(t)  = mean over p of |E_p(t)|                   the frame's mean absolute error
//   E'_p(t) = (E_p(t) - E_p(t - 1)) / dt                the SMC paper eq. 10, dt = one frame
//   |E'|(t) = mean over p of |E'_p(t)|                  (from the second frame on)
// |E'| shows flicker: an error that stays put from frame to frame does not count, one that
// changes does. As the paper notes, it can be non-zero with fixed VPLs when the camera moves.
//
// Images are linear RGB float, 3 floats per pixel (RenderedImage::radiance or ::indirect).
// Luminance: Rec. 709 weights, as the tonemap's. Computed in double.

#include <cstddef>
#include <span>
#include <vector>

namespace vplkit {

// Reinhard's global operator on each pixel's luminance: L / (1 + L), L = exposure x Y(rgb).
// Throws vplkit::Error for a NaN or infinite value or a negative luminance (names the pixel).
std::vector<double> reinhard_luminance(std::span<const float> rgb, double exposure = 1.0);

// Per frame: |E| and, from the second frame, |E'| (NaN for the first).
struct TemporalError {
    std::vector<double> mean_abs_error;         // |E|(t)
    std::vector<double> mean_abs_error_change;  // |E'|(t), NaN at t = 0
    // Their averages over the sequence (|E'| over frames 1..n-1; NaN for a single frame).
    double average_error() const;
    double average_error_change() const;
};

// Accumulates a sequence frame by frame, keeping only the previous frame's errors.
class TemporalErrorMeter {
public:
    // Tonemapped luminances of the frame and its reference (reinhard_luminance), same size;
    // throws vplkit::Error when their sizes differ or change from the previous frame.
    void add_frame(std::span<const double> test, std::span<const double> reference);
    const TemporalError& result() const { return result_; }

private:
    std::vector<double> previous_;
    TemporalError result_;
};

}  // namespace vplkit
