// The colour of each piece, shared by render, the PLY/glTF exports and the contact sheets so
// that a piece has the same colour everywhere. Linear-light RGB in [0, 1].
#pragma once

#include <array>
#include <cstdint>

namespace shatter {

// Twelve well-separated hues (a qualitative palette); pieces beyond cycle with a lighter shade.
inline std::array<float, 3> piece_colour(uint32_t piece) {
    static constexpr float kSrgb[12][3] = {
        {0.894f, 0.102f, 0.110f}, {0.216f, 0.494f, 0.722f}, {0.302f, 0.686f, 0.290f}, {0.596f, 0.306f, 0.639f},
        {1.000f, 0.498f, 0.000f}, {0.651f, 0.337f, 0.157f}, {0.969f, 0.506f, 0.749f}, {0.400f, 0.761f, 0.647f},
        {0.988f, 0.553f, 0.384f}, {0.553f, 0.627f, 0.796f}, {0.906f, 0.541f, 0.765f}, {0.651f, 0.847f, 0.329f}};
    const float* c = kSrgb[piece % 12];
    const float lift = static_cast<float>((piece / 12) % 3) * 0.25f;
    std::array<float, 3> out{};
    for (int i = 0; i < 3; ++i) {
        const float s = c[i] + (1.0f - c[i]) * lift;  // sRGB, then to linear light
        out[i] = s <= 0.04045f ? s / 12.92f : static_cast<float>(__builtin_pow((s + 0.055) / 1.055, 2.4));
    }
    return out;
}

// 8-bit sRGB of a linear value in [0, 1].
inline uint8_t linear_to_srgb8(float v) {
    v = v < 0 ? 0 : (v > 1 ? 1 : v);
    const float s = v <= 0.0031308f ? v * 12.92f : 1.055f * static_cast<float>(__builtin_pow(v, 1.0 / 2.4)) - 0.055f;
    return static_cast<uint8_t>(s * 255.0f + 0.5f);
}

}  // namespace shatter
