#pragma once
// Plots for `vplkit bench`, drawn by vplkit itself into RGBA8 pictures (there is no plotting
// library among the packages vplkit may use): several series of (x, y) points on linear or
// logarithmic axes, with ticks at 1-2-5 steps (powers of ten on log axes), a title, axis labels,
// a legend and ringed points (e.g. a Pareto front). Text uses the bitmap font of plot_font.hpp at
// twice its size.
//
// Points that cannot be placed (NaN or infinite coordinates, zero or negative ones on a log axis)
// are skipped: the line of their series breaks there. A plot without any point that can be placed
// still draws its axes, and says "no data".

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vplkit::cli {

struct Rgb {
    uint8_t r = 0, g = 0, b = 0;
    friend bool operator==(const Rgb&, const Rgb&) = default;
};

struct Series {
    std::string name;          // its legend entry
    std::vector<double> x, y;  // the same length (render_plot throws vplkit::Error otherwise)
    bool lines = true;         // join consecutive points
    bool markers = true;       // a filled marker at each point
};

// A point of a plot: `index` into series[series].x and .y.
struct PointRef {
    size_t series = 0;
    size_t index = 0;
    friend bool operator==(const PointRef&, const PointRef&) = default;
};

struct PlotSpec {
    std::string title, x_label, y_label;  // the y label is written above the y axis, horizontally
    bool log_x = false, log_y = false;
    std::vector<Series> series;
    std::vector<PointRef> highlight;  // drawn ringed; references to missing points are ignored
    std::string highlight_label;      // the rings' legend entry ("Pareto front"); empty: none
    uint32_t width = 960, height = 600;
};

// Series i's colour: the Okabe-Ito palette (safe for colour-blind readers) without its yellow,
// which is hard to see on white, repeated after 7 series. Markers also change shape, every 4.
Rgb series_colour(size_t i);

// The points no other point beats on both coordinates, smaller being better on each (error
// against frame time): among all series, the points (x, y) for which no other point has x' <= x
// and y' <= y with one of them strictly smaller. Points with a NaN or infinite coordinate take no
// part. Sorted by x. Equal points are all on the front.
std::vector<PointRef> pareto_front(const std::vector<Series>& series);

// Tick values: multiples of the smallest step 1, 2 or 5 x 10^k that leaves at most `max_ticks`
// multiples in [lo, hi]. Empty unless lo < hi, both finite.
std::vector<double> linear_ticks(double lo, double hi, size_t max_ticks = 8);
// For a log axis: the powers of ten in [lo, hi] (every 2nd, 3rd, ... when more than 8); with
// fewer than three of those, the 1, 2 and 5 multiples of powers of ten in [lo, hi]; with still
// fewer than two, linear_ticks. Empty unless 0 < lo < hi, both finite.
std::vector<double> log_ticks(double lo, double hi);
// A tick label: `value` with as many decimals as `step` needs ("0.25", "100", "-3"); values from
// 10^6 up or below 10^-3 in mantissa-exponent form ("2e6", "1e-5"). Zero is "0".
std::string format_tick(double value, double step);

// The data-to-pixel mapping of a plot, and where its parts go.
struct AxisRange {
    double lo = 0, hi = 1;  // the axis' ends, in data units (both > 0 on a log axis)
    bool log = false;
};
struct PixelRect {
    int left = 0, top = 0, right = 0, bottom = 0;  // pixel centres on the plot area's frame
};

class PlotAxes {
public:
    // The ranges of the spec's points that can be placed, padded by 5% of their span on each side
    // (of their decades on a log axis, whose ends then move out to the next 1-2-5 value); a
    // single value, or all equal, gets a range around it. Without data: 0..1, or 1..10 when log.
    // The plot area leaves room for the title, the labels and the tick labels.
    static PlotAxes fit(const PlotSpec& spec);

    // Whether a point can be placed: finite, and positive on a log axis.
    bool placeable(double x, double y) const;
    // Pixel coordinates (x right, y down; a pixel's centre at integer values) of a placeable
    // point. The axis' lo is at area.left / area.bottom, hi at area.right / area.top.
    struct Pixel {
        double x = 0, y = 0;
    };
    Pixel to_pixel(double x, double y) const;

    AxisRange x, y;
    PixelRect area;
    std::vector<double> x_ticks, y_ticks;
};

// An RGBA8 picture, rows top to bottom, every alpha 255.
class Canvas {
public:
    Canvas(uint32_t width, uint32_t height, Rgb background);
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    Rgb pixel(uint32_t x, uint32_t y) const;
    // Pixels outside the canvas are not drawn (no error).
    void set(int x, int y, Rgb colour);
    void fill_rect(int x0, int y0, int x1, int y1, Rgb colour);  // inclusive corners
    // A Bresenham line `thickness` pixels wide (a square brush), from centre to centre.
    void line(int x0, int y0, int x1, int y1, Rgb colour, int thickness = 1);
    const std::vector<uint8_t>& rgba() const { return rgba_; }
    std::vector<uint8_t> take_rgba() { return std::move(rgba_); }

private:
    uint32_t width_, height_;
    std::vector<uint8_t> rgba_;
};

// Text in the font of plot_font.hpp, each pixel of a glyph a `scale` x `scale` square; (x, y) is
// the top left corner of the first character's cell. Characters outside ' '..'~' draw as '?'.
void draw_text(Canvas& canvas, int x, int y, std::string_view text, Rgb colour, int scale = 2);
// The width of `text`'s cells: text.size() * font::advance * scale (the last one's blank column included).
int text_width(std::string_view text, int scale = 2);

// The plot as RGBA8, spec.width * spec.height * 4 bytes, rows top to bottom.
std::vector<uint8_t> render_plot(const PlotSpec& spec);
// render_plot written as a PNG (vplkit::write_png: a failure leaves no partial file).
void write_plot_png(const std::filesystem::path& path, const PlotSpec& spec);

}  // namespace vplkit::cli
