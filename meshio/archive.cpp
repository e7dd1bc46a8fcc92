#include "meshio/archive.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <tuple>
#include <utility>

#include <archive.h>
#include <archive_entry.h>
#include <assimp/Importer.hpp>
#include <fmt/format.h>

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

// The archive formats read, by the file name's ending.
bool archive_name(const std::string& path) {
    const std::string name = lower_case(fs::path(path).filename().string());
    for (const char* end : {".zip", ".7z", ".rar", ".tar", ".tar.gz", ".tgz", ".tar.bz2", ".tar.xz", ".txz"}) {
        const std::string e = end;
        if (name.size() > e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0) return true;
    }
    return false;
}

struct Reader {
    archive* a = archive_read_new();
    ~Reader() { archive_read_free(a); }
};

}  // namespace

std::optional<MeshArchive> MeshArchive::open(const std::string& path, const std::string& member) {
    if (!archive_name(path)) return std::nullopt;
    Reader reader;
    archive* in = reader.a;
    // These formats only (libarchive reads many more, some of which name other files on disk).
    archive_read_support_format_zip(in);
    archive_read_support_format_7zip(in);
    archive_read_support_format_rar(in);
    archive_read_support_format_rar5(in);
    archive_read_support_format_tar(in);
    archive_read_support_filter_gzip(in);
    archive_read_support_filter_bzip2(in);
    archive_read_support_filter_xz(in);
    const auto why = [in] { return std::string(archive_error_string(in) ? archive_error_string(in) : "unknown error"); };
    if (archive_read_open_filename(in, path.c_str(), 1 << 16) != ARCHIVE_OK)
        throw_input_error(path, "cannot read the archive (" + why() + ")", kFix);
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
    archive_entry* entry = nullptr;
    int status = ARCHIVE_OK;
    while ((status = archive_read_next_header(in, &entry)) == ARCHIVE_OK || status == ARCHIVE_WARN) {
        if (++entries > kMaxArchiveEntries)
            throw_input_error(path, fmt::format("the archive holds more than {} files", kMaxArchiveEntries), kFix);
        const char* raw_name = archive_entry_pathname(entry);
        // Regular files only (folders are made as needed; links and devices are skipped).
        if (archive_entry_filetype(entry) != AE_IFREG || !raw_name) continue;
        const std::string name = safe_name(raw_name);
        if (name.empty() || name.back() == '/') continue;  // a name outside the folder
        const fs::path target = fs::path(folder) / name;
        std::error_code ec;
        fs::create_directories(target.parent_path(), ec);
        // A name an earlier entry took as a folder, or under an earlier file's name: skipped.
        if (ec || !fs::is_directory(target.parent_path()) || fs::is_directory(target)) continue;
        std::ofstream out(target, std::ios::binary);
        uint64_t bytes = 0;
        la_ssize_t n = 0;
        while ((n = archive_read_data(in, buffer.data(), buffer.size())) > 0) {
            bytes += uint64_t(n);
            total += uint64_t(n);
            if (total > kMaxArchiveBytes)
                throw_input_error(path, fmt::format("the archive unpacks to more than {} GB", kMaxArchiveBytes >> 30), kFix);
            out.write(buffer.data(), std::streamsize(n));
        }
        if (n < 0)
            throw_input_error(path, fmt::format("its entry '{}' cannot be unpacked ({})", name, why()), kFix);
        if (!out) throw_io_error(target.string(), "cannot write the unpacked file");
        if (const int rank = format_rank(name); rank >= 0)
            meshes.push_back({rank, size_t(std::distance(fs::path(name).begin(), fs::path(name).end())), bytes, name});
    }
    if (status != ARCHIVE_EOF) throw_input_error(path, "the archive is damaged (" + why() + ")", kFix);
    if (meshes.empty())
        throw_input_error(path, "the archive holds no mesh file assimp reads",
                          "check that it is the model's download (glTF, FBX, OBJ, ...), or unpack it and give shatter "
                          "the mesh file");
    std::sort(meshes.begin(), meshes.end(), [](const Candidate& x, const Candidate& y) {
        return std::make_tuple(x.rank, x.depth, -int64_t(x.bytes), x.name) <
               std::make_tuple(y.rank, y.depth, -int64_t(y.bytes), y.name);
    });
    if (!member.empty()) {
        const auto it = std::find_if(meshes.begin(), meshes.end(), [&](const Candidate& c) { return c.name == member; });
        if (it == meshes.end()) {
            std::string names;
            for (const Candidate& c : meshes) names += (names.empty() ? "" : ", ") + c.name;
            throw_input_error(path, fmt::format("mesh.member = \"{}\" is no mesh file in the archive", member),
                              "use one of its mesh files: " + names);
        }
        std::rotate(meshes.begin(), it, it + 1);  // first, the others in their order
    }
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
