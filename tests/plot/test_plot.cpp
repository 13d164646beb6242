// The plots of `vplkit bench` (samples/vplkit/plot.hpp) and their bitmap font: picture size and
// background, where points land on linear and log axes, tick values and labels, ranges of one
// value, values that cannot be drawn, rings, the Pareto front, and the font's glyphs. Example
// plots go to the build folder (VPLKIT_PLOT_OUT_DIR) for a person to look at.

#include "plot.hpp"
#include "plot_font.hpp"

#include "vplkit/error.hpp"
#include "vplkit/image_io.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <set>
#include <string>
#include <vector>

using namespace vplkit::cli;

// Failed colour checks print the colours.
template <>
struct doctest::StringMaker<Rgb> {
    static doctest::String convert(const Rgb& c) {
        return ("rgb(" + std::to_string(c.r) + ", " + std::to_string(c.g) + ", " + std::to_string(c.b) + ")").c_str();
    }
};

namespace {

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();
constexpr double infinity = std::numeric_limits<double>::infinity();
constexpr Rgb white{255, 255, 255};
constexpr Rgb ink{20, 20, 20};            // plot.cpp's text and ring colour
constexpr Rgb faint_text{130, 130, 130};  // plot.cpp's "no data"

Rgb pixel_at(const std::vector<uint8_t>& rgba, uint32_t width, int x, int y) {
    const size_t i = (size_t(y) * width + size_t(x)) * 4;
    return {rgba[i], rgba[i + 1], rgba[i + 2]};
}

Rgb pixel_at(const std::vector<uint8_t>& rgba, uint32_t width, PlotAxes::Pixel p) {
    return pixel_at(rgba, width, int(std::lround(p.x)), int(std::lround(p.y)));
}

size_t count_colour(const std::vector<uint8_t>& rgba, uint32_t width, const PixelRect& r, Rgb colour) {
    size_t n = 0;
    for (int y = r.top; y <= r.bottom; ++y) {
        for (int x = r.left; x <= r.right; ++x) n += pixel_at(rgba, width, x, y) == colour ? 1 : 0;
    }
    return n;
}

void check_ticks(const std::vector<double>& ticks, const std::vector<double>& expected) {
    REQUIRE(ticks.size() == expected.size());
    for (size_t i = 0; i < ticks.size(); ++i) CHECK(ticks[i] == doctest::Approx(expected[i]).epsilon(1e-12));
}

std::filesystem::path out_dir() {
    return VPLKIT_PLOT_OUT_DIR;
}

}  // namespace

TEST_CASE("the picture has the requested size and a white background") {
    PlotSpec spec;
    spec.width = 640;
    spec.height = 400;
    const std::vector<uint8_t> rgba = render_plot(spec);
    REQUIRE(rgba.size() == size_t(640) * 400 * 4);
    for (size_t i = 3; i < rgba.size(); i += 4) REQUIRE(rgba[i] == 255);

    // Without series or text only the grid, the frame, the ticks and "no data" are drawn: a pixel
    // of the plot area off the grid lines and the "no data" text is white, and so is the margin.
    const PlotAxes axes = PlotAxes::fit(spec);
    std::set<int> grid_x, grid_y;
    for (double t : axes.x_ticks) grid_x.insert(int(std::lround(axes.to_pixel(t, axes.y.lo).x)));
    for (double t : axes.y_ticks) grid_y.insert(int(std::lround(axes.to_pixel(axes.x.lo, t).y)));
    const int text_x0 = (axes.area.left + axes.area.right - text_width("no data")) / 2;
    const int text_y0 = (axes.area.top + axes.area.bottom - 14) / 2;
    size_t checked = 0;
    for (int y = axes.area.top + 1; y < axes.area.bottom; ++y) {
        for (int x = axes.area.left + 1; x < axes.area.right; ++x) {
            if (grid_x.count(x) || grid_y.count(y)) continue;
            if (x >= text_x0 && x < text_x0 + text_width("no data") && y >= text_y0 && y < text_y0 + 16) continue;
            CAPTURE(x);
            CAPTURE(y);
            REQUIRE(pixel_at(rgba, 640, x, y) == white);
            ++checked;
        }
    }
    CHECK(checked > size_t(400) * 200);
    for (int y = 0; y < 400; ++y) {
        for (int x = 0; x < 640; ++x) {
            if (x < 10 || y < 10 || x >= 630 || y >= 390) REQUIRE(pixel_at(rgba, 640, x, y) == white);
        }
    }
    CHECK(count_colour(rgba, 640, axes.area, faint_text) > 0);  // "no data"

    // The default size, with data and text.
    PlotSpec full;
    full.title = "title";
    full.x_label = "x";
    full.y_label = "y";
    full.series.push_back({"a", {1, 2, 3}, {3, 1, 2}});
    const std::vector<uint8_t> full_rgba = render_plot(full);
    CHECK(full_rgba.size() == size_t(960) * 600 * 4);
    CHECK(count_colour(full_rgba, 960, PlotAxes::fit(full).area, faint_text) == 0);
    for (int x = 0; x < 960; ++x) CHECK(pixel_at(full_rgba, 960, x, 599) == white);
}

