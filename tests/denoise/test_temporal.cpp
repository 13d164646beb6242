// temporal_accumulate.comp: reprojection (a static camera maps each pixel to itself, a sideways
// camera move shifts history by the analytic number of pixels, a depth step is a disocclusion),
// the running mean's error against the exact mean falling like 1/sqrt(F) until a history cap,
// a static camera's exact running mean past the moving camera's cap (no cap there), and the
// whole pass against the double reference (tests/reference/denoise_reference.cpp).
// Tolerances: positions and the matrix are float, so a reprojected coordinate is off by ~1e-5
// pixel; colours here are O(1), so history values are off by ~1e-5 (checked at 1e-4).

#include "denoise_setup.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/denoise.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/trigonometric.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

using namespace vplkit;
using namespace vplkit::test;

namespace {

constexpr uint32_t kSize = 64;
constexpr float kPlaneZ = -5.0f;

PlaneScene flat_plane() {
    return {[](int, int) { return kPlaneZ; }, [](int, int) { return glm::vec3(0, 0, 1); }};
}

// A closer box face over the columns x >= 32 (z = -3), the back plane elsewhere.
PlaneScene stepped_plane() {
    return {[](int x, int) { return x >= 32 ? -3.0f : kPlaneZ; }, [](int, int) { return glm::vec3(0, 0, 1); }};
}

stages::DenoiseOptions test_options() {
    stages::DenoiseOptions options;
    options.scene_scale = 10.0f;  // max plane distance 0.1: the step (2 units) is another surface
    return options;
}

reference::TemporalParameters parameters_of(const stages::DenoiseOptions& options, const glm::mat4& previous_vp,
                                            bool has_history) {
    reference::TemporalParameters p;
    for (int i = 0; i < 16; ++i) p.previous_view_projection[i] = (&previous_vp[0][0])[i];
    p.max_plane_distance = double(options.max_plane_distance_fraction) * options.scene_scale;
    p.min_normal_cos = options.min_normal_cos;
    p.max_history = options.max_history;
    p.has_history = has_history;
    p.static_max_history = options.static_max_history;
    return p;
}

// One temporal pass on the GPU from images given as data.
reference::TemporalResult run_temporal(const DenoiseImage& irradiance, const DenoiseGeometry& current,
                                       const DenoiseGeometry& previous, const DenoiseImage& previous_color,
                                       const DenoiseImage& previous_moments, const glm::mat4& previous_vp,
                                       const stages::DenoiseOptions& options, DenoiseGeometry* stored = nullptr) {
    Context& ctx = context();
    auto in = upload_image(ctx, irradiance, "irradiance");
    auto position = upload_image(ctx, current.position, "position");
    auto normal = upload_image(ctx, current.normal, "normal");
    auto prev_position = upload_image(ctx, previous.position, "previous position");
    auto prev_normal = upload_image(ctx, previous.normal, "previous normal");
    auto prev_color = upload_image(ctx, previous_color, "previous color");
    auto prev_moments = upload_image(ctx, previous_moments, "previous moments");
    auto next_position = float4_image(ctx, kSize, kSize, "next position");
    auto next_normal = float4_image(ctx, kSize, kSize, "next normal");
    auto accumulated = float4_image(ctx, kSize, kSize, "accumulated");
    auto moments = float4_image(ctx, kSize, kSize, "moments");
    PassList passes("temporal test");
    stages::add_temporal_accumulate_pass(
        ctx, passes, in, position, normal, {prev_position, prev_normal, prev_color, prev_moments},
        {next_position, next_normal, {}, {}}, accumulated, moments, previous_vp, true, options);
    passes.run(ctx);
    if (stored) *stored = {download_image(next_position), download_image(next_normal)};
    return {download_image(accumulated), download_image(moments)};
}

DenoiseImage random_image(std::mt19937& rng, double lo, double hi) {
    std::uniform_real_distribution<double> u(lo, hi);
    DenoiseImage image(kSize, kSize);
    for (auto& t : image.texels) t = {u(rng), u(rng), u(rng), 0.0};
    return to_float_precision(image);
}

DenoiseImage constant_moments(double m1, double m2, double n) {
    DenoiseImage image(kSize, kSize);
    for (auto& t : image.texels) t = {m1, m2, n, 0.0};
    return image;
}

// The two history sets a renderer swaps between frames (the runtime's Denoiser keeps the same).
struct HistorySlot {
    Image position, normal, color, moments;
};
using HistorySlots = std::array<HistorySlot, 2>;

HistorySlots history_slots(Context& ctx) {
    HistorySlots slots;
    for (auto& s : slots)
        s = {float4_image(ctx, kSize, kSize, "history position"), float4_image(ctx, kSize, kSize, "history normal"),
             float4_image(ctx, kSize, kSize, "history color"), float4_image(ctx, kSize, kSize, "history moments")};
    return slots;
}

}  // namespace

