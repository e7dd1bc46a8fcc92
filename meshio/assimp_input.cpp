// The user's file made readable for assimp 5.2. Design notes: assimp_input.h.
#include "meshio/assimp_input.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/MemoryIOWrapper.h>
#include <archive.h>
#include <archive_entry.h>

#include <array>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "meshio/archive.h"
#include "meshio/gltf_extensions.h"
#include "meshio/mesh_load.h"

namespace shatter {
namespace {

void append_utf8(std::string& out, uint32_t c) {
    if (c < 0x80) {
        out += static_cast<char>(c);
    } else if (c < 0x800) {
        out += static_cast<char>(0xC0 | (c >> 6));
        out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
        out += static_cast<char>(0xE0 | (c >> 12));
        out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (c & 0x3F));
    } else {
        out += static_cast<char>(0xF0 | (c >> 18));
        out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (c & 0x3F));
    }
}

// A file as assimp opens it, given instead as the text read_scene's notes describe when it is
// UTF-16 or an OFF file with comments; every other file (and every binary one: only the first
// two bytes are read to tell) is passed through as it is.
class ReadableText : public Assimp::DefaultIOSystem {
public:
    Assimp::IOStream* Open(const char* file, const char* mode) override {
        Assimp::IOStream* stream = DefaultIOSystem::Open(file, mode);
        if (stream == nullptr || std::strchr(mode, 'w') != nullptr) return stream;
        unsigned char head[2] = {0, 0};
        const bool got = stream->Read(head, 1, 2) == 2;
        const bool utf16 = got && ((head[0] == 0xFF && head[1] == 0xFE) || (head[0] == 0xFE && head[1] == 0xFF));
        const bool off = lower_extension(file) == ".off";
        std::optional<std::string> text;
        if (utf16 || off) {
            std::string bytes(stream->FileSize(), '\0');
            stream->Seek(0, aiOrigin_SET);
            bytes.resize(stream->Read(bytes.data(), 1, bytes.size()));
            text = utf16 ? utf16_as_utf8(bytes) : std::optional<std::string>(bytes);
            if (text && off) {
                if (std::optional<std::string> readable = off_for_assimp(*text)) text = std::move(readable);
                else if (!utf16) text.reset();
            }
        }
        if (!text) {
            stream->Seek(0, aiOrigin_SET);
            return stream;
        }
        Close(stream);
        auto* buffer = new uint8_t[text->size()];
        std::memcpy(buffer, text->data(), text->size());
        return new Assimp::MemoryIOStream(buffer, text->size(), true);
    }
};

// The fields of one line, split at spaces and tabs.
std::vector<std::string_view> fields(std::string_view line) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        const size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

// The first file of a ZIP archive, whole; throws Error(BadInput) naming `path` when it cannot be
// read or unpacks past kMaxArchiveBytes.
std::string first_zip_entry(const std::string& path) {
    std::unique_ptr<archive, int (*)(archive*)> in(archive_read_new(), archive_read_free);
    const auto why = [&in] {
        const char* e = archive_error_string(in.get());
        return std::string(e != nullptr ? e : "no reason given");
    };
    archive_read_support_format_zip(in.get());
    archive_entry* entry = nullptr;
    const std::string fix = "unzip it and give shatter the file inside, or export it again";
    if (archive_read_open_filename(in.get(), path.c_str(), 1 << 16) != ARCHIVE_OK)
        throw_input_error(path, "cannot read the ZIP archive: " + why(), fix);
    int status;
    while ((status = archive_read_next_header(in.get(), &entry)) == ARCHIVE_OK || status == ARCHIVE_WARN) {
        if (archive_entry_filetype(entry) != AE_IFREG) continue;
        std::string out;
        char buffer[1 << 16];
        la_ssize_t n;
        while ((n = archive_read_data(in.get(), buffer, sizeof buffer)) > 0) {
            out.append(buffer, static_cast<size_t>(n));
            if (out.size() > kMaxArchiveBytes)
                throw_input_error(path, fmt::format("the file inside unpacks past {} bytes", kMaxArchiveBytes), fix);
        }
        if (n < 0) throw_input_error(path, "cannot unpack: " + why(), fix);
        return out;
    }
    throw_input_error(path, "the ZIP archive holds no file", fix);
}

}  // namespace