TEST_CASE("markers have their series' colour at their data position on linear axes") {
    PlotSpec spec;
    spec.series.push_back({"first", {0.0, 0.5, 1.0}, {0.0, 2.0, 1.0}, false, true});
    spec.series.push_back({"second", {0.25, 0.75}, {1.5, 0.5}, false, true});
    const PlotAxes axes = PlotAxes::fit(spec);
    // Padded by 5% of the span on each side.
    CHECK(axes.x.lo == doctest::Approx(-0.05));
    CHECK(axes.x.hi == doctest::Approx(1.05));
    CHECK(axes.y.lo == doctest::Approx(-0.1));
    CHECK(axes.y.hi == doctest::Approx(2.1));
    // The axis ends are the plot area's frame; the middle is in the middle.
    CHECK(axes.to_pixel(axes.x.lo, axes.y.lo).x == doctest::Approx(axes.area.left));
    CHECK(axes.to_pixel(axes.x.lo, axes.y.lo).y == doctest::Approx(axes.area.bottom));
    CHECK(axes.to_pixel(axes.x.hi, axes.y.hi).x == doctest::Approx(axes.area.right));
    CHECK(axes.to_pixel(axes.x.hi, axes.y.hi).y == doctest::Approx(axes.area.top));
    CHECK(axes.to_pixel(0.5, 1.0).x == doctest::Approx((axes.area.left + axes.area.right) / 2.0));
    CHECK(axes.to_pixel(0.5, 1.0).y == doctest::Approx((axes.area.top + axes.area.bottom) / 2.0));

    const std::vector<uint8_t> rgba = render_plot(spec);
    for (size_t s = 0; s < spec.series.size(); ++s) {
        for (size_t i = 0; i < spec.series[s].x.size(); ++i) {
            const PlotAxes::Pixel p = axes.to_pixel(spec.series[s].x[i], spec.series[s].y[i]);
            CAPTURE(s);
            CAPTURE(i);
            // The marker's centre and its 3x3 neighbourhood (inside both shapes).
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) CHECK(pixel_at(rgba, 960, {p.x + dx, p.y + dy}) == series_colour(s));
            }
        }
    }
    CHECK(series_colour(0) != series_colour(1));
    // Between the markers, without lines, the plot is white.
    CHECK(pixel_at(rgba, 960, axes.to_pixel(0.1, 1.9)) == white);
}

TEST_CASE("markers have their series' colour at their data position on log axes") {
    PlotSpec spec;
    spec.log_x = spec.log_y = true;
    spec.series.push_back({"log", {3.0, 30.0, 870.0}, {0.001, 0.05, 2.0}, false, true});
    const PlotAxes axes = PlotAxes::fit(spec);
    CHECK(axes.x.log);
    CHECK(axes.y.log);
    // A decade is the same length everywhere; the geometric mean of the ends is the middle.
    const double mid_x = std::sqrt(axes.x.lo * axes.x.hi), mid_y = std::sqrt(axes.y.lo * axes.y.hi);
    CHECK(axes.to_pixel(mid_x, mid_y).x == doctest::Approx((axes.area.left + axes.area.right) / 2.0));
    CHECK(axes.to_pixel(mid_x, mid_y).y == doctest::Approx((axes.area.top + axes.area.bottom) / 2.0));
    CHECK(axes.to_pixel(100, 1).x - axes.to_pixel(10, 1).x ==
          doctest::Approx(axes.to_pixel(1000, 1).x - axes.to_pixel(100, 1).x));

    const std::vector<uint8_t> rgba = render_plot(spec);
    for (size_t i = 0; i < 3; ++i) {
        CAPTURE(i);
        CHECK(pixel_at(rgba, 960, axes.to_pixel(spec.series[0].x[i], spec.series[0].y[i])) == series_colour(0));
    }
}

