// temporal_accumulate.comp with the G-buffer's motion: a panel sliding sideways in front of a
// still wall, seen by a still camera (and by a moving one). Each pixel must find its history where
// its point was (position + motion), never where the panel is now: the panel carries a ramp tied
// to the panel, so history found where the point was equals this frame's value exactly (bilinear
// taps of a ramp that is affine on the screen), and history from anywhere else differs by the
// slide (0.1 m of a 0.8 m ramp of 0.5: 0.0625). Against the double reference
// (tests/reference/denoise_reference.cpp) fed with the previous positions, every pixel; and the
// camera-only reprojection (no motion) fails the same check, so the check can fail.

#include "denoise_setup.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/denoise.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/mat4x4.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

using namespace vplkit;
using namespace vplkit::test;

namespace {

constexpr uint32_t kSize = 64;
constexpr float kWallZ = -5.0f, kPanelZ = -3.0f;
constexpr double kPanelWidth = 0.8, kPanelHalfHeight = 0.5;
constexpr double kSlide = 0.1;          // metres per frame along +x: 2.6 pixels at the panel's depth
constexpr double kWallHistory = 100.0;  // far outside the panel's values: a wall tap shows at once

// Where the panel's left edge is in frame `f` (0: the previous frame, 1: this one).
double panel_left(int f) {
    return -0.5 + kSlide * f;
}

// The panel's irradiance: a ramp along the panel, 0.2 at its left edge to 0.7 at its right (each
// channel scaled, so a colour mix-up shows too).
reference::Texel4 panel_color(double x_on_panel) {
    const double r = 0.2 + 0.5 * x_on_panel / kPanelWidth;
    return {r, 0.8 * r, 0.6 * r, 0.0};
}

struct Frame {
    DenoiseGeometry geometry;
    DenoiseImage motion;  // previous position - position
    DenoiseImage color;   // the panel's ramp, the wall's constant
    std::vector<bool> panel;
};

// Frame f seen through `view_projection`: the panel over the wall, its colour, and its motion
// (-kSlide along x on the panel for f = 1; 0 on the wall and in frame 0).
Frame frame_of(int f, const glm::mat4& view_projection, double wall_value) {
    const DenoiseGeometry at_panel_depth = plane_geometry(
        view_projection, kSize, kSize, {[](int, int) { return kPanelZ; }, [](int, int) { return glm::vec3(0, 0, 1); }});
    Frame out;
    out.panel.assign(kSize * kSize, false);
    for (int y = 0; y < int(kSize); ++y) {
        for (int x = 0; x < int(kSize); ++x) {
            const auto& p = at_panel_depth.position.at(x, y);
            const double u = p[0] - panel_left(f);
            out.panel[y * kSize + x] = u >= 0.0 && u <= kPanelWidth && std::abs(p[1]) <= kPanelHalfHeight;
        }
    }
    const std::vector<bool> panel = out.panel;
    out.geometry = plane_geometry(view_projection, kSize, kSize,
                                  {[panel](int x, int y) { return panel[y * kSize + x] ? kPanelZ : kWallZ; },
                                   [](int, int) { return glm::vec3(0, 0, 1); }});
    out.motion = DenoiseImage(kSize, kSize);
    out.color = DenoiseImage(kSize, kSize);
    for (int y = 0; y < int(kSize); ++y) {
        for (int x = 0; x < int(kSize); ++x) {
            const bool on_panel = out.panel[y * kSize + x];
            const double px = out.geometry.position.at(x, y)[0];
            out.color.at(x, y) =
                on_panel ? panel_color(px - panel_left(f)) : reference::Texel4{wall_value, wall_value, wall_value, 0.0};
            if (on_panel && f == 1) out.motion.at(x, y) = {-kSlide, 0.0, 0.0, 0.0};
        }
    }
    out.motion = to_float_precision(out.motion);
    out.color = to_float_precision(out.color);
    return out;
}

stages::DenoiseOptions test_options() {
    stages::DenoiseOptions options;
    options.scene_scale = 10.0f;  // max plane distance 0.1: the panel (2 m in front) is another surface
    return options;
}

struct Result {
    reference::TemporalResult gpu, reference;
};

// One temporal pass of `now` over the history `before` (n = 3 everywhere), with the motion or
// without it (the camera alone), on the GPU and in the reference.
Result accumulate(const Frame& before, const Frame& now, const glm::mat4& previous_vp, bool with_motion) {
    Context& ctx = context();
    const stages::DenoiseOptions options = test_options();
    DenoiseImage moments(kSize, kSize);
    for (auto& t : moments.texels) t = {0.5, 0.3, 3.0, 0.0};
    auto in = upload_image(ctx, now.color, "irradiance");
    auto position = upload_image(ctx, now.geometry.position, "position");
    auto normal = upload_image(ctx, now.geometry.normal, "normal");
    auto motion = upload_image(ctx, now.motion, "motion");
    auto prev_position = upload_image(ctx, before.geometry.position, "previous position");
    auto prev_normal = upload_image(ctx, before.geometry.normal, "previous normal");
    auto prev_color = upload_image(ctx, before.color, "previous color");
    auto prev_moments = upload_image(ctx, moments, "previous moments");
    auto next_position = float4_image(ctx, kSize, kSize, "next position");
    auto next_normal = float4_image(ctx, kSize, kSize, "next normal");
    auto accumulated = float4_image(ctx, kSize, kSize, "accumulated");
    auto out_moments = float4_image(ctx, kSize, kSize, "moments");
    PassList passes("motion reprojection test");
    stages::add_temporal_accumulate_pass(ctx, passes, in, position, normal,
                                         {prev_position, prev_normal, prev_color, prev_moments},
                                         {next_position, next_normal, {}, {}}, accumulated, out_moments, previous_vp,
                                         true, options, with_motion ? ImageView(motion) : ImageView{});
    passes.run(ctx);

    // The reference reprojects each pixel's previous position: position + motion.
    DenoiseGeometry was = now.geometry;
    if (with_motion) {
        for (size_t i = 0; i < was.position.texels.size(); ++i) {
            for (int c = 0; c < 3; ++c) {
                was.position.texels[i][c] = double(float(was.position.texels[i][c]) + float(now.motion.texels[i][c]));
            }
        }
    }
    reference::TemporalParameters p;
    for (int i = 0; i < 16; ++i) p.previous_view_projection[i] = (&previous_vp[0][0])[i];
    p.max_plane_distance = double(options.max_plane_distance_fraction) * options.scene_scale;
    p.min_normal_cos = options.min_normal_cos;
    p.max_history = options.max_history;
    p.has_history = true;
    p.static_max_history = options.static_max_history;
    return {{download_image(accumulated), download_image(out_moments)},
            reference::temporal_accumulate(now.color, was, before.geometry, before.color, moments, p)};
}

// How far the panel's accumulated colour strays from this frame's (the ramp at the same panel
// point), over the panel's pixels whose previous position lies inside the panel's previous
// pixels with a margin of 2 (all four taps on the panel); and how many pixels were checked.
double panel_stray(const Frame& before, const Frame& now, const reference::TemporalResult& out,
                   const glm::mat4& previous_vp, int& checked) {
    std::array<double, 16> vp{};
    for (int i = 0; i < 16; ++i) vp[i] = (&previous_vp[0][0])[i];
    double worst = 0.0;
    checked = 0;
    for (int y = 0; y < int(kSize); ++y) {
        for (int x = 0; x < int(kSize); ++x) {
            if (!now.panel[y * kSize + x]) continue;
            const auto& p = now.geometry.position.at(x, y);
            double px = 0.0, py = 0.0;
            if (!reference::reproject(vp, {p[0] - kSlide, p[1], p[2]}, kSize, kSize, px, py)) continue;
            bool inside = true;
            for (int dy = -2; dy <= 2; ++dy) {
                for (int dx = -2; dx <= 2; ++dx) {
                    const int qx = int(std::floor(px)) + dx, qy = int(std::floor(py)) + dy;
                    inside = inside && qx >= 0 && qy >= 0 && qx < int(kSize) && qy < int(kSize) &&
                             before.panel[qy * kSize + qx];
                }
            }
            if (!inside) continue;
            ++checked;
            for (int c = 0; c < 3; ++c) {
                worst = std::max(worst, std::abs(out.accumulated.at(x, y)[c] - now.color.at(x, y)[c]));
            }
        }
    }
    return worst;
}

void check_against_reference(const Result& r) {
    double worst = 0.0;
    int count_mismatch = 0;
    for (int y = 0; y < int(kSize); ++y) {
        for (int x = 0; x < int(kSize); ++x) {
            for (int c = 0; c < 3; ++c) {
                const double e = r.reference.accumulated.at(x, y)[c];
                worst = std::max(worst, std::abs(r.gpu.accumulated.at(x, y)[c] - e) / (std::abs(e) + 1.0));
            }
            count_mismatch += r.gpu.moments.at(x, y)[2] != r.reference.moments.at(x, y)[2] ? 1 : 0;
        }
    }
    CHECK(worst < 1e-4);
    CHECK(count_mismatch == 0);
}

}  // namespace