TEST_CASE("denoise temporal: a static camera reprojects every pixel to itself") {
    const glm::mat4 vp = denoise_camera({0, 0, 0}, kSize, kSize);
    const DenoiseGeometry geometry = plane_geometry(vp, kSize, kSize, stepped_plane());
    std::mt19937 rng(11);
    const DenoiseImage current = random_image(rng, 0.0, 1.0), history = random_image(rng, 0.0, 1.0);
    const DenoiseImage moments = constant_moments(0.5, 0.3, 3.0);
    DenoiseGeometry stored;
    const auto out = run_temporal(current, geometry, geometry, history, moments, vp, test_options(), &stored);
    double worst = 0.0;
    for (int y = 0; y < int(kSize); ++y) {
        for (int x = 0; x < int(kSize); ++x) {
            CHECK(out.moments.at(x, y)[2] == 4.0);  // n = 3 + 1
            for (int c = 0; c < 3; ++c) {
                const double expected = 0.75 * history.at(x, y)[c] + 0.25 * current.at(x, y)[c];
                worst = std::max(worst, std::abs(out.accumulated.at(x, y)[c] - expected));
            }
        }
    }
    CHECK(worst < 1e-4);
    // The next frame's history holds this frame's geometry, unchanged.
    for (size_t i = 0; i < stored.position.texels.size(); ++i) {
        CAPTURE(i);
        for (int c = 0; c < 4; ++c) {
            CHECK(std::abs(stored.position.texels[i][c] - geometry.position.texels[i][c]) < 1e-6);
            CHECK(stored.normal.texels[i][c] == geometry.normal.texels[i][c]);
        }
    }
}

TEST_CASE("denoise temporal: a camera translation moves history by the analytic amount") {
    // Sideways by t: a point of the plane z = -5 moves by t / (5 tan(fov / 2)) x W / 2 pixels.
    const double shift = 2.5;
    const float t = float(shift * 2.0 / kSize * 5.0 * std::tan(glm::radians(22.5)));
    const glm::mat4 previous_vp = denoise_camera({0, 0, 0}, kSize, kSize);
    const glm::mat4 vp = denoise_camera({t, 0, 0}, kSize, kSize);
    const DenoiseGeometry previous = plane_geometry(previous_vp, kSize, kSize, flat_plane());
    const DenoiseGeometry current = plane_geometry(vp, kSize, kSize, flat_plane());
    // History = its own pixel coordinates (a ramp: bilinear interpolation of it is exact).
    DenoiseImage ramp(kSize, kSize);
    for (int y = 0; y < int(kSize); ++y)
        for (int x = 0; x < int(kSize); ++x) ramp.at(x, y) = {double(x), double(y), 0.0, 0.0};
    const DenoiseImage zero(kSize, kSize);
    const auto out =
        run_temporal(zero, current, previous, ramp, constant_moments(0, 0, 1.0), previous_vp, test_options());
    double worst = 0.0;
    for (int y = 0; y < int(kSize); ++y) {
        for (int x = 0; x + shift <= kSize - 1; ++x) {
            CAPTURE(x);
            CHECK(out.moments.at(x, y)[2] == 2.0);
            // alpha = 1 / 2: half the history at (x + shift, y), half the current 0.
            worst = std::max(worst, std::abs(out.accumulated.at(x, y)[0] - 0.5 * (x + shift)));
            worst = std::max(worst, std::abs(out.accumulated.at(x, y)[1] - 0.5 * y));
        }
        // Where the history ran off the previous image's edge: a new pixel.
        CHECK(out.moments.at(kSize - 1, y)[2] == 1.0);
    }
    CHECK(worst < 1e-3);
}