TEST_CASE("tick values are 1-2-5 steps and powers of ten") {
    check_ticks(linear_ticks(0, 1), {0, 0.2, 0.4, 0.6, 0.8, 1.0});
    check_ticks(linear_ticks(-0.05, 1.05), {0, 0.2, 0.4, 0.6, 0.8, 1.0});
    check_ticks(linear_ticks(0, 870), {0, 200, 400, 600, 800});
    check_ticks(linear_ticks(-3, 3), {-3, -2, -1, 0, 1, 2, 3});
    check_ticks(linear_ticks(0.0012, 0.0019), {0.0012, 0.0013, 0.0014, 0.0015, 0.0016, 0.0017, 0.0018, 0.0019});
    CHECK(linear_ticks(1, 1).empty());
    CHECK(linear_ticks(2, 1).empty());
    CHECK(linear_ticks(0, infinity).empty());
    CHECK(linear_ticks(not_a_number, 1).empty());
    for (double span : {1e-9, 0.3, 7.0, 123.0, 5e8}) {
        const std::vector<double> ticks = linear_ticks(1.0, 1.0 + span);
        CAPTURE(span);
        CHECK(ticks.size() >= 2);
        CHECK(ticks.size() <= 8);
    }

    check_ticks(log_ticks(1, 1000), {1, 10, 100, 1000});
    check_ticks(log_ticks(1, 100), {1, 10, 100});
    check_ticks(log_ticks(1, 50), {1, 2, 5, 10, 20, 50});  // two powers only: 2 and 5 multiples too
    check_ticks(log_ticks(3, 870), {5, 10, 20, 50, 100, 200, 500});
    check_ticks(log_ticks(2, 5), {2, 5});
    check_ticks(log_ticks(1e-6, 1e6), {1e-6, 1e-4, 1e-2, 1, 1e2, 1e4, 1e6});  // every second power
    CHECK(log_ticks(0, 10).empty());
    CHECK(log_ticks(-1, 10).empty());

    // A log axis over 3..870 reaches out to 1-2-5 values, and its ticks are 10, 100, 1000.
    PlotSpec spec;
    spec.log_x = true;
    spec.series.push_back({"s", {3.0, 870.0}, {1.0, 2.0}});
    const PlotAxes axes = PlotAxes::fit(spec);
    CHECK(axes.x.lo == doctest::Approx(2));
    CHECK(axes.x.hi == doctest::Approx(2000));
    check_ticks(axes.x_ticks, {10, 100, 1000});
    check_ticks(axes.y_ticks, {1.0, 1.2, 1.4, 1.6, 1.8, 2.0});
}

TEST_CASE("tick labels") {
    CHECK(format_tick(0.2, 0.2) == "0.2");
    CHECK(format_tick(0.0, 0.2) == "0");
    CHECK(format_tick(1e-17, 0.2) == "0");  // rounding residue of a zero tick
    CHECK(format_tick(1.0, 0.2) == "1.0");
    CHECK(format_tick(0.25, 0.05) == "0.25");
    CHECK(format_tick(-3, 1) == "-3");
    CHECK(format_tick(1000, 1000) == "1000");
    CHECK(format_tick(600, 200) == "600");
    CHECK(format_tick(0.0015, 0.0001) == "0.0015");
    CHECK(format_tick(1e-5, 1e-5) == "1e-5");
    CHECK(format_tick(2.5e-5, 5e-6) == "2.5e-5");
    CHECK(format_tick(1e6, 1e6) == "1e6");
    CHECK(format_tick(2e6, 1e6) == "2e6");
    CHECK(format_tick(-4e7, 2e7) == "-4e7");
}

