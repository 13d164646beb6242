#pragma once
// The text of `vplkit bench` plots: a 5x8 pixel bitmap font for printable ASCII (32..126), drawn
// for vplkit (plot_font.cpp holds the glyphs as pictures), so a plot needs no font file.

#include <array>
#include <cstdint>

namespace vplkit::cli::font {

inline constexpr uint32_t glyph_width = 5;   // columns of a glyph's picture
inline constexpr uint32_t glyph_height = 8;  // rows: 0..6 down to the baseline, 7 the descender
inline constexpr uint32_t advance = 6;       // cell width: the glyph and one blank column
inline constexpr uint32_t line_height = 10;  // cell height: the glyph and two blank rows
inline constexpr char first = ' ';
inline constexpr char last = '~';

// One row per entry, top to bottom; bit (glyph_width - 1 - column) set is ink at that column.
using Glyph = std::array<uint8_t, glyph_height>;

// The picture of `c`; a character outside first..last gets the picture of '?'.
const Glyph& glyph(char c);

}  // namespace vplkit::cli::font
