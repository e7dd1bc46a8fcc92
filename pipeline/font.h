// A built-in 5x7 bitmap font for the labels of contact sheets and strips: printable ASCII plus
// the Greek alpha, drawn at an integer scale. No font files, no system dependency, and the same
// pixels everywhere.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "render/image.h"

namespace shatter {

struct Rgb {
    uint8_t r = 0, g = 0, b = 0;
};

inline constexpr int kGlyphWidth = 5;    // (unit: font pixels)
inline constexpr int kGlyphHeight = 7;   // (unit: font pixels)
inline constexpr int kGlyphAdvance = 6;  // (unit: font pixels) glyph plus one column of space

// The next code point of UTF-8 `s` from byte `i` (advanced past it); malformed bytes give U+FFFD,
// one byte at a time.
char32_t next_code_point(std::string_view s, size_t& i);

// The 7 rows of a code point's glyph, top first, bit 4 = leftmost column. Characters the font
// lacks get a hollow box.
const uint8_t* glyph_rows(char32_t code_point);

// Width in image pixels of `utf8` drawn at `scale` (no trailing space column).
int text_width(std::string_view utf8, int scale);

// Draws `utf8` with its top-left corner at (x, y), clipped to the image.
void draw_text(Image& image, int x, int y, std::string_view utf8, int scale, Rgb colour);

}  // namespace shatter
