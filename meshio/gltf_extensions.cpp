#include "meshio/gltf_extensions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

#include <fmt/format.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "meshio/mesh_load.h"

namespace shatter {

namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

constexpr uint64_t kMaxFileBytes = 2ull << 30;     // what a GLB's 32-bit length allows
constexpr uint64_t kMaxDecodedBytes = 1ull << 31;  // one decoded buffer view at most
constexpr uint32_t kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;
constexpr int kFloat = 5126;
constexpr uint64_t kMaxInstancedTriangles = 10'000'000;  // what a file's instances may draw in all
const char* const kFix = "or write it with plain float positions: gltfpack -i FILE -o plain.glb -noq (the npm package "
                         "gltfpack), then give shatter plain.glb";

std::string read_bytes(const std::string& path, uint64_t limit) {
    std::error_code ec;
    const uint64_t size = fs::file_size(path, ec);
    if (ec || size > limit) return "";
    std::ifstream in(path, std::ios::binary);
    std::string bytes(size, '\0');
    in.read(bytes.data(), std::streamsize(size));
    bytes.resize(size_t(in.gcount()));
    return bytes;
}

uint32_t le32(const std::string& b, size_t at) {
    uint32_t v = 0;
    std::memcpy(&v, b.data() + at, 4);  // little-endian, as GLB is (and as this machine is)
    return v;
}

// A glTF file as JSON and its GLB binary chunk ("" for a .gltf, or a GLB without one).
struct GltfFile {
    json doc;
    std::string bin;
    bool ok = false;
};

// The JSON chunk alone unless `with_bin` (a large file that needs no decoding is not read whole);
// not ok for a file that names neither extension.
GltfFile read_gltf(const std::string& path, bool with_bin) {
    GltfFile f;
    const std::string ext = lower_extension(path);
    if (ext != ".glb" && ext != ".gltf") return f;
    std::error_code ec;
    const uint64_t file_bytes = fs::file_size(path, ec);
    if (ec) return f;
    std::ifstream in(path, std::ios::binary);
    std::string header(20, '\0');
    in.read(header.data(), 20);
    header.resize(size_t(in.gcount()));
    std::string text;
    if (header.size() == 20 && header.compare(0, 4, "glTF") == 0) {
        const uint32_t length = le32(header, 12);
        // Chunk lengths are taken only as far as the file reaches.
        if (le32(header, 16) != kJsonChunk || length > file_bytes - 20) return f;
        text.assign(length, '\0');
        in.read(text.data(), std::streamsize(length));
        text.resize(size_t(in.gcount()));
        if (with_bin) {
            std::string chunk(8, '\0');
            in.read(chunk.data(), 8);
            if (in.gcount() == 8 && le32(chunk, 4) == kBinChunk && le32(chunk, 0) <= file_bytes - 28 - length) {
                f.bin.assign(le32(chunk, 0), '\0');
                in.read(f.bin.data(), std::streamsize(f.bin.size()));
                f.bin.resize(size_t(in.gcount()));
            }
        }
    } else {
        text = read_bytes(path, kMaxFileBytes);
    }
    // Most files name none of the extensions decoded here: they are not parsed (a .gltf with its
    // buffers inlined can be tens of MB, and is read for the mesh and again for its appearance).
    if (text.find("EXT_meshopt_compression") == std::string::npos && text.find("KHR_mesh_quantization") == std::string::npos &&
        text.find("KHR_texture_transform") == std::string::npos && text.find("EXT_texture_webp") == std::string::npos &&
        text.find("EXT_mesh_gpu_instancing") == std::string::npos && text.find("KHR_texture_basisu") == std::string::npos)
        return f;
    f.doc = json::parse(text, nullptr, false);
    f.ok = !f.doc.is_discarded() && f.doc.is_object();
    return f;
}

std::string first_unreadable(const json& doc) {
    if (!doc.contains("extensionsRequired") || !doc["extensionsRequired"].is_array()) return "";
    for (const char* name : {"EXT_meshopt_compression", "KHR_mesh_quantization"})
        for (const auto& e : doc["extensionsRequired"])
            if (e.is_string() && e.get<std::string>() == name) return name;
    return "";
}

// A material's base colour texture transform (KHR_texture_transform), or nullptr.
const json* base_colour_transform(const json& material) {
    if (!material.is_object() || !material.contains("pbrMetallicRoughness")) return nullptr;
    const json& pbr = material["pbrMetallicRoughness"];
    if (!pbr.is_object() || !pbr.contains("baseColorTexture")) return nullptr;
    const json& info = pbr["baseColorTexture"];
    if (!info.is_object() || !info.contains("extensions") || !info["extensions"].is_object() ||
        !info["extensions"].contains("KHR_texture_transform") || !info["extensions"]["KHR_texture_transform"].is_object())
        return nullptr;
    return &info["extensions"]["KHR_texture_transform"];
}

// The image a texture names through one of the extensions assimp 5.2 does not know, or nullptr:
// EXT_texture_webp's (a WebP image, read here), or KHR_texture_basisu's when the texture has no
// other (a KTX2 image, which the appearance reader then names in a warning instead of dropping
// the texture unsaid).
const json* extension_source(const json& texture) {
    if (!texture.is_object() || !texture.contains("extensions") || !texture["extensions"].is_object()) return nullptr;
    const json& extensions = texture["extensions"];
    for (const std::string name : {"EXT_texture_webp", "KHR_texture_basisu"}) {
        if (!extensions.contains(name) || (name == "KHR_texture_basisu" && texture.contains("source"))) continue;
        const json& ext = extensions[name];
        if (ext.is_object() && ext.contains("source") && ext["source"].is_number_unsigned()) return &ext["source"];
    }
    return nullptr;
}

// A node's instances (EXT_mesh_gpu_instancing), or nullptr.
const json* instancing(const json& node) {
    if (!node.is_object() || !node.contains("extensions") || !node["extensions"].is_object() ||
        !node["extensions"].contains("EXT_mesh_gpu_instancing"))
        return nullptr;
    const json& ext = node["extensions"]["EXT_mesh_gpu_instancing"];
    return ext.is_object() && ext.contains("attributes") && ext["attributes"].is_object() ? &ext : nullptr;
}

// Whether an element of the document's array `key` has what `find` looks for.
bool any_in(const json& doc, const char* key, const json* (*find)(const json&)) {
    if (!doc.contains(key) || !doc[key].is_array()) return false;
    for (const json& e : doc[key])
        if (find(e)) return true;
    return false;
}

// Decoding, with every index and range checked against what the file holds.
class Decoder {
public:
    Decoder(const std::string& path, GltfFile& file) : path_(path), f_(file), doc_(file.doc) {}