TEST_CASE("denoise temporal: a depth step is a disocclusion, both ways") {
    const glm::mat4 vp = denoise_camera({0, 0, 0}, kSize, kSize);
    const DenoiseGeometry flat = plane_geometry(vp, kSize, kSize, flat_plane());
    const DenoiseGeometry stepped = plane_geometry(vp, kSize, kSize, stepped_plane());
    std::mt19937 rng(12);
    const DenoiseImage current = random_image(rng, 0.0, 1.0), history = random_image(rng, 0.0, 1.0);
    for (int way = 0; way < 2; ++way) {
        CAPTURE(way);
        const DenoiseGeometry& before = way == 0 ? flat : stepped;
        const DenoiseGeometry& after = way == 0 ? stepped : flat;
        const auto out =
            run_temporal(current, after, before, history, constant_moments(0.5, 0.3, 5.0), vp, test_options());
        int wrong = 0;
        for (int y = 0; y < int(kSize); ++y) {
            for (int x = 0; x < int(kSize); ++x) {
                const bool disoccluded = x >= 32;
                const double n = out.moments.at(x, y)[2];
                wrong += (disoccluded ? n != 1.0 : n != 6.0) ? 1 : 0;
                if (disoccluded) {
                    // A restart: the current value alone, variance 0.
                    CHECK(out.accumulated.at(x, y)[0] == doctest::Approx(current.at(x, y)[0]));
                    CHECK(out.accumulated.at(x, y)[3] == 0.0);
                }
            }
        }
        CHECK(wrong == 0);
    }
}

TEST_CASE("denoise temporal: against the double reference on a moving camera over a step") {
    const double shift = 1.3;  // pixels: fractional bilinear weights
    const float t = float(shift * 2.0 / kSize * 5.0 * std::tan(glm::radians(22.5)));
    const glm::mat4 previous_vp = denoise_camera({0, 0, 0}, kSize, kSize);
    const glm::mat4 vp = denoise_camera({t, 0.5f * t, 0}, kSize, kSize);
    const DenoiseGeometry previous = plane_geometry(previous_vp, kSize, kSize, stepped_plane());
    const DenoiseGeometry current = plane_geometry(vp, kSize, kSize, stepped_plane());
    std::mt19937 rng(13);
    const DenoiseImage in = random_image(rng, 0.0, 2.0), history = random_image(rng, 0.0, 2.0);
    // History lengths constant on each surface: a bilinear mean of different lengths can land on
    // x.5, where float and double may round n apart.
    DenoiseImage moments(kSize, kSize);
    for (int y = 0; y < int(kSize); ++y)
        for (int x = 0; x < int(kSize); ++x) moments.at(x, y) = {0.7, 0.9, x >= 32 ? 12.0 : 5.0, 0.0};
    const stages::DenoiseOptions options = test_options();
    const auto out = run_temporal(in, current, previous, history, moments, previous_vp, options);
    const auto expected = reference::temporal_accumulate(in, current, previous, history, moments,
                                                         parameters_of(options, previous_vp, true));
    CHECK(max_relative_error(out.accumulated, expected.accumulated, 1.0) < 1e-4);
    CHECK(max_relative_error(out.moments, expected.moments, 1.0) < 1e-4);
}

