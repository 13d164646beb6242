// sequence_metrics.hpp (the SMC paper sec. 5.2, eq. 10) against values worked out by hand on tiny
// synthetic sequences of 2-pixel frames. Exact arithmetic on small fractions: 1e-12.

#include "vplkit/error.hpp"
#include "vplkit/sequence_metrics.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

TEST_CASE("sequence metrics: Reinhard luminance is Y / (1 + Y)") {
    // Y of (1, 1, 1) is 1 -> 0.5; of (3, 3, 3) x exposure 1 is 3 -> 0.75; black -> 0.
    const std::vector<float> rgb = {1, 1, 1, 3, 3, 3, 0, 0, 0};
    const auto l = vplkit::reinhard_luminance(rgb);
    REQUIRE(l.size() == 3);
    CHECK(l[0] == doctest::Approx(0.5).epsilon(1e-12));
    CHECK(l[1] == doctest::Approx(0.75).epsilon(1e-12));
    CHECK(l[2] == 0.0);
    // Exposure scales L before the curve: (1, 1, 1) x 3 -> 0.75. Pure green: Y = 0.7152.
    CHECK(vplkit::reinhard_luminance(std::vector<float>{1, 1, 1}, 3.0)[0] == doctest::Approx(0.75).epsilon(1e-12));
    CHECK(vplkit::reinhard_luminance(std::vector<float>{0, 1, 0})[0] ==
          doctest::Approx(0.7152 / 1.7152).epsilon(1e-12));
    CHECK_THROWS_AS(vplkit::reinhard_luminance(std::vector<float>{NAN, 0, 0}), vplkit::Error);
    CHECK_THROWS_AS(vplkit::reinhard_luminance(std::vector<float>{-1, -1, -1}), vplkit::Error);
}

TEST_CASE("sequence metrics: |E| and |E'| of hand-computed sequences") {
    // Reference (0.5, 0.5) in every frame. Frames: (0.6, 0.5), (0.6, 0.3), (0.4, 0.3).
    // Errors: (0.1, 0), (0.1, -0.2), (-0.1, -0.2).
    // |E| = 0.05, 0.15, 0.15; |E'|: -, (0 + 0.2) / 2 = 0.1, (0.2 + 0) / 2 = 0.1.
    vplkit::TemporalErrorMeter meter;
    const std::vector<double> ref = {0.5, 0.5};
    meter.add_frame(std::vector<double>{0.6, 0.5}, ref);
    meter.add_frame(std::vector<double>{0.6, 0.3}, ref);
    meter.add_frame(std::vector<double>{0.4, 0.3}, ref);
    const auto& r = meter.result();
    REQUIRE(r.mean_abs_error.size() == 3);
    CHECK(r.mean_abs_error[0] == doctest::Approx(0.05).epsilon(1e-12));
    CHECK(r.mean_abs_error[1] == doctest::Approx(0.15).epsilon(1e-12));
    CHECK(r.mean_abs_error[2] == doctest::Approx(0.15).epsilon(1e-12));
    CHECK(std::isnan(r.mean_abs_error_change[0]));
    CHECK(r.mean_abs_error_change[1] == doctest::Approx(0.1).epsilon(1e-12));
    CHECK(r.mean_abs_error_change[2] == doctest::Approx(0.1).epsilon(1e-12));
    CHECK(r.average_error() == doctest::Approx(0.35 / 3).epsilon(1e-12));
    CHECK(r.average_error_change() == doctest::Approx(0.1).epsilon(1e-12));
}

TEST_CASE("sequence metrics: a constant error has |E'| = 0 and a moving reference counts") {
    // A steady bias: |E| stays, |E'| is zero (no flicker).
    vplkit::TemporalErrorMeter steady;
    steady.add_frame(std::vector<double>{0.7, 0.2}, std::vector<double>{0.5, 0.4});
    steady.add_frame(std::vector<double>{0.7, 0.2}, std::vector<double>{0.5, 0.4});
    CHECK(steady.result().mean_abs_error[1] == doctest::Approx(0.2).epsilon(1e-12));
    CHECK(steady.result().mean_abs_error_change[1] == doctest::Approx(0.0).epsilon(1e-12));
    // Identical frames over a changing reference: the error changes by the reference's change.
    vplkit::TemporalErrorMeter moving;
    moving.add_frame(std::vector<double>{0.5, 0.5}, std::vector<double>{0.5, 0.5});
    moving.add_frame(std::vector<double>{0.5, 0.5}, std::vector<double>{0.4, 0.7});
    CHECK(moving.result().mean_abs_error_change[1] == doctest::Approx(0.15).epsilon(1e-12));
    CHECK(std::isnan(vplkit::TemporalError{}.average_error()));
}

TEST_CASE("sequence metrics: mismatched sizes are refused") {
    vplkit::TemporalErrorMeter meter;
    CHECK_THROWS_AS(meter.add_frame(std::vector<double>{0.1}, std::vector<double>{0.1, 0.2}), vplkit::Error);
    meter.add_frame(std::vector<double>{0.1}, std::vector<double>{0.1});
    CHECK_THROWS_AS(meter.add_frame(std::vector<double>{0.1, 0.2}, std::vector<double>{0.1, 0.2}), vplkit::Error);
}