    std::string glb() {
        load_buffers();
        decode_views();
        dequantize_attributes();
        bake_texture_transforms();
        use_extension_images();
        expand_instances();
        return write();
    }

private:
    [[noreturn]] void fail(const std::string& what) const {
        throw_input_error(path_, "its glTF " + what, std::string("check that the file is complete, ") + kFix);
    }
    const json& array(const char* key) const {
        static const json empty = json::array();
        return doc_.contains(key) && doc_[key].is_array() ? doc_[key] : empty;
    }
    static uint64_t number(const json& o, const char* key, uint64_t fallback) {
        if (!o.contains(key)) return fallback;
        return o[key].is_number_unsigned() ? o[key].get<uint64_t>() : UINT64_MAX;
    }
    uint64_t required(const json& o, const char* key, const std::string& what) const {
        const uint64_t v = number(o, key, UINT64_MAX);
        if (v == UINT64_MAX) fail(fmt::format("{} has no valid {}", what, key));
        return v;
    }

    // Each buffer's bytes: the GLB's binary chunk, a data: URI, or a file beside the .gltf. A
    // buffer that only backs compressed views (EXT_meshopt_compression's fallback) may have none.
    void load_buffers() {
        const json& buffers = array("buffers");
        for (size_t i = 0; i < buffers.size(); ++i) {
            const json& b = buffers[i];
            std::string bytes;
            if (b.contains("uri") && b["uri"].is_string()) {
                const std::string uri = b["uri"].get<std::string>();
                if (uri.rfind("data:", 0) == 0) {
                    const size_t comma = uri.find(',');
                    if (comma == std::string::npos || uri.find(";base64") > comma) fail(fmt::format("buffer {} has a data URI that is not base64", i));
                    bytes = base64_decode(uri.substr(comma + 1), i);
                } else {
                    const fs::path file = fs::path(path_).parent_path() / uri;
                    bytes = read_bytes(file.string(), kMaxFileBytes);
                    if (bytes.empty()) fail(fmt::format("buffer {} ('{}') cannot be read beside the file", i, uri));
                }
            } else if (i == 0) {
                bytes = f_.bin;
            }
            buffers_.push_back(std::move(bytes));
        }
    }
    std::string base64_decode(const std::string& text, size_t buffer) const {
        std::string out;
        uint32_t acc = 0;
        int bits = 0;
        for (char c : text) {
            int v;
            if (c >= 'A' && c <= 'Z') v = c - 'A';
            else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
            else if (c >= '0' && c <= '9') v = c - '0' + 52;
            else if (c == '+') v = 62;
            else if (c == '/') v = 63;
            else if (c == '=') break;
            else fail(fmt::format("buffer {}'s data URI is not base64", buffer));
            acc = (acc << 6) | uint32_t(v);
            bits += 6;
            if (bits >= 8) {
                bits -= 8;
                out.push_back(char((acc >> bits) & 0xFF));
            }
        }
        return out;
    }
    const std::string& slice_source(uint64_t buffer, uint64_t offset, uint64_t length, const std::string& what,
                                     std::string* out) const {
        if (buffer >= buffers_.size()) fail(fmt::format("{} names buffer {}, which does not exist", what, buffer));
        const std::string& b = buffers_[size_t(buffer)];
        if (offset > b.size() || length > b.size() - offset)
            fail(fmt::format("{} reaches past its buffer ({} + {} bytes of {})", what, offset, length, b.size()));
        out->assign(b, size_t(offset), size_t(length));
        return *out;
    }

