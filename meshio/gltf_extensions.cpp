#include "meshio/gltf_extensions.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace shatter {

namespace {

constexpr uint64_t kMaxJsonBytes = 256ull << 20;  // a .gltf with its buffers inlined; larger is not checked

// The JSON of a glTF file: a .glb's first chunk, a .gltf's whole text; "" when there is none.
std::string gltf_json(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return "";
    char header[20] = {};
    in.read(header, sizeof header);
    if (in.gcount() == sizeof header && std::memcmp(header, "glTF", 4) == 0) {
        uint32_t length = 0;
        std::memcpy(&length, header + 12, 4);  // little-endian, as the format is
        if (std::memcmp(header + 16, "JSON", 4) != 0 || length > kMaxJsonBytes) return "";
        std::string json(length, '\0');
        in.read(json.data(), std::streamsize(length));
        json.resize(size_t(in.gcount()));
        return json;
    }
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(path, ec);
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ec || bytes > kMaxJsonBytes || ext != ".gltf") return "";
    std::string json(bytes, '\0');
    in.clear();
    in.seekg(0);
    in.read(json.data(), std::streamsize(bytes));
    json.resize(size_t(in.gcount()));
    return json;
}

}  // namespace

std::string unreadable_gltf_extension(const std::string& path) {
    const std::string text = gltf_json(path);
    if (text.empty()) return "";
    const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_discarded() || !j.is_object() || !j.contains("extensionsRequired") || !j["extensionsRequired"].is_array())
        return "";
    for (const char* name : {"EXT_meshopt_compression", "KHR_mesh_quantization"})
        for (const auto& e : j["extensionsRequired"])
            if (e.is_string() && e.get<std::string>() == name) return name;
    return "";
}

void check_gltf_extensions(const std::string& path) {
    const std::string ext = unreadable_gltf_extension(path);
    if (ext.empty()) return;
    const std::string what = ext == "KHR_mesh_quantization"
                                 ? "its positions are quantized (glTF extension KHR_mesh_quantization, as gltfpack "
                                   "writes by default), which the mesh reader (assimp) reads as garbage"
                                 : "its buffers are compressed with meshoptimizer (glTF extension "
                                   "EXT_meshopt_compression, gltfpack -c), which the mesh reader (assimp) cannot "
                                   "decompress";
    throw_input_error(path, what,
                      "write it with plain float positions: gltfpack -i FILE -o plain.glb -noq (the npm package "
                      "gltfpack), then give shatter plain.glb");
}

}  // namespace shatter
