// Decoding the input's texture images (core/model.h Material::texture: the encoded file) with
// stb_image (Debian's libstb: PNG, JPEG, TGA, BMP, ...) and libwebp (WebP, as glTF's
// EXT_texture_webp and web tools' texture compression store them). Used by render (textures in
// GL), the .glb (TGA, BMP and WebP re-encoded as PNG) and OUT.pieces.ply (vertex colours from the
// texture).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace shatter {

struct DecodedImage {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;  // sRGB RGBA8, the file's top row first

    // The texel at texture coordinates (u, v) in assimp's convention (v up), wrapping (glTF's
    // default repeat), nearest texel.
    const uint8_t* at(float u, float v) const;
};

// Whether the bytes begin as a WebP file does (RIFF....WEBP).
bool is_webp(const std::string& bytes);

// nullopt, with `why` set, when the bytes are not an image stb_image or libwebp reads (or a WebP
// over 16384 pixels on a side).
std::optional<DecodedImage> decode_image(const std::string& bytes, std::string* why);

// The mean colour of an image in linear light (alpha ignored).
std::array<float, 3> mean_linear_colour(const DecodedImage& image);

}  // namespace shatter