TEST_CASE("denoise temporal: error against the exact mean falls like 1 over sqrt(F) until the cap") {
    // Each frame: the exact value 1 plus uniform noise in [-1, 1] (sigma 1 / sqrt(3)) per channel.
    // A running mean of F frames has RMSE sigma / sqrt(F); past the cap N, alpha stays 1 / N and
    // the RMSE settles at sigma sqrt(alpha / (2 - alpha)) (an exponential moving average). The
    // camera is static, so the cap asked for here is static_max_history (by default there is none:
    // the next case).
    // 12288 values per frame: each measured RMSE is within 0.5% (1 sigma) of its expectation, so
    // the slope's tolerance of 0.03 and the levels' 4% are several sigma wide.
    Context& ctx = context();
    const glm::mat4 vp = denoise_camera({0, 0, 0}, kSize, kSize);
    const DenoiseGeometry geometry = plane_geometry(vp, kSize, kSize, flat_plane());
    const double sigma = 1.0 / std::sqrt(3.0);
    for (uint32_t cap : {32u, 4u}) {
        CAPTURE(cap);
        stages::DenoiseOptions options = test_options();
        options.max_history = cap;
        options.static_max_history = cap;
        auto position = upload_image(ctx, geometry.position, "position");
        auto normal = upload_image(ctx, geometry.normal, "normal");
        HistorySlots slots = history_slots(ctx);
        std::mt19937 rng(100 + cap);
        const int frames = cap == 32 ? 16 : 40;
        std::vector<double> log_f, log_rmse;
        double last_rmse = 0.0;
        for (int f = 1; f <= frames; ++f) {
            HistorySlot& previous = slots[(f + 1) % 2];
            HistorySlot& next = slots[f % 2];
            auto in = upload_image(ctx, random_image(rng, 0.0, 2.0), "irradiance");
            PassList passes("accumulate");
            stages::add_temporal_accumulate_pass(ctx, passes, in, position, normal,
                                                 {previous.position, previous.normal, previous.color, previous.moments},
                                                 {next.position, next.normal, next.color, next.moments}, next.color,
                                                 next.moments, vp, f > 1, options);
            passes.run(ctx);
            const DenoiseImage out = download_image(next.color);
            double sum2 = 0.0;
            for (const auto& t : out.texels)
                for (int c = 0; c < 3; ++c) sum2 += (t[c] - 1.0) * (t[c] - 1.0);
            last_rmse = std::sqrt(sum2 / (3.0 * out.texels.size()));
            if (f <= int(cap)) {
                CAPTURE(f);
                CHECK(last_rmse * std::sqrt(double(f)) / sigma == doctest::Approx(1.0).epsilon(0.04));
                log_f.push_back(std::log(double(f)));
                log_rmse.push_back(std::log(last_rmse));
            }
        }
        if (cap == 32) {
            // Least-squares slope of log RMSE over log F, F = 1..16.
            double mx = 0, my = 0;
            for (size_t i = 0; i < log_f.size(); ++i) mx += log_f[i], my += log_rmse[i];
            mx /= log_f.size(), my /= log_f.size();
            double sxy = 0, sxx = 0;
            for (size_t i = 0; i < log_f.size(); ++i)
                sxy += (log_f[i] - mx) * (log_rmse[i] - my), sxx += (log_f[i] - mx) * (log_f[i] - mx);
            MESSAGE("slope of log RMSE over log F (1..16): " << sxy / sxx);
            CHECK(sxy / sxx == doctest::Approx(-0.5).epsilon(0.06));
        } else {
            const double alpha = 1.0 / cap;
            MESSAGE("RMSE after 40 frames at cap 4: " << last_rmse
                                                      << " (EMA: " << sigma * std::sqrt(alpha / (2 - alpha)) << ")");
            CHECK(last_rmse == doctest::Approx(sigma * std::sqrt(alpha / (2.0 - alpha))).epsilon(0.04));
        }
    }
}

TEST_CASE("denoise temporal: no ghost of the old surface after a disocclusion") {
    // Six frames see a closer face (x >= 32, z = -3) of radiance 5; then it is gone and the back
    // plane (exact value 1, noise +-1) shows. In the k-th frame after, the revealed pixels must hold
    // a running mean of k frames of the plane: their mean error within 4 sigma / sqrt(k n) of 0
    // (n = 1024 pixels x 3 channels: a ghost of 4 / k would be hundreds of sigma away).
    Context& ctx = context();
    const glm::mat4 vp = denoise_camera({0, 0, 0}, kSize, kSize);
    const DenoiseGeometry flat = plane_geometry(vp, kSize, kSize, flat_plane());
    const DenoiseGeometry stepped = plane_geometry(vp, kSize, kSize, stepped_plane());
    const stages::DenoiseOptions options = test_options();
    HistorySlots slots = history_slots(ctx);
    std::mt19937 rng(31);
    const double sigma = 1.0 / std::sqrt(3.0);
    for (int f = 1; f <= 10; ++f) {
        const bool revealed = f > 6;
        const DenoiseGeometry& g = revealed ? flat : stepped;
        DenoiseImage frame = random_image(rng, 0.0, 2.0);
        if (!revealed)
            for (int y = 0; y < int(kSize); ++y)
                for (int x = 32; x < int(kSize); ++x) frame.at(x, y) = {5.0, 5.0, 5.0, 0.0};
        auto in = upload_image(ctx, frame, "irradiance");
        auto position = upload_image(ctx, g.position, "position");
        auto normal = upload_image(ctx, g.normal, "normal");
        HistorySlot& previous = slots[(f + 1) % 2];
        HistorySlot& next = slots[f % 2];
        PassList passes("ghosting");
        stages::add_temporal_accumulate_pass(
            ctx, passes, in, position, normal, {previous.position, previous.normal, previous.color, previous.moments},
            {next.position, next.normal, next.color, next.moments}, next.color, next.moments, vp, f > 1, options);
        passes.run(ctx);
        if (!revealed) continue;
        const int k = f - 6;
        const DenoiseImage out = download_image(next.color);
        double sum = 0.0;
        int count = 0;
        for (int y = 0; y < int(kSize); ++y)
            for (int x = 32; x < int(kSize); ++x)
                for (int c = 0; c < 3; ++c, ++count) sum += out.at(x, y)[c] - 1.0;
        const double bound = 4.0 * sigma / std::sqrt(double(k) * count);
        CAPTURE(k);
        MESSAGE("mean error in the revealed region, frame " << k << " after: " << sum / count << " (bound " << bound
                                                            << ")");
        CHECK(std::abs(sum / count) < bound);
    }
}

