// The input's textures (core/model.h Material::texture, the encoded image file) for drawing:
// decoded with stb_image (meshio/image_decode.h), and uploaded to GL as sRGB
// textures with mipmaps, so that sampling decodes them to linear light (trilinear filtering,
// repeat wrapping, as glTF's default sampler).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/model.h"
#include "core/render_settings.h"
#include "meshio/image_decode.h"
#include "render/mesh_builder.h"

namespace shatter {

// The largest texture side render uploads (unit: texels): llvmpipe takes 16,384, but one such
// RGBA texture with its mipmaps is 1.4 GB.
inline constexpr uint32_t kMaxTextureSide = 8192;

// How each material of `model` is drawn (mesh_builder.h MaterialLook), and the decoded images
// its textures index into `images`. A texture that does not decode, or is larger than
// kMaxTextureSide, is logged as a warning (once per material) and its material drawn in its
// base colour; never an error.
std::vector<MaterialLook> material_looks(const Model& model, std::vector<DecodedImage>* images);

// [render] interior_texture as the file's bytes and its image; Error(BadInput) naming the file
// when it cannot be read or decoded (render and the .glb read it alike).
struct InteriorTexture {
    std::string bytes;
    DecodedImage image;
};
InteriorTexture read_interior_texture(const std::string& path);

// One repeat of the interior texture (unit: m): interior_texture_size when given, else a quarter
// of the diagonal of `model`'s tets' bounding box (render's projection and the .glb's crack
// coordinates use the same).
double interior_texture_span(const Model& model, const RenderSettings& settings);

// A decoded image as a GL texture (needs a current context).
class GpuTexture {
public:
    explicit GpuTexture(const DecodedImage& image);
    ~GpuTexture();
    GpuTexture(const GpuTexture&) = delete;
    GpuTexture& operator=(const GpuTexture&) = delete;
    unsigned id() const { return id_; }

private:
    unsigned id_ = 0;
};

}  // namespace shatter
