#include "core/utf8.h"

#include <cstdint>

namespace shatter {

namespace {

// The length of the valid UTF-8 sequence at bytes[i], or 0.
size_t sequence_length(std::string_view bytes, size_t i) {
    const auto at = [&](size_t k) { return uint8_t(bytes[k]); };
    const uint8_t b = at(i);
    if (b < 0x80) return 1;
    size_t n = 0;
    uint32_t cp = 0;
    if ((b & 0xE0) == 0xC0) n = 2, cp = b & 0x1F;
    else if ((b & 0xF0) == 0xE0) n = 3, cp = b & 0x0F;
    else if ((b & 0xF8) == 0xF0) n = 4, cp = b & 0x07;
    else return 0;
    if (i + n > bytes.size()) return 0;
    for (size_t k = 1; k < n; ++k) {
        if ((at(i + k) & 0xC0) != 0x80) return 0;
        cp = cp << 6 | (at(i + k) & 0x3F);
    }
    const uint32_t least[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < least[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
    return n;
}

}  // namespace

std::string as_utf8(std::string_view bytes) {
    for (size_t i = 0; i < bytes.size();) {
        const size_t n = sequence_length(bytes, i);
        if (n == 0) return to_utf8(bytes);
        i += n;
    }
    return std::string(bytes);
}

std::string to_utf8(std::string_view bytes) {
    std::string out;
    out.reserve(bytes.size());
    for (size_t i = 0; i < bytes.size();) {
        const uint8_t b = uint8_t(bytes[i]);
        const size_t n = sequence_length(bytes, i);
        if (n == 1 && b < 0x20) {
            out.push_back('?');
        } else if (n > 0) {
            out.append(bytes.substr(i, n));
        } else {
            out.push_back(char(0xC0 | (b >> 6)));
            out.push_back(char(0x80 | (b & 0x3F)));
        }
        i += n > 0 ? n : 1;
    }
    return out;
}

}  // namespace shatter