    // Every buffer view's bytes, meshopt-compressed ones decoded.
    void decode_views() {
        const json& views = array("bufferViews");
        for (size_t i = 0; i < views.size(); ++i) {
            json& v = doc_["bufferViews"][i];
            const std::string what = fmt::format("buffer view {}", i);
            std::string data;
            const json* ext = v.contains("extensions") && v["extensions"].contains("EXT_meshopt_compression")
                                  ? &v["extensions"]["EXT_meshopt_compression"]
                                  : nullptr;
            if (ext) {
                std::string source;
                slice_source(required(*ext, "buffer", what), number(*ext, "byteOffset", 0),
                             required(*ext, "byteLength", what), what, &source);
                const uint64_t count = required(*ext, "count", what), stride = required(*ext, "byteStride", what);
                const std::string mode = ext->value("mode", std::string()), filter = ext->value("filter", std::string("NONE"));
                // meshoptimizer's codecs shrink data at most 64-fold (an all-zero attribute: 2 bits per
                // 16 bytes): a view that claims more than 128 times its compressed bytes is not one.
                if (stride == 0 || stride > 256 || count > kMaxDecodedBytes / stride ||
                    count * stride > 128 * uint64_t(source.size()) + 4096)
                    fail(fmt::format("{} claims {} elements of {} bytes from {} compressed bytes", what, count, stride,
                                     source.size()));
                data.assign(size_t(count * stride), '\0');
                const auto* src = reinterpret_cast<const unsigned char*>(source.data());
                int status = -1;
                if (mode == "ATTRIBUTES" && stride % 4 == 0)
                    status = meshopt_decodeVertexBuffer(data.data(), size_t(count), size_t(stride), src, source.size());
                else if (mode == "TRIANGLES" && (stride == 2 || stride == 4) && count % 3 == 0)
                    status = meshopt_decodeIndexBuffer(data.data(), size_t(count), size_t(stride), src, source.size());
                else if (mode == "INDICES" && (stride == 2 || stride == 4))
                    status = meshopt_decodeIndexSequence(data.data(), size_t(count), size_t(stride), src, source.size());
                if (status != 0)
                    fail(fmt::format("{} does not decode (EXT_meshopt_compression mode {}, {} bytes per element)", what,
                                     mode, stride));
                if (filter == "OCTAHEDRAL" && (stride == 4 || stride == 8))
                    meshopt_decodeFilterOct(data.data(), size_t(count), size_t(stride));
                else if (filter == "QUATERNION" && stride == 8)
                    meshopt_decodeFilterQuat(data.data(), size_t(count), size_t(stride));
                else if (filter == "EXPONENTIAL" && stride % 4 == 0)
                    meshopt_decodeFilterExp(data.data(), size_t(count), size_t(stride));
                else if (filter != "NONE")
                    fail(fmt::format("{} has filter {} for {} bytes per element", what, filter, stride));
                v["extensions"].erase("EXT_meshopt_compression");
                if (v["extensions"].empty()) v.erase("extensions");
            } else {
                slice_source(required(v, "buffer", what), number(v, "byteOffset", 0), required(v, "byteLength", what),
                             what, &data);
            }
            views_.push_back(std::move(data));
        }
    }