TEST_CASE("denoise motion: a sliding panel's history is found where it was, exactly, against the reference") {
    const glm::mat4 vp = denoise_camera({0, 0, 0}, kSize, kSize);
    const Frame before = frame_of(0, vp, kWallHistory), now = frame_of(1, vp, 0.05);
    const Result moving = accumulate(before, now, vp, true);
    check_against_reference(moving);

    // The panel's interior: its own history, at the same panel point (the ramp's value now).
    int checked = 0;
    const double stray = panel_stray(before, now, moving.gpu, vp, checked);
    CHECK(checked > 200);
    CHECK(stray < 1e-4);
    // No panel pixel takes anything from the wall (whose history is 100), and every one has history.
    int panel_pixels = 0;
    for (int y = 0; y < int(kSize); ++y) {
        for (int x = 0; x < int(kSize); ++x) {
            if (!now.panel[y * kSize + x]) continue;
            ++panel_pixels;
            CAPTURE(x);
            CAPTURE(y);
            CHECK(moving.gpu.accumulated.at(x, y)[0] < 1.0);
            CHECK(moving.gpu.moments.at(x, y)[2] == 4.0);
        }
    }
    CHECK(panel_pixels > checked);
    // Uncovered wall (the panel was there, the wall is now): the history starts over (n = 1) with
    // this frame's value; the wall elsewhere keeps its own history.
    int uncovered = 0;
    for (int y = 0; y < int(kSize); ++y) {
        for (int x = 0; x < int(kSize); ++x) {
            if (now.panel[y * kSize + x]) continue;
            CAPTURE(x);
            CAPTURE(y);
            if (before.panel[y * kSize + x]) {
                ++uncovered;
                CHECK(moving.gpu.moments.at(x, y)[2] == 1.0);
                CHECK(std::abs(moving.gpu.accumulated.at(x, y)[0] - 0.05) < 1e-6);
            } else {
                CHECK(moving.gpu.moments.at(x, y)[2] == 4.0);
            }
        }
    }
    CHECK(uncovered >= 2 * 25);  // 2.6 pixel columns of the panel's ~26 rows

    // The camera alone: the panel's pixels take the panel's history at the same pixel, a point
    // 0.1 m further along its ramp, and the leading edge (wall before) starts over.
    const Result camera_only = accumulate(before, now, vp, false);
    check_against_reference(camera_only);
    int checked_camera_only = 0;
    const double stray_camera_only = panel_stray(before, now, camera_only.gpu, vp, checked_camera_only);
    MESSAGE("panel interior (" << checked << " pixels): largest stray " << stray << " with the motion, "
                               << stray_camera_only << " with the camera alone");
    CHECK(checked_camera_only == checked);
    CHECK(stray_camera_only > 0.03);  // 0.75 x 0.0625 on the red channel
}

TEST_CASE("denoise motion: with the camera moving too, the panel's point is found through both") {
    const glm::mat4 previous_vp = denoise_camera({-0.15f, 0.05f, 0.0f}, kSize, kSize);
    const glm::mat4 vp = denoise_camera({0, 0, 0}, kSize, kSize);
    const Frame before = frame_of(0, previous_vp, kWallHistory), now = frame_of(1, vp, 0.05);
    const Result moving = accumulate(before, now, previous_vp, true);
    check_against_reference(moving);
    int checked = 0;
    CHECK(panel_stray(before, now, moving.gpu, previous_vp, checked) < 1e-4);
    CHECK(checked > 200);
    const Result camera_only = accumulate(before, now, previous_vp, false);
    int checked_camera_only = 0;
    CHECK(panel_stray(before, now, camera_only.gpu, previous_vp, checked_camera_only) > 0.03);
}
