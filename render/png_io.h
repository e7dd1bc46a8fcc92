// PNG reading and writing with libpng.
//
// Writing is tuned for speed, since at 1280x720 a frame compresses slower than it renders:
// zlib level 1 with the RLE strategy and the SUB filter only (~13 ms a frame instead of ~70 ms at libpng's defaults),
// for files ~30% larger. The bytes depend only on the pixels (no time stamp, no text chunks),
// so a frame is the same file whichever process wrote it. Files carry an sRGB chunk.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "render/image.h"

namespace shatter {

// Encodes `height` rows of `width` pixels with `channels` bytes each (3: RGB; 4: RGBA whose
// fourth byte is dropped), rows `stride` bytes apart, top row first.
std::string encode_png(const uint8_t* pixels, uint32_t width, uint32_t height, int channels, size_t stride);
std::string encode_png(const Image& image);

// Decodes any PNG (grey, palette, 16-bit, alpha: composited on black) to 8-bit sRGB RGB.
// Throws Error(BadInput) naming `source` when the bytes are not a readable PNG.
Image decode_png(std::string_view bytes, const std::string& source);
Image load_png(const std::string& path);
void save_png(const std::string& path, const Image& image);  // atomic

}  // namespace shatter
