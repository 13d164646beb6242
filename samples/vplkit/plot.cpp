// Plots for `vplkit bench` (plot.hpp). The picture is drawn back to front: grid, frame and ticks,
// every series' lines, then every series' markers (so no line hides a point), the rings, the
// legend, and the text around the plot area.

#include "plot.hpp"

#include "plot_font.hpp"
#include "vplkit/error.hpp"
#include "vplkit/image_io.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace vplkit::cli {
namespace {

constexpr int text_scale = 2;
constexpr int text_height = int(font::glyph_height) * text_scale;
// Capitals and digits stand on rows 0..6: that is the height to centre on a tick.
constexpr int cap_height = (int(font::glyph_height) - 1) * text_scale;
constexpr int line_spacing = int(font::line_height) * text_scale;

constexpr int margin = 12;      // between the picture's edge and anything drawn
constexpr int tick_length = 6;  // outward from the frame
constexpr int label_gap = 4;    // between a tick and its label
constexpr int marker_radius = 4;
constexpr int ring_inner = 7, ring_outer = 9;

constexpr Rgb white{255, 255, 255};
constexpr Rgb ink{20, 20, 20};
constexpr Rgb frame_colour{90, 90, 90};
constexpr Rgb grid_colour{228, 228, 228};
constexpr Rgb minor_grid_colour{243, 243, 243};
constexpr Rgb legend_border{160, 160, 160};
constexpr Rgb faint_text{130, 130, 130};

// Okabe & Ito, "Color Universal Design" (2008): blue, vermillion, bluish green, reddish purple,
// orange, sky blue, black (yellow left out: too faint on white).
constexpr std::array<Rgb, 7> palette{{
    {0, 114, 178},
    {213, 94, 0},
    {0, 158, 115},
    {204, 121, 167},
    {230, 159, 0},
    {86, 180, 233},
    {0, 0, 0},
}};

enum class Shape { circle, square, diamond, triangle };
Shape series_shape(size_t i) {
    return Shape(i % 4);
}

bool finite(double v) {
    return std::isfinite(v);
}

// A 1-2-5 value: multiplier 1, 2 or 5, times 10^exponent.
double nice_value(int multiplier, int exponent) {
    return multiplier * std::pow(10.0, exponent);
}

// The largest 1-2-5 value <= v (v > 0), and the smallest >= v. The tolerance keeps a value that is
// a 1-2-5 value up to rounding where it is.
double nice_floor(double v) {
    const int e = int(std::floor(std::log10(v)));
    const double m = v / std::pow(10.0, e);
    for (int multiplier : {10, 5, 2, 1}) {
        if (m >= multiplier * (1 - 1e-9)) return nice_value(multiplier, e);
    }
    return nice_value(5, e - 1);  // m just under 1 by rounding of log10
}
double nice_ceil(double v) {
    const int e = int(std::floor(std::log10(v)));
    const double m = v / std::pow(10.0, e);
    for (int multiplier : {1, 2, 5, 10}) {
        if (m <= multiplier * (1 + 1e-9)) return nice_value(multiplier, e);
    }
    return nice_value(2, e + 1);  // m just over 10 by rounding of log10
}

// The span of the placeable values of one axis.
struct Extent {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -std::numeric_limits<double>::infinity();
    bool empty() const { return lo > hi; }
    void add(double v) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
};

AxisRange fit_linear(const Extent& extent) {
    if (extent.empty()) return {0.0, 1.0, false};
    double lo = extent.lo, hi = extent.hi;
    const double span = hi - lo;
    if (!(span > 1e-12 * std::max(std::abs(lo), std::abs(hi)))) {
        // One value (or all equal): 10% of it on either side; 1 around zero.
        const double half = lo != 0 ? std::abs(lo) * 0.1 : 1.0;
        return {lo - half, hi + half, false};
    }
    const double padded_lo = lo - 0.05 * span, padded_hi = hi + 0.05 * span;
    if (finite(padded_lo) && finite(padded_hi)) return {padded_lo, padded_hi, false};
    return {lo, hi, false};  // padding would overflow
}

AxisRange fit_log(const Extent& extent) {
    if (extent.empty()) return {1.0, 10.0, true};
    const double l0 = std::log10(extent.lo), l1 = std::log10(extent.hi);
    const double pad = l1 - l0 > 1e-12 ? 0.05 * (l1 - l0) : 0.05;  // decades
    double lo = nice_floor(std::pow(10.0, l0 - pad));
    double hi = nice_ceil(std::pow(10.0, l1 + pad));
    // Near the ends of double's range the padding or snapping may not be representable.
    if (!(lo > 0) || !finite(lo)) lo = extent.lo;
    if (!finite(hi)) hi = extent.hi;
    if (!(hi > lo)) {
        lo = extent.lo * 0.5;
        hi = extent.hi * 2.0;
    }
    return {lo, hi, true};
}

// Axis position in 0..1 (lo..hi) of a placeable value.
double axis_fraction(const AxisRange& axis, double v) {
    if (axis.log) return (std::log10(v) - std::log10(axis.lo)) / (std::log10(axis.hi) - std::log10(axis.lo));
    return (v - axis.lo) / (axis.hi - axis.lo);
}

bool placeable_on(const AxisRange& axis, double v) {
    return finite(v) && (!axis.log || v > 0);
}

std::vector<double> ticks_for(const AxisRange& axis) {
    return axis.log ? log_ticks(axis.lo, axis.hi) : linear_ticks(axis.lo, axis.hi);
}

// The step a tick label is formatted with: the tick spacing of a linear axis; on a log axis each
// value is its own step (1000 needs no decimals, 0.02 needs two).
double label_step(const AxisRange& axis, const std::vector<double>& ticks, size_t i) {
    if (axis.log) return ticks[i];
    return ticks.size() > 1 ? ticks[1] - ticks[0] : std::abs(ticks[i]);
}

// Minor grid lines on a log axis: when its ticks are all powers of ten (not its 2 and 5
// multiples), over few enough decades that 8 lines per decade stay apart.
bool minor_grid_helps(const AxisRange& axis, const std::vector<double>& ticks) {
    if (ticks.size() < 2 || std::log10(axis.hi / axis.lo) > 6) return false;
    return std::all_of(ticks.begin(), ticks.end(), [](double t) {
        const double e = std::log10(t);
        return std::abs(e - std::round(e)) < 1e-9;
    });
}

int to_int(double pixel) {
    return int(std::lround(std::clamp(pixel, -1e6, 1e6)));
}

void draw_marker(Canvas& canvas, int cx, int cy, Shape shape, Rgb colour) {
    const int r = marker_radius;
    for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
            bool inside = false;
            switch (shape) {
                case Shape::circle:
                    inside = dx * dx + dy * dy <= r * r + r;
                    break;
                case Shape::square:
                    inside = std::abs(dx) <= r - 1 && std::abs(dy) <= r - 1;
                    break;
                case Shape::diamond:
                    inside = std::abs(dx) + std::abs(dy) <= r + 1;
                    break;
                // Apex at the top, base on the bottom row: the half width grows by one every row.
                case Shape::triangle:
                    inside = 2 * std::abs(dx) <= dy + r + 1;
                    break;
            }
            if (inside) canvas.set(cx + dx, cy + dy, colour);
        }
    }
}

