// `vplkit view --screenshot` on lavapipe under xvfb-run: the window's image (not the renderer's
// buffer) comes back lit, at the window's size, the frame whole left of the panel's column; bad
// input fails before a window opens. Each case runs the program, with the validation layer on.

#include <doctest/doctest.h>

#include "vplkit/image_io.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <sys/wait.h>

namespace {

struct Run {
    int exit_code = -1;
    std::string output;
};

// Runs vplkit with `args` (already quoted), stdout and stderr together.
Run run_vplkit(const std::string& args, bool with_display = true) {
    std::string command = "VPLKIT_DEVICE=cpu ";
    // One virtual X server at a time: `xvfb-run -a` picks a free display number, and two
    // started at once can pick the same one.
    if (with_display) {
        command += "flock " + std::string(VPLKIT_VIEW_TEST_DIR) + "/xvfb.lock " + std::string(VPLKIT_XVFB_RUN) +
                   " -a -s '-screen 0 640x480x24' ";
    }
    command += std::string(VPLKIT_PROGRAM) + " " + args + " 2>&1";
    Run run;
    FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    char buffer[4096];
    while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) run.output.append(buffer, n);
    const int status = pclose(pipe);
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

std::string output_path(const std::string& name) {
    const std::filesystem::path path = std::filesystem::path(VPLKIT_VIEW_TEST_DIR) / name;
    std::filesystem::remove(path);
    return path.string();
}

double mean_of(const vplkit::PngImage& image, int channel) {
    double sum = 0.0;
    for (size_t i = size_t(channel); i < image.rgba.size(); i += 4) sum += image.rgba[i];
    return sum / double(image.width * image.height);
}

}  // namespace

TEST_CASE("view screenshot: the window shows the lit Cornell box") {
    const std::string png = output_path("cornell.png");
    const Run run = run_vplkit(
        "view --scene cornell --width 96 --height 72 --no-panel --frames 2 --validation "
        "--screenshot " +
        png);
    INFO(run.output);
    REQUIRE(run.exit_code == 0);
    CHECK(run.output.find("wrote " + png + " (96x72") != std::string::npos);
    const vplkit::PngImage image = vplkit::read_png(png);
    REQUIRE(image.width == 96);
    REQUIRE(image.height == 72);
    // Lit, and the box's walls: its left wall red, its right wall green (a black or a garbled
    // window fails one of these).
    const double luminance = (mean_of(image, 0) + mean_of(image, 1) + mean_of(image, 2)) / 3.0;
    CHECK(luminance > 40.0);
    auto at = [&](uint32_t x, uint32_t y, int c) { return int(image.rgba[(size_t(y) * image.width + x) * 4 + c]); };
    CHECK(at(22, 36, 0) > at(22, 36, 1) + 40);  // left wall: red
    CHECK(at(74, 36, 1) > at(74, 36, 0) + 40);  // right wall: green
}

// The mean absolute difference (0..255) of `a`'s pixels in the w x h rectangle at (ax, ay) and
// `b`'s at (bx, by), over R, G and B.
double region_difference(const vplkit::PngImage& a, uint32_t ax, uint32_t ay, const vplkit::PngImage& b, uint32_t bx,
                         uint32_t by, uint32_t w, uint32_t h) {
    double sum = 0.0;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            for (size_t c = 0; c < 3; ++c) {
                const size_t i = ((size_t(ay) + y) * a.width + ax + x) * 4 + c;
                const size_t j = ((size_t(by) + y) * b.width + bx + x) * 4 + c;
                sum += std::abs(int(a.rgba[i]) - int(b.rgba[j]));
            }
    return sum / double(w * h * 3);
}

// The mean of R, G and B (0..255) over the w x h rectangle at (x0, y0).
double region_luminance(const vplkit::PngImage& image, uint32_t x0, uint32_t y0, uint32_t w, uint32_t h) {
    double sum = 0.0;
    for (uint32_t y = y0; y < y0 + h; ++y)
        for (uint32_t x = x0; x < x0 + w; ++x)
            for (size_t c = 0; c < 3; ++c) sum += image.rgba[(size_t(y) * image.width + x) * 4 + c];
    return sum / double(w * h * 3);
}

