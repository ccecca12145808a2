// A built-in 5x7 bitmap font for printable ASCII, so figures need no font files or FreeType.
#pragma once

#include <string>
#include <vector>

namespace vaegail::plot {

// Cell geometry in font pixels: glyphs are kGlyphWidth wide with one blank column after each;
// capitals and digits fill rows [0, kCapHeight); descenders (g, j, p, q, y, comma) reach down
// to kCellHeight.
inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphAdvance = kGlyphWidth + 1;
inline constexpr int kCapHeight = 7;
inline constexpr int kCellHeight = 9;

// Rows of one glyph from the top, each kGlyphWidth characters of '#' (ink) or '.' (blank).
// Characters outside 32..126 get the glyph of '?'.
const std::vector<std::string>& glyph_rows(char c);

// Width in font pixels of a line of text: no trailing blank column.
int text_width(const std::string& text);

}  // namespace vaegail::plot