std::optional<std::string> utf16_as_utf8(const std::string& bytes) {
    if (bytes.size() < 2 || bytes.size() % 2 != 0) return std::nullopt;
    const auto byte = [&bytes](size_t i) { return static_cast<uint32_t>(static_cast<unsigned char>(bytes[i])); };
    bool little;
    if (byte(0) == 0xFF && byte(1) == 0xFE) little = true;
    else if (byte(0) == 0xFE && byte(1) == 0xFF) little = false;
    else return std::nullopt;
    const auto unit = [&](size_t i) { return little ? byte(i) | byte(i + 1) << 8 : byte(i) << 8 | byte(i + 1); };
    std::string out;
    out.reserve(bytes.size() / 2);
    for (size_t i = 2; i < bytes.size(); i += 2) {
        uint32_t c = unit(i);
        if (c == 0) return std::nullopt;
        if (c >= 0xD800 && c < 0xDC00) {  // a high surrogate: its low half follows
            if (i + 3 >= bytes.size()) return std::nullopt;
            const uint32_t low = unit(i + 2);
            if (low < 0xDC00 || low >= 0xE000) return std::nullopt;
            c = 0x10000 + ((c - 0xD800) << 10) + (low - 0xDC00);
            i += 2;
        } else if (c >= 0xDC00 && c < 0xE000) {
            return std::nullopt;
        }
        append_utf8(out, c);
    }
    return out;
}

std::optional<std::string> off_for_assimp(const std::string& text) {
    // The lines that hold something, comments taken out.
    std::vector<std::string> lines;
    bool changed = false;
    size_t i = 0;
    while (i < text.size()) {
        size_t end = text.find('\n', i);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(i, end - i);
        i = end + 1;
        if (const size_t hash = line.find('#'); hash != std::string::npos) {
            line.resize(hash);
            changed = true;
        }
        if (fields(line).empty()) {
            changed = changed || !line.empty();
            continue;
        }
        lines.push_back(std::move(line));
    }
    // The header ([ST][C][N]OFF, its counts on its own line or the next) and, when its vertices
    // have colours, each vertex line whose colour has three components (x y z, [nx ny nz], r g b,
    // [s t]) gets an alpha of 1.
    if (!lines.empty()) {
        const std::vector<std::string_view> head = fields(lines[0]);
        const std::string_view key = head[0];
        const bool off = key.size() >= 3 && key.substr(key.size() - 3) == "OFF";
        const std::string_view prefix = off ? key.substr(0, key.size() - 3) : std::string_view();
        if (off && prefix.find('C') != std::string_view::npos) {
            const size_t counts_line = head.size() > 1 ? 0 : 1;
            const size_t normals = prefix.find('N') != std::string_view::npos ? 3 : 0;
            const size_t texture = prefix.rfind("ST", 0) == 0 ? 2 : 0;
            unsigned long vertices = 0;
            if (counts_line < lines.size()) {
                const std::vector<std::string_view> counts = fields(lines[counts_line]);
                const std::string_view n = counts[counts_line == 0 ? 1 : 0];
                std::from_chars(n.data(), n.data() + n.size(), vertices);
            }
            for (size_t v = 0; v < vertices && counts_line + 1 + v < lines.size(); ++v) {
                std::string& line = lines[counts_line + 1 + v];
                const std::vector<std::string_view> f = fields(line);
                if (f.size() != 3 + normals + 3 + texture) continue;
                const size_t after_blue = static_cast<size_t>(f[5 + normals].data() - line.data()) + f[5 + normals].size();
                line.insert(after_blue, " 1");
                changed = true;
            }
        }
    }
    if (!changed) return std::nullopt;
    std::string out;
    out.reserve(text.size());
    for (const std::string& line : lines) out += line + "\n";
    return out;
}

