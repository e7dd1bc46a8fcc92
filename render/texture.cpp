#include "render/texture.h"

#include <algorithm>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "render/gl.h"

namespace shatter {

InteriorTexture read_interior_texture(const std::string& path) {
    InteriorTexture t;
    t.bytes = read_file(path, "[render] interior_texture");
    std::string why;
    std::optional<DecodedImage> image = decode_image(t.bytes, &why);
    if (!image)
        throw_input_error(path, "[render] interior_texture cannot be decoded: " + why,
                          "give a PNG, JPEG, TGA, BMP or WebP image");
    t.image = std::move(*image);
    return t;
}

double interior_texture_span(const Model& model, const RenderSettings& settings) {
    if (settings.interior_texture_size > 0) return settings.interior_texture_size;
    Eigen::AlignedBox3d box;
    for (const Vec3& v : model.mesh.vertices) box.extend(v);
    return box.isEmpty() ? 1.0 : std::max(box.diagonal().norm() / 4, 1e-6);
}

std::vector<MaterialLook> material_looks(const Model& model, std::vector<DecodedImage>* images) {
    std::vector<MaterialLook> looks;
    for (const Material& m : model.materials) {
        MaterialLook look;
        look.base = {m.base_colour[0], m.base_colour[1], m.base_colour[2]};
        look.mean = look.base;
        if (!m.texture.empty()) {
            std::string why;
            std::optional<DecodedImage> image = decode_image(m.texture, &why);
            if (image && std::max(image->width, image->height) > kMaxTextureSide) {
                why = fmt::format("{} x {} texels, more than the {} a side render takes", image->width, image->height,
                                  kMaxTextureSide);
                image.reset();
            }
            if (image) {
                const Colour mean = mean_linear_colour(*image);
                for (int k = 0; k < 3; ++k) look.mean[size_t(k)] *= mean[size_t(k)];
                look.texture = int32_t(images->size());
                images->push_back(std::move(*image));
            } else {
                spdlog::warn("material '{}': its texture '{}' ({} bytes) is not drawn ({}); drawn in its base colour",
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
