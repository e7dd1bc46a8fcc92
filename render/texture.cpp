#include "render/texture.h"

#include <cmath>

#include <spdlog/spdlog.h>
#include <stb/stb_image.h>

#include "render/gl.h"

namespace shatter {

namespace {

float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

}  // namespace

std::optional<DecodedImage> decode_image(const std::string& bytes, std::string* why) {
    int w = 0, h = 0, channels = 0;
    stbi_uc* data = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &w, &h,
                                          &channels, 4);
    if (data == nullptr || w <= 0 || h <= 0) {
        if (why) *why = stbi_failure_reason() ? stbi_failure_reason() : "not an image";
        if (data) stbi_image_free(data);
        return std::nullopt;
    }
    DecodedImage image;
    image.width = uint32_t(w);
    image.height = uint32_t(h);
    image.rgba.assign(data, data + size_t(w) * size_t(h) * 4);
    stbi_image_free(data);
    return image;
}

Colour mean_linear_colour(const DecodedImage& image) {
    float table[256];
    for (int i = 0; i < 256; ++i) table[i] = srgb_to_linear(float(i) / 255.0f);
    double sum[3] = {0, 0, 0};
    const size_t n = size_t(image.width) * image.height;
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) sum[k] += table[image.rgba[4 * i + size_t(k)]];
    if (n == 0) return {1, 1, 1};
    return {float(sum[0] / double(n)), float(sum[1] / double(n)), float(sum[2] / double(n))};
}

std::vector<MaterialLook> material_looks(const Model& model, std::vector<DecodedImage>* images) {
    std::vector<MaterialLook> looks;
    for (const Material& m : model.materials) {
        MaterialLook look;
        look.base = {m.base_colour[0], m.base_colour[1], m.base_colour[2]};
        look.mean = look.base;
        if (!m.texture.empty()) {
            std::string why;
            if (std::optional<DecodedImage> image = decode_image(m.texture, &why)) {
                const Colour mean = mean_linear_colour(*image);
                for (int k = 0; k < 3; ++k) look.mean[size_t(k)] *= mean[size_t(k)];
                look.texture = int32_t(images->size());
                images->push_back(std::move(*image));
            } else {
                spdlog::warn("material '{}': its texture '{}' ({} bytes) does not decode ({}); drawn in its base colour",
                             m.name, m.texture_name, m.texture.size(), why);
            }
        }
        looks.push_back(look);
    }
    return looks;
}

GpuTexture::GpuTexture(const DecodedImage& image) {
    glGenTextures(1, &id_);
    glBindTexture(GL_TEXTURE_2D, id_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8_ALPHA8, GLsizei(image.width), GLsizei(image.height), 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, image.rgba.data());
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glBindTexture(GL_TEXTURE_2D, 0);
}

GpuTexture::~GpuTexture() {
    if (id_) glDeleteTextures(1, &id_);
}

}  // namespace shatter