TEST_CASE("denoise temporal: a static camera's accumulation is the exact running mean past the moving cap") {
    // 64 frames of noise on a static camera with the default options (max_history 32 for a moving
    // one): every pixel must hold the plain mean of its 64 inputs, computed here in double, and
    // n = 64. A cap of 32 would leave the first frames weighted (31/32)^32 ~ 0.36 of 1/32 each:
    // off by ~0.1 here. Float: 64 rounded mixes of O(1) values, a few 1e-7 each: checked at 2e-5.
    Context& ctx = context();
    const glm::mat4 vp = denoise_camera({0, 0, 0}, kSize, kSize);
    const DenoiseGeometry geometry = plane_geometry(vp, kSize, kSize, stepped_plane());
    const stages::DenoiseOptions options = test_options();
    auto position = upload_image(ctx, geometry.position, "position");
    auto normal = upload_image(ctx, geometry.normal, "normal");
    HistorySlots slots = history_slots(ctx);
    std::mt19937 rng(64);
    constexpr int kFrames = 64;
    std::vector<double> mean(std::size_t(kSize) * kSize * 3, 0.0);
    for (int f = 1; f <= kFrames; ++f) {
        const DenoiseImage frame = random_image(rng, 0.0, 2.0);
        for (std::size_t i = 0; i < frame.texels.size(); ++i)
            for (int c = 0; c < 3; ++c) mean[i * 3 + c] += frame.texels[i][c] / kFrames;
        auto in = upload_image(ctx, frame, "irradiance");
        HistorySlot& previous = slots[(f + 1) % 2];
        HistorySlot& next = slots[f % 2];
        PassList passes("static accumulation");
        stages::add_temporal_accumulate_pass(
            ctx, passes, in, position, normal, {previous.position, previous.normal, previous.color, previous.moments},
            {next.position, next.normal, next.color, next.moments}, next.color, next.moments, vp, f > 1, options);
        passes.run(ctx);
    }
    const DenoiseImage out = download_image(slots[kFrames % 2].color);
    const DenoiseImage moments = download_image(slots[kFrames % 2].moments);
    double worst = 0.0;
    int wrong_count = 0;
    for (std::size_t i = 0; i < out.texels.size(); ++i) {
        wrong_count += moments.texels[i][2] == double(kFrames) ? 0 : 1;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(out.texels[i][c] - mean[i * 3 + c]));
    }
    MESSAGE("largest difference from the 64 frames' mean: " << worst);
    CHECK(wrong_count == 0);
    CHECK(worst < 2e-5);
}

TEST_CASE("denoise temporal: a static pixel against the double reference, and the moving cap still holds") {
    // One pass with history length 40 everywhere: a static camera gives n = 41 (no cap), a camera
    // moved by 1.3 pixels gives the moving cap, 32; both against the reference.
    std::mt19937 rng(65);
    const DenoiseImage in = random_image(rng, 0.0, 2.0), history = random_image(rng, 0.0, 2.0);
    const DenoiseImage moments = constant_moments(0.7, 0.9, 40.0);
    const stages::DenoiseOptions options = test_options();
    const glm::mat4 vp = denoise_camera({0, 0, 0}, kSize, kSize);
    const DenoiseGeometry still = plane_geometry(vp, kSize, kSize, flat_plane());
    const auto out = run_temporal(in, still, still, history, moments, vp, options);
    const auto expected =
        reference::temporal_accumulate(in, still, still, history, moments, parameters_of(options, vp, true));
    CHECK(max_relative_error(out.accumulated, expected.accumulated, 1.0) < 1e-4);
    CHECK(max_relative_error(out.moments, expected.moments, 1.0) < 1e-4);
    CHECK(out.moments.at(20, 20)[2] == 41.0);
    const float t = float(1.3 * 2.0 / kSize * 5.0 * std::tan(glm::radians(22.5)));
    const glm::mat4 moved_vp = denoise_camera({t, 0, 0}, kSize, kSize);
    const DenoiseGeometry moved = plane_geometry(moved_vp, kSize, kSize, flat_plane());
    const auto out_moved = run_temporal(in, moved, still, history, moments, vp, options);
    const auto expected_moved =
        reference::temporal_accumulate(in, moved, still, history, moments, parameters_of(options, vp, true));
    CHECK(max_relative_error(out_moved.accumulated, expected_moved.accumulated, 1.0) < 1e-4);
    CHECK(out_moved.moments.at(20, 20)[2] == 32.0);
}