TEST_CASE("view screenshot: the panel is docked right of the frame, which stays whole and lit") {
    const std::string plain = output_path("plain.png");
    const std::string docked = output_path("docked.png");
    const std::string common = "view --scene cornell --width 64 --height 48 --frames 1 --validation ";
    const Run without = run_vplkit(common + "--no-panel --screenshot " + plain);
    const Run with = run_vplkit(common + "--screenshot " + docked);
    INFO(without.output);
    INFO(with.output);
    REQUIRE(without.exit_code == 0);
    REQUIRE(with.exit_code == 0);
    const vplkit::PngImage a = vplkit::read_png(plain);
    const vplkit::PngImage b = vplkit::read_png(docked);
    // Without the panel the window is the frame; with it, the frame plus a 380-pixel column, at
    // least 480 high, the frame at its own size centred in the left part.
    REQUIRE(a.width == 64);
    REQUIRE(a.height == 48);
    REQUIRE(b.width == 64 + 380);
    REQUIRE(b.height == 480);
    CHECK(region_luminance(a, 0, 0, 64, 48) > 40.0);
    CHECK(region_difference(a, 0, 0, b, 0, (480 - 48) / 2, 64, 48) < 1.0);  // the same frame, uncovered
    // The column holds the panel: text and widgets, not one colour (the window's clear colour is
    // at its top left, above the frame).
    uint32_t drawn = 0;
    for (uint32_t y = 0; y < b.height; ++y)
        for (uint32_t x = 64; x < b.width; ++x) drawn += region_difference(b, x, y, b, 0, 0, 1, 1) > 30.0 ? 1 : 0;
    CHECK(drawn > (b.width - 64) * b.height / 50);
}

TEST_CASE("view screenshot: --window scales the frame into the window, left of the panel when it shows") {
    const std::string plain = output_path("scaled.png");
    const std::string panel = output_path("scaled-panel.png");
    const std::string common = "view --scene cornell --width 64 --height 48 --window 480x360 --frames 1 --validation ";
    const Run without = run_vplkit(common + "--no-panel --screenshot " + plain);
    const Run with = run_vplkit(common + "--screenshot " + panel);
    INFO(without.output);
    INFO(with.output);
    REQUIRE(without.exit_code == 0);
    REQUIRE(with.exit_code == 0);
    const vplkit::PngImage a = vplkit::read_png(plain);
    const vplkit::PngImage b = vplkit::read_png(panel);
    REQUIRE(a.width == 480);
    REQUIRE(a.height == 360);
    REQUIRE(b.width == 480);
    REQUIRE(b.height == 360);
    CHECK(region_luminance(a, 0, 0, 480, 360) > 40.0);  // scaled up to the whole window, still lit
    // With the panel the frame fits the 100 pixels left of the column: 100x75, centred.
    CHECK(region_luminance(b, 0, 143, 100, 74) > 40.0);
    CHECK(region_difference(a, 0, 0, b, 100, 0, 380, 360) > 10.0);  // the column is not the frame
}

// The number after "relative RMSE against the exact frame: " in the output, or -1.
double exact_error_in(const std::string& output) {
    const std::string label = "relative RMSE against the exact frame: ";
    const size_t at = output.find(label);
    return at == std::string::npos ? -1.0 : std::stod(output.substr(at + label.size()));
}

TEST_CASE("view --compare-exact: frames accumulated on a still camera come closer to the exact frame") {
    const std::string common =
        "view --scene cornell --width 64 --height 48 --method hybrid --denoise temporal "
        "--no-panel --compare-exact --validation --screenshot " +
        output_path("accumulated.png");
    const Run one = run_vplkit(common + " --frames 1");
    const Run many = run_vplkit(common + " --frames 16");
    INFO(one.output);
    INFO(many.output);
    REQUIRE(one.exit_code == 0);
    REQUIRE(many.exit_code == 0);
    const double first = exact_error_in(one.output);
    const double accumulated = exact_error_in(many.output);
    REQUIRE(first > 0.0);
    REQUIRE(accumulated > 0.0);
    // Measured 0.44 and 0.15 (lavapipe): the view's frame counter restarts only on a change.
    // Anti-aliasing is on (the default) but pauses while the exact frame is held: with the
    // jitter, at 64x48 the edges' difference from the pixel centres outweighed the noise (0.56
    // after 16 frames), and this check failed.
    CHECK(accumulated < 0.6 * first);
}

TEST_CASE("view: bad input fails before a window opens, with one clear line") {
    const Run jpeg = run_vplkit("view --screenshot shot.jpg", false);
    CHECK(jpeg.exit_code == 2);
    CHECK(jpeg.output.find("--screenshot expects a .png file name, got 'shot.jpg'") != std::string::npos);
    const Run folder = run_vplkit("view --screenshot /nonexistent-folder/shot.png", false);
    CHECK(folder.exit_code == 2);
    CHECK(folder.output.find("the folder /nonexistent-folder does not exist") != std::string::npos);
    const Run size = run_vplkit("view --window 320by240", false);
    CHECK(size.exit_code == 2);
    CHECK(size.output.find("--window expects WIDTHxHEIGHT, got '320by240'") != std::string::npos);
}

TEST_CASE("view: without a display it says so and exits 1") {
    const Run run = run_vplkit("view --frames 1", false);
    INFO(run.output);
    // Under a desktop session a display exists: nothing to check there.
    if (std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY")) return;
    CHECK(run.exit_code == 1);
    CHECK(run.output.find("view: cannot open a window") != std::string::npos);
}
