// The plots' raster (plot.hpp): Canvas, an RGBA picture with clipped pixels, rectangles and
// thick lines (Bresenham), and text in plot_font.hpp's bitmap font. plot.cpp draws the plots on it.

#include "plot.hpp"

#include "plot_font.hpp"

#include <algorithm>
#include <cstdlib>

namespace vplkit::cli {

Canvas::Canvas(uint32_t width, uint32_t height, Rgb background)
    : width_(width), height_(height), rgba_(size_t(width) * height * 4) {
    for (size_t i = 0; i < rgba_.size(); i += 4) {
        rgba_[i + 0] = background.r;
        rgba_[i + 1] = background.g;
        rgba_[i + 2] = background.b;
        rgba_[i + 3] = 255;
    }
}

Rgb Canvas::pixel(uint32_t x, uint32_t y) const {
    const size_t i = (size_t(y) * width_ + x) * 4;
    return {rgba_[i], rgba_[i + 1], rgba_[i + 2]};
}

void Canvas::set(int x, int y, Rgb colour) {
    if (x < 0 || y < 0 || uint32_t(x) >= width_ || uint32_t(y) >= height_) return;
    const size_t i = (size_t(y) * width_ + uint32_t(x)) * 4;
    rgba_[i + 0] = colour.r;
    rgba_[i + 1] = colour.g;
    rgba_[i + 2] = colour.b;
}

void Canvas::fill_rect(int x0, int y0, int x1, int y1, Rgb colour) {
    for (int y = std::max(std::min(y0, y1), 0); y <= std::min(std::max(y0, y1), int(height_) - 1); ++y) {
        for (int x = std::max(std::min(x0, x1), 0); x <= std::min(std::max(x0, x1), int(width_) - 1); ++x)
            set(x, y, colour);
    }
}

void Canvas::line(int x0, int y0, int x1, int y1, Rgb colour, int thickness) {
    const int below = (thickness - 1) / 2, above = thickness / 2;  // brush offsets
    const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
    const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int error = dx + dy;
    for (;;) {
        fill_rect(x0 - below, y0 - below, x0 + above, y0 + above, colour);
        if (x0 == x1 && y0 == y1) break;
        const int e2 = 2 * error;
        if (e2 >= dy) {
            error += dy;
            x0 += sx;
        }
        if (e2 <= dx) {
            error += dx;
            y0 += sy;
        }
    }
}

void draw_text(Canvas& canvas, int x, int y, std::string_view text, Rgb colour, int scale) {
    for (size_t i = 0; i < text.size(); ++i) {
        const font::Glyph& glyph = font::glyph(text[i]);
        const int cell_x = x + int(i) * int(font::advance) * scale;
        for (uint32_t row = 0; row < font::glyph_height; ++row) {
            for (uint32_t column = 0; column < font::glyph_width; ++column) {
                if (!(glyph[row] >> (font::glyph_width - 1 - column) & 1u)) continue;
                const int px = cell_x + int(column) * scale, py = y + int(row) * scale;
                canvas.fill_rect(px, py, px + scale - 1, py + scale - 1, colour);
            }
        }
    }
}

int text_width(std::string_view text, int scale) {
    return int(text.size()) * int(font::advance) * scale;
}

}  // namespace vplkit::cli
