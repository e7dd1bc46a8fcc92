#include "render/srgb_encode.h"

#include <array>
#include <cmath>
#include <cstddef>

#include "core/palette.h"

namespace shatter {

float half_to_float(uint16_t h) {
    const int sign = h >> 15, exponent = (h >> 10) & 0x1f, mantissa = h & 0x3ff;
    float v;
    if (exponent == 0) v = std::ldexp(float(mantissa), -24);                       // subnormal
    else if (exponent == 31) v = mantissa ? NAN : INFINITY;                        // inf, NaN
    else v = std::ldexp(float(mantissa | 0x400), exponent - 25);                   // normal
    return sign ? -v : v;
}

namespace {

const std::array<uint8_t, 65536>& srgb_table() {
    static const std::array<uint8_t, 65536> table = [] {
        std::array<uint8_t, 65536> t{};
        for (uint32_t h = 0; h < 65536; ++h) {
            const float v = half_to_float(uint16_t(h));
            t[h] = std::isnan(v) ? 0 : linear_to_srgb8(v);
        }
        return t;
    }();
    return table;
}

}  // namespace

void encode_srgb_rows(const uint16_t* rgba_half, uint32_t width, uint32_t height, uint8_t* rgb) {
    const std::array<uint8_t, 65536>& table = srgb_table();
    for (uint32_t y = 0; y < height; ++y) {
        const uint16_t* in = rgba_half + size_t(height - 1 - y) * width * 4;
        uint8_t* out = rgb + size_t(y) * width * 3;
        for (uint32_t x = 0; x < width; ++x) {
            out[3 * x + 0] = table[in[4 * x + 0]];
            out[3 * x + 1] = table[in[4 * x + 1]];
            out[3 * x + 2] = table[in[4 * x + 2]];
        }
    }
}

}  // namespace shatter
