#include "meshio/archive.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <tuple>
#include <utility>

#include <assimp/Importer.hpp>
#include <fmt/format.h>
#include <minizip/unzip.h>
#include <spdlog/spdlog.h>

#include "core/error.h"
#include "meshio/mesh_load.h"

namespace shatter {

namespace fs = std::filesystem;

namespace {

const char* const kFix = "unpack the archive and give shatter the mesh file in it";

// How likely a format is to carry the model whole, 0 first; -1 for a file that is no mesh.
int format_rank(const std::string& name) {
    const std::string ext = lower_extension(name);
    static const std::vector<std::vector<std::string>> ranks = {
        {".glb", ".gltf"}, {".fbx"}, {".dae"}, {".obj"}, {".3ds"}, {".blend"}};
    for (size_t r = 0; r < ranks.size(); ++r)
        if (std::find(ranks[r].begin(), ranks[r].end(), ext) != ranks[r].end()) return int(r);
    static const Assimp::Importer importer;
    return !ext.empty() && importer.IsExtensionSupported(ext) ? int(ranks.size()) : -1;
}

// The entry's name as a relative path inside the folder, or "" for one that would leave it.
std::string safe_name(std::string name) {
    std::replace(name.begin(), name.end(), '\\', '/');
    if (name.empty() || name.front() == '/' || name.find(':') != std::string::npos) return "";
    for (const auto& part : fs::path(name))
        if (part == "..") return "";
    return name;
}

struct Unzip {
    unzFile file = nullptr;
    ~Unzip() {
        if (file) unzClose(file);
    }
};

}  // namespace

std::optional<MeshArchive> MeshArchive::open(const std::string& path) {
    if (lower_extension(path) != ".zip") return std::nullopt;
    if (read_file_head(path, 4) != std::string("PK\x03\x04", 4))
        throw_input_error(path, "is named .zip but is not a ZIP archive (its first bytes)", kFix);
    Unzip zip;
    zip.file = unzOpen64(path.c_str());
    if (!zip.file) throw_input_error(path, "cannot read the ZIP archive", kFix);
    MeshArchive a;
    std::string folder = (fs::temp_directory_path() / "shatter-archive-XXXXXX").string();
    if (!mkdtemp(folder.data())) throw_io_error(folder, "cannot make a temporary folder to unpack the archive into");
    a.folder_ = folder;

    struct Candidate {
        int rank;
        size_t depth;
        uint64_t bytes;
        std::string name;
    };
    std::vector<Candidate> meshes;
    uint64_t total = 0;
    size_t entries = 0;
    std::vector<char> buffer(1 << 16);
    for (int status = unzGoToFirstFile(zip.file); status == UNZ_OK; status = unzGoToNextFile(zip.file)) {
        if (++entries > kMaxArchiveEntries)
            throw_input_error(path, fmt::format("the archive holds more than {} files", kMaxArchiveEntries), kFix);
        unz_file_info64 info;
        char raw_name[4096];
        if (unzGetCurrentFileInfo64(zip.file, &info, raw_name, sizeof raw_name, nullptr, 0, nullptr, 0) != UNZ_OK)
            throw_input_error(path, "the archive's list of files is damaged", kFix);
        const std::string name = safe_name(std::string(raw_name, std::min<size_t>(info.size_filename, sizeof raw_name)));
        if (name.empty() || name.back() == '/') continue;  // a folder, or a name outside the archive
        const fs::path target = fs::path(folder) / name;
        std::error_code ec;
        fs::create_directories(target.parent_path(), ec);
        // A name an earlier entry took as a folder, or under an earlier file's name: skipped.
        if (ec || !fs::is_directory(target.parent_path()) || fs::is_directory(target)) continue;
        if (unzOpenCurrentFile(zip.file) != UNZ_OK)
            throw_input_error(path, fmt::format("its entry '{}' cannot be unpacked (encrypted, or a method ZIP readers "
                                                "rarely know)", name), kFix);
        std::ofstream out(target, std::ios::binary);
        uint64_t bytes = 0;
        int n = 0;
        while ((n = unzReadCurrentFile(zip.file, buffer.data(), unsigned(buffer.size()))) > 0) {
            bytes += uint64_t(n);
            total += uint64_t(n);
            if (total > kMaxArchiveBytes)
                throw_input_error(path, fmt::format("the archive unpacks to more than {} GB", kMaxArchiveBytes >> 30), kFix);
            out.write(buffer.data(), n);
        }
        unzCloseCurrentFile(zip.file);
        if (n < 0) throw_input_error(path, fmt::format("its entry '{}' is damaged (unzip error {})", name, n), kFix);
        if (!out) throw_io_error(target.string(), "cannot write the unpacked file");
        if (const int rank = format_rank(name); rank >= 0)
            meshes.push_back({rank, size_t(std::distance(fs::path(name).begin(), fs::path(name).end())), bytes, name});
    }
    if (meshes.empty())
        throw_input_error(path, "the archive holds no mesh file assimp reads",
                          "check that it is the model's download (glTF, FBX, OBJ, ...), or unpack it and give shatter "
                          "the mesh file");
    std::sort(meshes.begin(), meshes.end(), [](const Candidate& x, const Candidate& y) {
        return std::make_tuple(x.rank, x.depth, -int64_t(x.bytes), x.name) <
               std::make_tuple(y.rank, y.depth, -int64_t(y.bytes), y.name);
    });
    a.name_ = meshes.front().name;
    a.mesh_ = (fs::path(folder) / a.name_).string();
    for (size_t i = 1; i < meshes.size(); ++i) a.others_.push_back(meshes[i].name);
    return a;
}

MeshArchive::MeshArchive(MeshArchive&& other) noexcept
    : folder_(std::exchange(other.folder_, {})), mesh_(std::move(other.mesh_)), name_(std::move(other.name_)),
      others_(std::move(other.others_)) {}

MeshArchive& MeshArchive::operator=(MeshArchive&& other) noexcept {
    if (this != &other) {
        remove_folder();
        folder_ = std::exchange(other.folder_, {});
        mesh_ = std::move(other.mesh_);
        name_ = std::move(other.name_);
        others_ = std::move(other.others_);
    }
    return *this;
}

MeshArchive::~MeshArchive() { remove_folder(); }

void MeshArchive::remove_folder() {
    if (folder_.empty()) return;
    std::error_code ec;
    fs::remove_all(folder_, ec);
    folder_.clear();
}

}  // namespace shatter