void draw_ring(Canvas& canvas, int cx, int cy, Rgb colour) {
    for (int dy = -ring_outer; dy <= ring_outer; ++dy) {
        for (int dx = -ring_outer; dx <= ring_outer; ++dx) {
            const int d2 = dx * dx + dy * dy;
            if (d2 >= ring_inner * ring_inner && d2 <= ring_outer * ring_outer) canvas.set(cx + dx, cy + dy, colour);
        }
    }
}

void draw_rect_outline(Canvas& canvas, int x0, int y0, int x1, int y1, Rgb colour) {
    canvas.line(x0, y0, x1, y0, colour);
    canvas.line(x0, y1, x1, y1, colour);
    canvas.line(x0, y0, x0, y1, colour);
    canvas.line(x1, y0, x1, y1, colour);
}

std::string legend_name(const PlotSpec& spec, size_t i) {
    return spec.series[i].name.empty() ? "series " + std::to_string(i + 1) : spec.series[i].name;
}

void check_spec(const PlotSpec& spec) {
    if (spec.width == 0 || spec.height == 0) {
        throw Error("plot '" + spec.title + "': the picture must be at least 1x1 pixels, got " +
                    std::to_string(spec.width) + "x" + std::to_string(spec.height));
    }
    for (const Series& s : spec.series) {
        if (s.x.size() != s.y.size()) {
            throw Error("plot '" + spec.title + "': series '" + s.name + "' has " + std::to_string(s.x.size()) +
                        " x values and " + std::to_string(s.y.size()) + " y values");
        }
    }
}

