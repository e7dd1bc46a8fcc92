// Reading and writing the model file (magic "SHTMODEL", docs/formats.md).
#pragma once

#include <string>
#include <string_view>

#include "core/model.h"

namespace shatter {

constexpr std::string_view kModelMagic = "SHTMODEL";
constexpr uint32_t kModelVersion = 1;  // the version written; the reader accepts 1..kModelVersion

std::string encode_model(const Model& model);
// Decodes and validates (every index in range, every number finite); throws Error(BadInput)
// naming `source`.
Model decode_model(std::string_view bytes, const std::string& source);

void save_model(const std::string& path, const Model& model);  // atomic
Model load_model(const std::string& path);

}  // namespace shatter