    // Integer vertex attributes as floats: positions, normals, tangents and texture coordinates
    // (the attributes quantization changes; joints stay integers, colours and weights stay as glTF
    // allows them).
    void dequantize_attributes() {
        std::map<uint64_t, bool> done;
        const auto visit = [&](const json& attributes) {
            if (!attributes.is_object()) return;
            for (const auto& [name, index] : attributes.items()) {
                const bool quantizable = name == "POSITION" || name == "NORMAL" || name == "TANGENT" ||
                                         name.rfind("TEXCOORD_", 0) == 0;
                if (!quantizable || !index.is_number_unsigned()) continue;
                const uint64_t a = index.get<uint64_t>();
                if (!done.emplace(a, true).second) continue;
                to_float(a);
            }
        };
        for (const auto& mesh : array("meshes"))
            if (mesh.contains("primitives") && mesh["primitives"].is_array())
                for (const auto& p : mesh["primitives"]) {
                    if (p.contains("attributes")) visit(p["attributes"]);
                    if (p.contains("targets") && p["targets"].is_array())
                        for (const auto& t : p["targets"]) visit(t);
                }
    }
    // The accessor's values as floats, `*width` per element, every index and range checked
    // against what the file holds.
    std::vector<float> values_of(uint64_t index, int* width) {
        if (index >= array("accessors").size()) fail(fmt::format("an attribute names accessor {}, which does not exist", index));
        const json& a = doc_["accessors"][size_t(index)];
        const std::string what = fmt::format("accessor {}", index);
        if (!a.is_object()) fail(what + " is not an object");
        if (a.contains("sparse")) fail(what + " is sparse, which is not decoded here");
        const int type = a.value("componentType", 0);
        const std::map<std::string, int> widths = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}};
        const auto w = widths.find(a.value("type", std::string()));
        const int size = type == 5120 || type == 5121 ? 1 : type == 5122 || type == 5123 ? 2 : type == 5125 || type == kFloat ? 4 : 0;
        if (w == widths.end() || size == 0) fail(what + " has a type or component type glTF does not define");
        const int n = w->second;
        *width = n;
        const uint64_t count = required(a, "count", what), view = required(a, "bufferView", what);
        if (view >= views_.size()) fail(fmt::format("{} names buffer view {}, which does not exist", what, view));
        const std::string& data = views_[size_t(view)];
        const uint64_t offset = number(a, "byteOffset", 0), element = uint64_t(n * size);
        const uint64_t stride = number(doc_["bufferViews"][size_t(view)], "byteStride", element);
        if (count == 0 || offset > data.size() || stride < element ||
            (count - 1) > (data.size() - offset - std::min<uint64_t>(element, data.size() - offset)) / stride ||
            data.size() - offset < element)
            fail(fmt::format("{} reaches past its buffer view ({} elements of {} bytes, stride {})", what, count, element,
                             stride));
        const bool normalized = a.value("normalized", false);
        const auto value = [&](const unsigned char* p) -> float {
            switch (type) {
                case 5120: { int8_t c; std::memcpy(&c, p, 1); return normalized ? std::max(c / 127.0f, -1.0f) : float(c); }
                case 5121: return normalized ? *p / 255.0f : float(*p);
                case 5122: { int16_t c; std::memcpy(&c, p, 2); return normalized ? std::max(c / 32767.0f, -1.0f) : float(c); }
                case 5123: { uint16_t c; std::memcpy(&c, p, 2); return normalized ? c / 65535.0f : float(c); }
                case kFloat: { float c; std::memcpy(&c, p, 4); return c; }
                default: { uint32_t c; std::memcpy(&c, p, 4); return normalized ? float(c / 4294967295.0) : float(c); }
            }
        };
        std::vector<float> out(size_t(count) * size_t(n));
        const auto* in = reinterpret_cast<const unsigned char*>(data.data() + offset);
        for (uint64_t e = 0; e < count; ++e)
            for (int c = 0; c < n; ++c) out[e * uint64_t(n) + uint64_t(c)] = value(in + e * stride + uint64_t(c * size));
        return out;
    }
    // The accessor's values as tightly packed floats in a view of their own; a float accessor too
    // when `copy` (a copy whose values are to change).
    void to_float(uint64_t index, bool copy = false) {
        if (index >= array("accessors").size()) fail(fmt::format("an attribute names accessor {}, which does not exist", index));
        json& a = doc_["accessors"][size_t(index)];
        const int type = a.value("componentType", 0);
        if (type == kFloat && !copy) return;
        int n = 0;
        const std::vector<float> values = values_of(index, &n);
        const bool normalized = a.value("normalized", false);
        // min and max (POSITION must have them) in the same units.
        for (const char* bound : {"min", "max"})
            if (a.contains(bound) && a[bound].is_array())
                for (auto& v : a[bound])
                    if (v.is_number()) {
                        const double d = v.get<double>();
                        v = normalized ? (type == 5121 ? d / 255 : type == 5123 ? d / 65535
                                          : type == 5120 ? std::max(d / 127, -1.0)
                                          : type == 5122 ? std::max(d / 32767, -1.0) : d / 4294967295.0)
                                       : d;
                    }
        std::string floats(values.size() * 4, '\0');
        std::memcpy(floats.data(), values.data(), floats.size());
        json view_json = {{"buffer", 0}, {"byteLength", floats.size()}};
        doc_["bufferViews"].push_back(view_json);
        views_.push_back(std::move(floats));
        converted_[index] = views_.size() - 1;
        a["bufferView"] = views_.size() - 1;
        a["componentType"] = kFloat;
        a.erase("byteOffset");
        a.erase("normalized");
    }

    // A KHR_texture_transform on the base colour texture (gltfpack's quantized coordinates come
    // with one that scales them back; Blender writes one for a mapping node): assimp 5.2 does not
    // apply it as glTF defines it. It is applied here instead, uv' = offset + R S uv with R =
    // [[cos, sin], [-sin, cos]] (the direction the Khronos TextureTransformTest asset marks
    // correct), to a float copy of the coordinates each of the material's primitives reads (the
    // same coordinates may serve several materials), and taken off the material. A material with
    // a primitive whose coordinates cannot be copied (sparse, or not VEC2) is left to assimp.
    void bake_texture_transforms() {
        if (!doc_.contains("materials") || !doc_["materials"].is_array() || !doc_.contains("meshes") ||
            !doc_["meshes"].is_array())
            return;
        json& materials = doc_["materials"];
        // Each primitive whose material transforms its base colour texture, with the attribute it reads.
        struct Use {
            json* primitive;
            size_t material;
            std::string attribute;
        };
        std::vector<Use> uses;
        std::vector<char> bakeable(materials.size(), 1), used(materials.size(), 0);
        for (auto& mesh : doc_["meshes"])
            if (mesh.is_object() && mesh.contains("primitives") && mesh["primitives"].is_array())
                for (auto& p : mesh["primitives"]) {
                    if (!p.is_object() || !p.contains("material") || !p["material"].is_number_unsigned() ||
                        !p.contains("attributes") || !p["attributes"].is_object())
                        continue;
                    const size_t m = p["material"].get<size_t>();
                    if (m >= materials.size()) continue;
                    const json* t = base_colour_transform(materials[m]);
                    if (!t) continue;
                    used[m] = 1;
                    const std::string name = "TEXCOORD_" + std::to_string(coordinate_set(materials[m], *t));
                    const json& attributes = p["attributes"];
                    const json* a = attributes.contains(name) && attributes[name].is_number_unsigned() &&
                                            attributes[name].get<uint64_t>() < array("accessors").size()
                                        ? &doc_["accessors"][attributes[name].get<size_t>()]
                                        : nullptr;
                    if (!a || !a->is_object() || a->contains("sparse") || a->value("type", std::string()) != "VEC2")
                        bakeable[m] = 0;
                    else
                        uses.push_back({&p, m, name});
                }
        std::map<std::pair<size_t, size_t>, size_t> copies;  // (accessor, material) -> its baked copy
        for (const Use& use : uses) {
            if (!bakeable[use.material]) continue;
            json& attribute = (*use.primitive)["attributes"][use.attribute];
            const std::pair<size_t, size_t> key{attribute.get<size_t>(), use.material};
            auto it = copies.find(key);
            if (it == copies.end()) {
                const size_t copy = float_copy(key.first);
                transform_coordinates(views_[converted_[copy]], *base_colour_transform(materials[use.material]));
                it = copies.emplace(key, copy).first;
            }
            attribute = it->second;
        }
        for (size_t m = 0; m < materials.size(); ++m) {
            if (!used[m] || !bakeable[m]) continue;
            json& info = materials[m]["pbrMetallicRoughness"]["baseColorTexture"];
            const json t = info["extensions"]["KHR_texture_transform"];
            info["texCoord"] = coordinate_set(materials[m], t);
            strip_transforms(materials[m], {t});  // and off its other textures that carry the same one
        }
    }
    // The coordinate set a material's base colour texture reads: the transform's texCoord, if any.
    static int coordinate_set(const json& material, const json& transform) {
        const json& info = material["pbrMetallicRoughness"]["baseColorTexture"];
        const json& from = transform.contains("texCoord") ? transform["texCoord"] : info.contains("texCoord") ? info["texCoord"] : json(0);
        return from.is_number_unsigned() && from.get<uint64_t>() < 64 ? from.get<int>() : 0;
    }
    // A new accessor with the same values as `a`, as floats in a view of their own.
    size_t float_copy(size_t a) {
        json copy = doc_["accessors"][a];
        copy.erase("min");
        copy.erase("max");
        doc_["accessors"].push_back(std::move(copy));
        const size_t c = doc_["accessors"].size() - 1;
        to_float(c, true);
        return c;
    }
    static void transform_coordinates(std::string& floats, const json& t) {
        const double r = t.contains("rotation") && t["rotation"].is_number() ? t["rotation"].get<double>() : 0.0;
        const double c = std::cos(r), sn = std::sin(r);
        const auto pair = [&t](const char* key, double fallback) {
            return t.contains(key) && t[key].is_array() && t[key].size() == 2 && t[key][0].is_number() && t[key][1].is_number()
                       ? std::array<double, 2>{t[key][0].get<double>(), t[key][1].get<double>()}
                       : std::array<double, 2>{fallback, fallback};
        };
        const std::array<double, 2> offset = pair("offset", 0), scale = pair("scale", 1);
        auto* uv = reinterpret_cast<float*>(floats.data());
        for (size_t i = 0; i + 1 < floats.size() / 4; i += 2) {
            const double u = uv[i] * scale[0], v = uv[i + 1] * scale[1];
            uv[i] = float(c * u + sn * v + offset[0]);
            uv[i + 1] = float(-sn * u + c * v + offset[1]);
        }
    }
    // A texture with a WebP image (EXT_texture_webp: glTF-Transform's and gltfpack's WebP texture
    // compression, often with no PNG or JPEG fallback) takes it as its source, which assimp reads
    // and meshio/image_decode.h decodes; assimp 5.2 does not know the extension and left such a
    // texture without an image. So does a texture with only a KTX2 image (KHR_texture_basisu),
    // which no Debian library decodes: the appearance reader then says so.
    void use_extension_images() {
        if (!doc_.contains("textures") || !doc_["textures"].is_array()) return;
        const size_t images = array("images").size();
        for (json& t : doc_["textures"]) {
            const json* source = extension_source(t);
            if (!source || source->get<uint64_t>() >= images) continue;
            t["source"] = *source;
            t["extensions"].erase("EXT_texture_webp");
            if (t["extensions"].empty()) t.erase("extensions");
        }
    }
    // A node drawing its mesh at many places (EXT_mesh_gpu_instancing: glTF-Transform's
    // `optimize` makes every mesh used more than a few times one), which assimp 5.2 draws once, at
    // the node: each instance becomes a child node with the instance's translation, rotation and
    // scale (in the node's space, as the extension defines them) and the node's mesh, while the
    // instances draw at most kMaxInstancedTriangles.
    void expand_instances() {
        if (!doc_.contains("nodes") || !doc_["nodes"].is_array()) return;
        const size_t nodes = doc_["nodes"].size();
        uint64_t made = 0;  // triangles the instances draw
        for (size_t i = 0; i < nodes; ++i) {
            const json* ext = instancing(doc_["nodes"][i]);
            if (!ext || !doc_["nodes"][i].contains("mesh")) continue;
            const std::string what = fmt::format("node {}'s EXT_mesh_gpu_instancing", i);
            const json& attributes = (*ext)["attributes"];
            std::map<std::string, std::vector<float>> values;
            size_t count = SIZE_MAX;
            for (const auto& [name, width] : {std::pair<std::string, int>{"TRANSLATION", 3}, {"ROTATION", 4}, {"SCALE", 3}}) {
                if (!attributes.contains(name)) continue;
                if (!attributes[name].is_number_unsigned()) fail(fmt::format("{} has a {} that is no accessor", what, name));
                int n = 0;
                values[name] = values_of(attributes[name].get<uint64_t>(), &n);
                if (n != width) fail(fmt::format("{} has a {} of {} components, not {}", what, name, n, width));
                count = std::min(count, values[name].size() / size_t(width));
            }
            if (count == SIZE_MAX) continue;  // no attributes: the node draws its mesh once, as it is
            const json mesh = doc_["nodes"][i]["mesh"];
            made += uint64_t(count) * std::max<uint64_t>(1, triangles_of(mesh));
            if (made > kMaxInstancedTriangles)
                fail(fmt::format("{} draws more than {} triangles with the file's other instances", what,
                                 kMaxInstancedTriangles));
            std::vector<size_t> children;
            for (size_t k = 0; k < count; ++k) {
                json child = {{"mesh", mesh}};
                const auto put = [&](const char* name, const char* key, int width) {
                    if (!values.count(name)) return;
                    json v = json::array();
                    for (int c = 0; c < width; ++c) v.push_back(values[name][k * size_t(width) + size_t(c)]);
                    child[key] = v;
                };
                put("TRANSLATION", "translation", 3);
                put("ROTATION", "rotation", 4);
                put("SCALE", "scale", 3);
                doc_["nodes"].push_back(std::move(child));
                children.push_back(doc_["nodes"].size() - 1);
            }
            json& node = doc_["nodes"][i];
            if (!node.contains("children") || !node["children"].is_array()) node["children"] = json::array();
            for (size_t c : children) node["children"].push_back(c);
            node.erase("mesh");
            node["extensions"].erase("EXT_mesh_gpu_instancing");
            if (node["extensions"].empty()) node.erase("extensions");
        }
    }
    // The triangles a mesh draws, from its accessors' counts (0 for a mesh not found).
    uint64_t triangles_of(const json& mesh) const {
        const json& meshes = array("meshes");
        if (!mesh.is_number_unsigned() || mesh.get<uint64_t>() >= meshes.size()) return 0;
        const json& m = meshes[mesh.get<size_t>()];
        if (!m.is_object() || !m.contains("primitives") || !m["primitives"].is_array()) return 0;
        const json& accessors = array("accessors");
        uint64_t n = 0;
        for (const json& p : m["primitives"]) {
            const json* counted = p.is_object() && p.contains("indices") ? &p["indices"]
                                  : p.is_object() && p.contains("attributes") && p["attributes"].is_object() &&
                                            p["attributes"].contains("POSITION")
                                      ? &p["attributes"]["POSITION"]
                                      : nullptr;
            if (counted && counted->is_number_unsigned() && counted->get<uint64_t>() < accessors.size())
                n = std::min(n + number(accessors[counted->get<size_t>()], "count", 0) / 3, kMaxInstancedTriangles + 1);
        }
        return n;  // (at most one past the limit: products of it with an instance count stay in range)
    }
    static void strip_transforms(json& node, const std::vector<json>& baked) {
        if (node.is_object()) {
            if (node.contains("index") && node.contains("extensions") && node["extensions"].is_object() &&
                node["extensions"].contains("KHR_texture_transform") &&
                std::find(baked.begin(), baked.end(), node["extensions"]["KHR_texture_transform"]) != baked.end()) {
                node["extensions"].erase("KHR_texture_transform");
                if (node["extensions"].empty()) node.erase("extensions");
            }
            for (auto& [key, value] : node.items()) strip_transforms(value, baked);
        } else if (node.is_array()) {
            for (auto& value : node) strip_transforms(value, baked);
        }
    }

    // One binary chunk holding every view, 4-byte aligned; the extensions decoded no longer listed.
    std::string write() {
        std::string bin;
        for (size_t i = 0; i < views_.size(); ++i) {
            json& v = doc_["bufferViews"][i];
            v["buffer"] = 0;
            v["byteOffset"] = bin.size();
            v["byteLength"] = views_[i].size();
            bin += views_[i];
            bin.resize((bin.size() + 3) / 4 * 4, '\0');
        }
        doc_["buffers"] = json::array({json{{"byteLength", bin.size()}}});
        for (const char* list : {"extensionsUsed", "extensionsRequired"})
            if (doc_.contains(list) && doc_[list].is_array()) {
                json kept = json::array();
                for (const auto& e : doc_[list])
                    if (!(e.is_string() && (e == "EXT_meshopt_compression" || e == "KHR_mesh_quantization" ||
                                            e == "EXT_texture_webp" || e == "EXT_mesh_gpu_instancing")))
                        kept.push_back(e);
                doc_[list] = kept;
            }
        std::string text = doc_.dump();
        text.resize((text.size() + 3) / 4 * 4, ' ');
        std::string out;
        const auto put = [&out](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
        out += "glTF";
        put(2);
        put(uint32_t(12 + 8 + text.size() + 8 + bin.size()));
        put(uint32_t(text.size()));
        put(kJsonChunk);
        out += text;
        put(uint32_t(bin.size()));
        put(kBinChunk);
        out += bin;
        return out;
    }

    const std::string& path_;
    GltfFile& f_;
    json& doc_;
    std::vector<std::string> buffers_, views_;
    std::map<size_t, size_t> converted_;  // accessor -> the view of its floats
};

}  // namespace

std::string unreadable_gltf_extension(const std::string& path) {
    const GltfFile f = read_gltf(path, false);
    return f.ok ? first_unreadable(f.doc) : "";
}

std::optional<std::string> plain_glb(const std::string& path) {
    const GltfFile probe = read_gltf(path, false);
    if (!probe.ok) return std::nullopt;
    const bool unreadable = !first_unreadable(probe.doc).empty();
    if (!unreadable && !any_in(probe.doc, "materials", base_colour_transform) &&
        !any_in(probe.doc, "textures", extension_source) && !any_in(probe.doc, "nodes", instancing))
        return std::nullopt;
    GltfFile f = read_gltf(path, true);
    try {
        return Decoder(path, f).glb();
    } catch (const json::exception& e) {  // a value of another type than glTF gives it (a string count, ...)
        if (!unreadable) return std::nullopt;
        throw_input_error(path, fmt::format("its glTF JSON has a value of the wrong type ({})", e.what()),
                          std::string("check that the file is complete, ") + kFix);
    } catch (const Error&) {
        // A file assimp reads by itself, decoded only for its textures or instances:
        // the reader says what is wrong with it, if anything.
        if (!unreadable) return std::nullopt;
        throw;
    }
}

}  // namespace shatter