TEST_CASE("a single point or equal values give a valid range") {
    for (bool log : {false, true}) {
        CAPTURE(log);
        for (const std::vector<double>& values : {std::vector<double>{3.0}, std::vector<double>{0.5, 0.5, 0.5}}) {
            PlotSpec spec;
            spec.log_x = spec.log_y = log;
            spec.series.push_back({"s", values, values});
            const PlotAxes axes = PlotAxes::fit(spec);
            CHECK(axes.x.lo < values[0]);
            CHECK(axes.x.hi > values[0]);
            CHECK(axes.y.lo < values[0]);
            CHECK(axes.y.hi > values[0]);
            CHECK(axes.x_ticks.size() >= 2);
            CHECK(axes.y_ticks.size() >= 2);
            const std::vector<uint8_t> rgba = render_plot(spec);
            CHECK(pixel_at(rgba, 960, axes.to_pixel(values[0], values[0])) == series_colour(0));
        }
    }
    // All zero on a linear axis: a range around zero.
    PlotSpec zeros;
    zeros.series.push_back({"zeros", {0, 0}, {0, 0}});
    const PlotAxes axes = PlotAxes::fit(zeros);
    CHECK(axes.x.lo < 0);
    CHECK(axes.x.hi > 0);
    CHECK(std::isfinite(axes.to_pixel(0, 0).x));
}

TEST_CASE("NaN and infinite values and non-positive values on log axes are skipped") {
    PlotSpec spec;
    spec.log_y = true;
    spec.series.push_back(
        {"mixed", {0, 1, 2, 3, 4, 5, not_a_number, 7}, {1, not_a_number, infinity, -infinity, -1, 0, 5, 10}});
    spec.highlight = {{0, 1}, {0, 4}, {0, 7}, {3, 0}, {0, 99}};  // skipped points, one drawable, bad references
    spec.highlight_label = "ringed";
    const PlotAxes axes = PlotAxes::fit(spec);
    CHECK_FALSE(axes.placeable(1, not_a_number));
    CHECK_FALSE(axes.placeable(2, infinity));
    CHECK_FALSE(axes.placeable(4, -1));
    CHECK_FALSE(axes.placeable(5, 0));
    CHECK_FALSE(axes.placeable(not_a_number, 5));
    CHECK(axes.placeable(-3, 5));  // negative x is fine on the linear x axis
    // The range comes from (0, 1) and (7, 10) only.
    CHECK(axes.x.lo == doctest::Approx(-0.35));
    CHECK(axes.x.hi == doctest::Approx(7.35));
    CHECK(axes.y.lo > 0);
    CHECK(axes.y.lo <= 1);
    CHECK(axes.y.hi >= 10);
    std::vector<uint8_t> rgba;
    CHECK_NOTHROW(rgba = render_plot(spec));
    CHECK(pixel_at(rgba, 960, axes.to_pixel(0, 1)) == series_colour(0));
    CHECK(pixel_at(rgba, 960, axes.to_pixel(7, 10)) == series_colour(0));

    // Nothing drawable at all: axes and "no data".
    for (bool log : {false, true}) {
        PlotSpec none;
        none.log_x = none.log_y = log;
        none.series.push_back({"nothing", {not_a_number, infinity, -1, 0}, {1, 2, not_a_number, -infinity}});
        const PlotAxes empty_axes = PlotAxes::fit(none);
        CHECK(empty_axes.x.lo < empty_axes.x.hi);
        CHECK(empty_axes.x_ticks.size() >= 2);
        CHECK_NOTHROW(rgba = render_plot(none));
        CHECK(count_colour(rgba, 960, empty_axes.area, faint_text) > 0);
    }
}

TEST_CASE("bad specs throw vplkit::Error") {
    PlotSpec spec;
    spec.series.push_back({"uneven", {1, 2, 3}, {1, 2}});
    CHECK_THROWS_AS(render_plot(spec), vplkit::Error);
    PlotSpec zero;
    zero.width = 0;
    CHECK_THROWS_AS(render_plot(zero), vplkit::Error);
}

TEST_CASE("a picture too small for its text still draws") {
    PlotSpec spec;
    spec.title = "a title much wider than the picture";
    spec.x_label = "x";
    spec.y_label = "y";
    spec.width = 24;
    spec.height = 16;
    spec.series.push_back({"s", {1, 2}, {3, 4}});
    spec.highlight = {{0, 0}};
    spec.highlight_label = "ring";
    std::vector<uint8_t> rgba;
    CHECK_NOTHROW(rgba = render_plot(spec));
    CHECK(rgba.size() == size_t(24) * 16 * 4);
    spec.width = spec.height = 1;
    CHECK_NOTHROW(rgba = render_plot(spec));
    CHECK(rgba.size() == 4);
}

