// Reading and writing the model file (magic "SHTMODEL", docs/formats.md).
#pragma once

#include <string>
#include <string_view>

#include "core/model.h"

namespace shatter {

class ByteWriter;
class ByteReader;

constexpr std::string_view kModelMagic = "SHTMODEL";
// The version written; the reader accepts 1..kModelVersion. 2: pieces may carry a render surface
// (version 1 files read with none: their pieces are drawn with the tet surface). 3: render
// surfaces may carry texture coordinates, colours and materials, and the model the input's
// materials with their textures (version 2 files read with none).
constexpr uint32_t kModelVersion = 3;

std::string encode_model(const Model& model);
// Decodes and validates (every index in range, every number finite); throws Error(BadInput)
// naming `source`.
Model decode_model(std::string_view bytes, const std::string& source);

// One material as the model file stores it (also the appearance reader's hand-over from its child
// process). read_material throws Error(BadInput) through `r` on what the model file cannot hold:
// a non-finite base colour, a texture longer than the bytes left, over-long names.
void write_material(ByteWriter& w, const Material& m);
Material read_material(ByteReader& r);

void save_model(const std::string& path, const Model& model);  // atomic
Model load_model(const std::string& path);

}  // namespace shatter
