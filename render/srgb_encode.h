// The one quantization of a frame: linear-light half floats, as read back from GL, to 8-bit sRGB
// (IEC 61966-2-1's piecewise curve, core/palette.h linear_to_srgb8), with GL's bottom-up rows
// turned top-down. A table of all 65,536 half-float values makes it exact, deterministic and
// ~1 ns per channel, so it runs beside the PNG encoder instead of as a GL pass (a resolve shader
// with three pow() per pixel cost ~25 ms a frame on llvmpipe). Values are clamped to [0, 1];
// NaN becomes 0.
#pragma once

#include <cstdint>

namespace shatter {

// `rgba_half`: width * height * 4 halves, bottom row first. `rgb`: width * height * 3 bytes,
// top row first.
void encode_srgb_rows(const uint16_t* rgba_half, uint32_t width, uint32_t height, uint8_t* rgb);

// The float value of an IEEE 754 binary16.
float half_to_float(uint16_t h);

}  // namespace shatter