TEST_CASE("highlighted points are ringed") {
    PlotSpec spec;
    // Points off the grid lines (ticks at multiples of 0.5), so that only the rings are near them.
    spec.series.push_back({"s", {0.1, 1.3, 2.1}, {2.1, 0.1, 1.3}, false, true});
    const PlotAxes axes = PlotAxes::fit(spec);
    const PlotAxes::Pixel p = axes.to_pixel(1.3, 0.1);
    const std::vector<uint8_t> plain = render_plot(spec);
    spec.highlight = {{0, 1}};
    REQUIRE(std::abs(axes.to_pixel(1.0, 0.0).y - p.y) > 9);  // the nearest grid lines are beyond the ring
    REQUIRE(std::abs(axes.to_pixel(1.5, 0.0).x - p.x) > 9);
    const std::vector<uint8_t> ringed = render_plot(spec);
    // Radius 8 lies on the ring (7..9), outside the marker (radius 4).
    for (const auto& [dx, dy] : {std::pair{8, 0}, std::pair{-8, 0}, std::pair{0, -8}, std::pair{0, 8}}) {
        CHECK(pixel_at(plain, 960, {p.x + dx, p.y + dy}) == white);
        CHECK(pixel_at(ringed, 960, {p.x + dx, p.y + dy}) == ink);
    }
    CHECK(pixel_at(ringed, 960, p) == series_colour(0));  // the marker stays visible inside
    const PlotAxes::Pixel q = axes.to_pixel(0.1, 2.1);
    CHECK(pixel_at(ringed, 960, {q.x + 8, q.y}) == white);  // not highlighted
}

TEST_CASE("the Pareto front is the points nothing beats on both coordinates") {
    std::vector<Series> series;
    series.push_back({"a", {1, 2, 4, not_a_number}, {5, 3, 1, 0}});
    series.push_back({"b", {1.5, 2, 3, 4}, {6, 2, 3, 1}});
    const std::vector<PointRef> front = pareto_front(series);
    // (2, 3) loses to (2, 2), (3, 3) to (2, 2), (1.5, 6) to (1, 5); (4, 1) twice: both stay.
    const std::vector<PointRef> expected{{0, 0}, {1, 1}, {0, 2}, {1, 3}};
    CHECK(front == expected);
    CHECK(pareto_front({}).empty());
}

TEST_CASE("every glyph renders inside its cell and differs from every other") {
    constexpr int scale = 2;
    const int cell_w = int(font::advance) * scale, cell_h = int(font::line_height) * scale;
    std::set<std::vector<uint8_t>> seen;
    for (int code = font::first; code <= font::last; ++code) {
        const char c = char(code);
        CAPTURE(c);
        // One cell in the middle of a 3x3-cell canvas: ink outside the cell's glyph box would show.
        Canvas canvas(uint32_t(cell_w * 3), uint32_t(cell_h * 3), white);
        draw_text(canvas, cell_w, cell_h, std::string(1, c), ink, scale);
        size_t inked = 0;
        std::vector<uint8_t> picture;
        for (uint32_t y = 0; y < canvas.height(); ++y) {
            for (uint32_t x = 0; x < canvas.width(); ++x) {
                const bool on = canvas.pixel(x, y) == ink;
                if (!on) {
                    REQUIRE(canvas.pixel(x, y) == white);
                    continue;
                }
                ++inked;
                const int gx = int(x) - cell_w, gy = int(y) - cell_h;
                REQUIRE(gx >= 0);
                REQUIRE(gy >= 0);
                REQUIRE(gx < int(font::glyph_width) * scale);  // the cell's last column stays blank
                REQUIRE(gy < int(font::glyph_height) * scale);
            }
        }
        for (uint32_t y = uint32_t(cell_h); y < uint32_t(2 * cell_h); ++y) {
            for (uint32_t x = uint32_t(cell_w); x < uint32_t(2 * cell_w); ++x)
                picture.push_back(canvas.pixel(x, y) == ink);
        }
        if (c == ' ') {
            CHECK(inked == 0);
        } else {
            CHECK(inked > 0);
        }
        CHECK(seen.insert(picture).second);  // no other glyph looked like this
    }
    CHECK(seen.size() == size_t(font::last - font::first + 1));
    // Outside printable ASCII: the question mark.
    CHECK(font::glyph('\n') == font::glyph('?'));
    CHECK(font::glyph(char(0xE9)) == font::glyph('?'));
    CHECK(font::glyph('\x7F') == font::glyph('?'));
}