// The legend: one row per series (a sample of its line and marker, then its name), and one for
// the rings when they have a label. It goes in the corner of the plot area that hides the fewest
// points and line pieces (top right on a tie).
void draw_legend(Canvas& canvas, const PlotSpec& spec, const PlotAxes& axes) {
    const bool ring_row = !spec.highlight.empty() && !spec.highlight_label.empty();
    const size_t rows = spec.series.size() + (ring_row ? 1 : 0);
    if (rows == 0) return;
    constexpr int padding = 8, sample_width = 28;
    int name_width = ring_row ? text_width(spec.highlight_label) : 0;
    for (size_t i = 0; i < spec.series.size(); ++i) name_width = std::max(name_width, text_width(legend_name(spec, i)));
    const int box_width = padding + sample_width + padding + name_width + padding;
    const int box_height = int(rows) * line_spacing + padding;

    // What each corner would hide: markers, and 8 samples along each line piece.
    std::vector<PlotAxes::Pixel> covered;
    for (const Series& s : spec.series) {
        bool previous = false;
        PlotAxes::Pixel last{};
        for (size_t j = 0; j < s.x.size(); ++j) {
            if (!axes.placeable(s.x[j], s.y[j])) {
                previous = false;
                continue;
            }
            const PlotAxes::Pixel p = axes.to_pixel(s.x[j], s.y[j]);
            covered.push_back(p);
            if (previous && s.lines) {
                for (int k = 1; k < 8; ++k) {
                    const double t = k / 8.0;
                    covered.push_back({last.x + t * (p.x - last.x), last.y + t * (p.y - last.y)});
                }
            }
            previous = true;
            last = p;
        }
    }
    const int inset = 10;
    const int left = axes.area.left + inset, right = axes.area.right - inset - box_width;
    const int top = axes.area.top + inset, bottom = axes.area.bottom - inset - box_height;
    const std::array<std::array<int, 2>, 4> corners{{{right, top}, {left, top}, {right, bottom}, {left, bottom}}};
    size_t best = 0, best_hidden = std::numeric_limits<size_t>::max();
    for (size_t c = 0; c < corners.size(); ++c) {
        const int x0 = corners[c][0] - marker_radius, y0 = corners[c][1] - marker_radius;
        const int x1 = corners[c][0] + box_width + marker_radius, y1 = corners[c][1] + box_height + marker_radius;
        const size_t hidden = size_t(std::count_if(covered.begin(), covered.end(), [&](const PlotAxes::Pixel& p) {
            return p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1;
        }));
        if (hidden < best_hidden) {
            best = c;
            best_hidden = hidden;
        }
    }
    const int x0 = std::max(corners[best][0], axes.area.left + 1), y0 = std::max(corners[best][1], axes.area.top + 1);

    canvas.fill_rect(x0, y0, x0 + box_width, y0 + box_height, white);
    draw_rect_outline(canvas, x0, y0, x0 + box_width, y0 + box_height, legend_border);
    for (size_t row = 0; row < rows; ++row) {
        const int row_top = y0 + padding / 2 + int(row) * line_spacing + (line_spacing - cap_height) / 2;
        const int mid_y = row_top + cap_height / 2;
        const int sample_x0 = x0 + padding, sample_x1 = sample_x0 + sample_width;
        const int mid_x = (sample_x0 + sample_x1) / 2;
        if (row < spec.series.size()) {
            const Series& s = spec.series[row];
            const Rgb colour = series_colour(row);
            if (s.lines) canvas.line(sample_x0, mid_y, sample_x1, mid_y, colour, 2);
            if (s.markers || !s.lines) draw_marker(canvas, mid_x, mid_y, series_shape(row), colour);
            draw_text(canvas, sample_x1 + padding, row_top, legend_name(spec, row), ink);
        } else {
            draw_ring(canvas, mid_x, mid_y, ink);
            draw_text(canvas, sample_x1 + padding, row_top, spec.highlight_label, ink);
        }
    }
}

}  // namespace

Rgb series_colour(size_t i) {
    return palette[i % palette.size()];
}