std::string jobj_as_obj(const std::string& text, const std::string& path) {
    const std::string fix =
        "a .jobj file (glmark2's jellyfish) has lines \"v X Y Z\" and \"i N\", three indices per triangle, counted "
        "from 0; export the model as OBJ or glTF instead";
    struct Triangle {
        std::array<unsigned long, 3> v;
        size_t line;  // of its last index
    };
    std::string obj;
    std::vector<Triangle> triangles;
    std::vector<unsigned long> pending;
    size_t vertices = 0, line = 0, i = 0;
    while (i < text.size()) {
        size_t end = text.find('\n', i);
        if (end == std::string::npos) end = text.size();
        ++line;
        const std::vector<std::string_view> f = fields(std::string_view(text.data() + i, end - i));
        i = end + 1;
        const auto bad = [&](const std::string& problem) { throw_input_error(fmt::format("{}:{}", path, line), problem, fix); };
        if (f.empty()) continue;
        if (f[0] == "v") {
            if (f.size() < 4) bad("a vertex line needs three coordinates");
            for (int k = 1; k <= 3; ++k) {
                double x = 0;
                const auto r = std::from_chars(f[k].data(), f[k].data() + f[k].size(), x);
                if (r.ec != std::errc() || r.ptr != f[k].data() + f[k].size())
                    bad(fmt::format("the coordinate \"{}\" is not a number", f[k]));
            }
            obj += fmt::format("v {} {} {}\n", f[1], f[2], f[3]);
            ++vertices;
        } else if (f[0] == "i") {
            unsigned long index = 0;
            const bool one = f.size() == 2;
            const auto r = one ? std::from_chars(f[1].data(), f[1].data() + f[1].size(), index) : std::from_chars_result{};
            if (!one || r.ec != std::errc() || r.ptr != f[1].data() + f[1].size())
                bad("an index line needs one whole number, \"i N\"");
            pending.push_back(index);
            if (pending.size() == 3) {
                triangles.push_back({{pending[0], pending[1], pending[2]}, line});
                pending.clear();
            }
        }
    }
    if (!pending.empty())
        throw_input_error(path, fmt::format("{} index lines left over: they must come in threes", pending.size()), fix);
    // An index may name a vertex listed after it: checked once all are read.
    for (const Triangle& t : triangles) {
        for (unsigned long v : t.v)
            if (v >= vertices)
                throw_input_error(fmt::format("{}:{}", path, t.line),
                                  fmt::format("the index {} names no vertex (there are {}, counted from 0)", v, vertices),
                                  "check that the file is complete");
        obj += fmt::format("f {} {} {}\n", t.v[0] + 1, t.v[1] + 1, t.v[2] + 1);
    }
    return obj;
}

bool shows_vertex_colours(const aiMesh& mesh) {
    if (!mesh.HasVertexColors(0)) return false;
    for (unsigned i = 0; i < mesh.mNumVertices; ++i)
        if (!no_vertex_colour(mesh.mColors[0][i])) return true;
    return false;
}

const aiScene* read_scene(Assimp::Importer& importer, const std::string& path) {
    if (const std::optional<std::string> glb = plain_glb(path))
        return importer.ReadFileFromMemory(glb->data(), glb->size(), 0, "glb");
    if (lower_extension(path) == ".jobj") {
        const std::string obj = jobj_as_obj(read_file(path, "mesh file"), path);
        return importer.ReadFileFromMemory(obj.data(), obj.size(), 0, "obj");
    }
    // AMF may be compressed as a ZIP of its one XML file (the specification allows it; OpenSCAD
    // and slicers write it so); assimp 5.2 reads only the XML.
    if (lower_extension(path) == ".amf" && read_file_head(path, 4) == std::string("PK\x03\x04", 4)) {
        const std::string xml = first_zip_entry(path);
        return importer.ReadFileFromMemory(xml.data(), xml.size(), 0, "amf");
    }
    importer.SetIOHandler(new ReadableText);
    return importer.ReadFile(path, 0);
}

}  // namespace shatter