TEST_CASE("text width is the number of characters times the advance") {
    CHECK(text_width("", 2) == 0);
    CHECK(text_width("a", 2) == int(font::advance) * 2);
    CHECK(text_width("rmse 0.25", 2) == 9 * int(font::advance) * 2);
    CHECK(text_width("abc", 3) == 3 * int(font::advance) * 3);
    // Drawn text stays within its width, and its characters sit one advance apart.
    const std::string text = "WMW";
    Canvas canvas(200, 40, white);
    draw_text(canvas, 10, 10, text, ink, 2);
    int rightmost = -1;
    for (uint32_t y = 0; y < canvas.height(); ++y) {
        for (uint32_t x = 0; x < canvas.width(); ++x) {
            if (canvas.pixel(x, y) == ink) rightmost = std::max(rightmost, int(x));
        }
    }
    // W's last column is ink; the blank column after it (2 pixels at scale 2) is not.
    CHECK(rightmost == 10 + text_width(text, 2) - 2 - 1);
    // The first and the third W are the same picture, two advances apart.
    const uint32_t two_advances = 2 * font::advance * 2;
    for (uint32_t y = 0; y < canvas.height(); ++y) {
        for (uint32_t x = 10; x < 10 + font::advance * 2; ++x)
            CHECK(canvas.pixel(x, y) == canvas.pixel(x + two_advances, y));
    }
}

TEST_CASE("example plots for a person to look at") {
    // Error against frame time, the shape `vplkit bench` draws: three methods, log-log, the
    // Pareto front of all of them ringed.
    PlotSpec spec;
    spec.title = "cornell, 1024x768: error against frame time";
    spec.x_label = "GI time per frame (ms)";
    spec.y_label = "relative RMSE of indirect light";
    spec.log_x = spec.log_y = true;
    spec.series.push_back({"sst", {2.1, 3.9, 7.6, 15.0, 29.8}, {0.31, 0.22, 0.16, 0.115, 0.082}});
    spec.series.push_back({"rtslc", {3.0, 5.2, 9.9, 19.5, 38.0}, {0.21, 0.15, 0.105, 0.074, 0.052}});
    spec.series.push_back({"hybrid", {2.6, 4.4, 8.1, 16.2, 31.0}, {0.24, 0.14, 0.098, 0.071, 0.055}});
    spec.series.push_back({"exact", {410.0}, {0.0}, false, true});  // zero on a log axis: skipped
    spec.highlight = pareto_front(spec.series);
    spec.highlight_label = "Pareto front";
    const std::filesystem::path path = out_dir() / "example_error_vs_time.png";
    write_plot_png(path, spec);
    const vplkit::PngImage image = vplkit::read_png(path);
    CHECK(image.width == 960);
    CHECK(image.height == 600);
    CHECK(image.rgba == render_plot(spec));
    MESSAGE("wrote " << path.string());

    // Linear axes: RMSE against block size.
    PlotSpec blocks;
    blocks.title = "rtslc: block size";
    blocks.x_label = "block size (pixels)";
    blocks.y_label = "RMSE";
    blocks.series.push_back({"rmse", {2, 4, 8, 16, 32}, {0.012, 0.0135, 0.016, 0.021, 0.029}});
    blocks.series.push_back({"rmse, interleaved", {2, 4, 8, 16, 32}, {0.0118, 0.0126, 0.0141, 0.017, 0.0215}});
    write_plot_png(out_dir() / "example_block_size.png", blocks);

    // The font, 32 characters a line, at scale 3.
    Canvas sheet(32 * font::advance * 3 + 24, 3 * font::line_height * 3 + 24, white);
    for (int code = font::first; code <= font::last; ++code) {
        const int i = code - font::first;
        draw_text(sheet, 12 + (i % 32) * int(font::advance) * 3, 12 + (i / 32) * int(font::line_height) * 3,
                  std::string(1, char(code)), ink, 3);
    }
    vplkit::write_png(out_dir() / "example_font.png", sheet.width(), sheet.height(), sheet.rgba());

    PlotSpec empty;
    empty.title = "no measurements";
    empty.x_label = "VPLs";
    empty.y_label = "build time (ms)";
    empty.log_x = true;
    write_plot_png(out_dir() / "example_empty.png", empty);
}
