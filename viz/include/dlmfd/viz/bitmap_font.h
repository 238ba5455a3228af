// A tiny built-in bitmap font (5 x 7 pixels per glyph, one column of space between glyphs) for the
// labels of pictures: digits, signs, Latin letters and a few punctuation marks. Any other
// character is drawn as a hollow box so that a missing glyph is visible, not silently dropped.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace dlmfd {

inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphHeight = 7;
inline constexpr int kGlyphAdvance = kGlyphWidth + 1;

// Row r (0 = top) of the glyph; bit 4 is the leftmost column.
using Glyph = std::array<std::uint8_t, kGlyphHeight>;
const Glyph& GlyphFor(char c);
// Width in font pixels of `text` (without the trailing space column).
int TextWidth(const std::string& text);

}  // namespace dlmfd