std::vector<PointRef> pareto_front(const std::vector<Series>& series) {
    struct Point {
        double x, y;
        PointRef ref;
    };
    std::vector<Point> points;
    for (size_t s = 0; s < series.size(); ++s) {
        const size_t n = std::min(series[s].x.size(), series[s].y.size());
        for (size_t i = 0; i < n; ++i) {
            if (finite(series[s].x[i]) && finite(series[s].y[i]))
                points.push_back({series[s].x[i], series[s].y[i], {s, i}});
        }
    }
    // By x, then y: a point is on the front when its y is below every y met before it at a smaller
    // x, or equals the best y among points of the same x (equal points all stay).
    std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) {
        if (a.x != b.x) return a.x < b.x;
        if (a.y != b.y) return a.y < b.y;
        return a.ref.series != b.ref.series ? a.ref.series < b.ref.series : a.ref.index < b.ref.index;
    });
    std::vector<PointRef> front;
    double best_y = std::numeric_limits<double>::infinity();  // best y at a smaller x
    for (size_t i = 0; i < points.size();) {
        size_t end = i;  // points[i, end) share one x; the first has the smallest y
        while (end < points.size() && points[end].x == points[i].x) ++end;
        const double group_y = points[i].y;
        if (group_y < best_y) {
            for (size_t j = i; j < end && points[j].y == group_y; ++j) front.push_back(points[j].ref);
            best_y = group_y;
        }
        i = end;
    }
    return front;
}

std::vector<double> linear_ticks(double lo, double hi, size_t max_ticks) {
    if (!(lo < hi) || !finite(lo) || !finite(hi) || !finite(hi - lo) || max_ticks == 0) return {};
    const double span = hi - lo;
    constexpr double tolerance = 1e-9;  // a tick at an end of the range, up to rounding, is in it
    const int e0 = int(std::floor(std::log10(span / double(max_ticks)))) - 1;
    for (int e = e0; e < e0 + 4; ++e) {
        for (int multiplier : {1, 2, 5}) {
            const double step = nice_value(multiplier, e);
            const double first = std::ceil(lo / step - tolerance), last = std::floor(hi / step + tolerance);
            if (last - first + 1 > double(max_ticks)) continue;
            std::vector<double> ticks;
            for (double k = first; k <= last; ++k) ticks.push_back(k == 0 ? 0.0 : k * step);
            return ticks;
        }
    }
    return {};  // not reached: a step of 10^(e0 + 2) leaves at most one tick
}

std::vector<double> log_ticks(double lo, double hi) {
    if (!(lo > 0) || !(lo < hi) || !finite(hi)) return {};
    const auto in_range = [&](double v) { return v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9); };
    const int e_lo = int(std::floor(std::log10(lo))), e_hi = int(std::ceil(std::log10(hi)));
    std::vector<double> powers;
    for (int e = e_lo; e <= e_hi; ++e) {
        if (in_range(nice_value(1, e))) powers.push_back(nice_value(1, e));
    }
    if (powers.size() >= 3) {
        // Many decades: every 2nd, 3rd, ... power so that at most 8 are labelled.
        const size_t stride = (powers.size() + 7) / 8;
        std::vector<double> ticks;
        for (size_t i = 0; i < powers.size(); i += stride) ticks.push_back(powers[i]);
        return ticks;
    }
    std::vector<double> ticks;
    for (int e = e_lo; e <= e_hi; ++e) {
        for (int multiplier : {1, 2, 5}) {
            if (in_range(nice_value(multiplier, e))) ticks.push_back(nice_value(multiplier, e));
        }
    }
    if (ticks.size() >= 2) return ticks;
    return linear_ticks(lo, hi);
}

std::string format_tick(double value, double step) {
    step = std::abs(step);
    if (!finite(value)) return value != value ? "nan" : value > 0 ? "inf" : "-inf";
    if (value == 0 || (step > 0 && std::abs(value) < step * 1e-6)) return "0";
    if (!(step > 0) || !finite(step)) step = std::abs(value);
    char text[64];
    const double magnitude = std::abs(value);
    if (magnitude >= 1e6 || magnitude < 1e-3) {
        int e = int(std::floor(std::log10(magnitude)));
        // The mantissa needs the digits of the step below the value's leading digit.
        const int decimals = std::clamp(e - int(std::floor(std::log10(step) + 1e-9)), 0, 6);
        double mantissa = value / std::pow(10.0, e);
        std::snprintf(text, sizeof text, "%.*f", decimals, mantissa);
        if (std::abs(std::strtod(text, nullptr)) >= 10) {  // rounded up to the next power of ten
            ++e;
            mantissa = value / std::pow(10.0, e);
            std::snprintf(text, sizeof text, "%.*f", decimals, mantissa);
        }
        return std::string(text) + "e" + std::to_string(e);
    }
    // As many decimals as the step has: the fewest that write it as a whole number of units.
    int decimals = 0;
    while (decimals < 9) {
        const double scaled = step * std::pow(10.0, decimals);
        if (std::abs(scaled - std::round(scaled)) <= 1e-6 * scaled) break;
        ++decimals;
    }
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

PlotAxes PlotAxes::fit(const PlotSpec& spec) {
    PlotAxes axes;
    axes.x.log = spec.log_x;
    axes.y.log = spec.log_y;
    Extent x_extent, y_extent;
    for (const Series& s : spec.series) {
        const size_t n = std::min(s.x.size(), s.y.size());
        for (size_t i = 0; i < n; ++i) {
            if (!axes.placeable(s.x[i], s.y[i])) continue;
            x_extent.add(s.x[i]);
            y_extent.add(s.y[i]);
        }
    }
    axes.x = spec.log_x ? fit_log(x_extent) : fit_linear(x_extent);
    axes.y = spec.log_y ? fit_log(y_extent) : fit_linear(y_extent);
    axes.x_ticks = ticks_for(axes.x);
    axes.y_ticks = ticks_for(axes.y);

    int y_label_width = 0;
    for (size_t i = 0; i < axes.y_ticks.size(); ++i) {
        y_label_width =
            std::max(y_label_width, text_width(format_tick(axes.y_ticks[i], label_step(axes.y, axes.y_ticks, i))));
    }
    int last_x_label_width = 0;
    if (!axes.x_ticks.empty()) {
        const size_t i = axes.x_ticks.size() - 1;
        last_x_label_width = text_width(format_tick(axes.x_ticks[i], label_step(axes.x, axes.x_ticks, i)));
    }
    int top = margin;
    if (!spec.title.empty()) top += line_spacing + 4;
    if (!spec.y_label.empty()) top += line_spacing;
    top += cap_height / 2 + 8;  // the top tick's label is centred on it, below the y label
    const int left = margin + y_label_width + label_gap + tick_length;
    const int right = int(spec.width) - 1 - margin - std::max(8, last_x_label_width / 2);
    int bottom = int(spec.height) - 1 - margin - (tick_length + label_gap + text_height);
    if (!spec.x_label.empty()) bottom -= line_spacing;
    // A picture too small for its text keeps a plot area of at least one pixel.
    axes.area = {left, top, std::max(right, left + 1), std::max(bottom, top + 1)};
    return axes;
}

bool PlotAxes::placeable(double px, double py) const {
    return placeable_on(x, px) && placeable_on(y, py);
}

PlotAxes::Pixel PlotAxes::to_pixel(double px, double py) const {
    return {area.left + axis_fraction(x, px) * (area.right - area.left),
            area.bottom - axis_fraction(y, py) * (area.bottom - area.top)};
}

std::vector<uint8_t> render_plot(const PlotSpec& spec) {
    check_spec(spec);
    const PlotAxes axes = PlotAxes::fit(spec);
    const PixelRect& area = axes.area;
    Canvas canvas(spec.width, spec.height, white);

    // Grid and ticks. A log axis labelled at powers of ten only gets unlabelled lines at their
    // 2..9 multiples too, fainter, to read values between the decades by.
    for (const auto* axis : {&axes.x, &axes.y}) {
        const std::vector<double>& ticks = axis == &axes.x ? axes.x_ticks : axes.y_ticks;
        if (!axis->log || !minor_grid_helps(*axis, ticks)) continue;
        for (int e = int(std::floor(std::log10(axis->lo))); e < int(std::ceil(std::log10(axis->hi))); ++e) {
            for (int multiplier = 2; multiplier <= 9; ++multiplier) {
                const double v = nice_value(multiplier, e);
                if (v <= axis->lo || v >= axis->hi) continue;
                if (axis == &axes.x) {
                    const int px = to_int(axes.to_pixel(v, axes.y.lo).x);
                    canvas.line(px, area.top, px, area.bottom, minor_grid_colour);
                } else {
                    const int py = to_int(axes.to_pixel(axes.x.lo, v).y);
                    canvas.line(area.left, py, area.right, py, minor_grid_colour);
                }
            }
        }
    }
    for (size_t i = 0; i < axes.x_ticks.size(); ++i) {
        const int px = to_int(axes.to_pixel(axes.x_ticks[i], axes.y.lo).x);
        canvas.line(px, area.top, px, area.bottom, grid_colour);
        canvas.line(px, area.bottom, px, area.bottom + tick_length, frame_colour);
        const std::string label = format_tick(axes.x_ticks[i], label_step(axes.x, axes.x_ticks, i));
        draw_text(canvas, px - text_width(label) / 2 + text_scale / 2, area.bottom + tick_length + label_gap, label,
                  ink);
    }
    for (size_t i = 0; i < axes.y_ticks.size(); ++i) {
        const int py = to_int(axes.to_pixel(axes.x.lo, axes.y_ticks[i]).y);
        canvas.line(area.left, py, area.right, py, grid_colour);
        canvas.line(area.left - tick_length, py, area.left, py, frame_colour);
        const std::string label = format_tick(axes.y_ticks[i], label_step(axes.y, axes.y_ticks, i));
        // Right-aligned; the blank column ending the last cell is not part of the label.
        draw_text(canvas, area.left - tick_length - label_gap - text_width(label) + text_scale, py - cap_height / 2,
                  label, ink);
    }
    draw_rect_outline(canvas, area.left, area.top, area.right, area.bottom, frame_colour);

    // Series: all lines first, then all markers.
    size_t placed = 0;
    for (size_t s = 0; s < spec.series.size(); ++s) {
        const Series& series = spec.series[s];
        if (!series.lines) continue;
        bool previous = false;
        int last_x = 0, last_y = 0;
        for (size_t i = 0; i < series.x.size(); ++i) {
            if (!axes.placeable(series.x[i], series.y[i])) {
                previous = false;  // the line breaks at a point that cannot be drawn
                continue;
            }
            const PlotAxes::Pixel p = axes.to_pixel(series.x[i], series.y[i]);
            const int px = to_int(p.x), py = to_int(p.y);
            if (previous) canvas.line(last_x, last_y, px, py, series_colour(s), 2);
            previous = true;
            last_x = px;
            last_y = py;
        }
    }
    for (size_t s = 0; s < spec.series.size(); ++s) {
        const Series& series = spec.series[s];
        for (size_t i = 0; i < series.x.size(); ++i) {
            if (!axes.placeable(series.x[i], series.y[i])) continue;
            ++placed;
            // A series drawn without lines or markers would be invisible: it gets markers.
            if (!series.markers && series.lines) continue;
            const PlotAxes::Pixel p = axes.to_pixel(series.x[i], series.y[i]);
            draw_marker(canvas, to_int(p.x), to_int(p.y), series_shape(s), series_colour(s));
        }
    }
    for (const PointRef& ref : spec.highlight) {
        if (ref.series >= spec.series.size() || ref.index >= spec.series[ref.series].x.size()) continue;
        const double hx = spec.series[ref.series].x[ref.index], hy = spec.series[ref.series].y[ref.index];
        if (!axes.placeable(hx, hy)) continue;
        const PlotAxes::Pixel p = axes.to_pixel(hx, hy);
        draw_ring(canvas, to_int(p.x), to_int(p.y), ink);
    }
    if (placed == 0) {
        const std::string no_data = "no data";
        draw_text(canvas, (area.left + area.right - text_width(no_data)) / 2, (area.top + area.bottom - cap_height) / 2,
                  no_data, faint_text);
    }
    draw_legend(canvas, spec, axes);

    // Text around the plot area.
    int y = margin;
    if (!spec.title.empty()) {
        draw_text(canvas, (int(spec.width) - text_width(spec.title)) / 2, y, spec.title, ink);
        y += line_spacing + 4;
    }
    if (!spec.y_label.empty()) draw_text(canvas, margin, y, spec.y_label, ink);
    if (!spec.x_label.empty()) {
        draw_text(canvas, (area.left + area.right - text_width(spec.x_label)) / 2,
                  area.bottom + tick_length + label_gap + line_spacing + 2, spec.x_label, ink);
    }
    return canvas.take_rgba();
}

void write_plot_png(const std::filesystem::path& path, const PlotSpec& spec) {
    write_png(path, spec.width, spec.height, render_plot(spec));
}

}  // namespace vplkit::cli
