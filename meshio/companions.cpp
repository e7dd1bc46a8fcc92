#include "meshio/companions.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <string_view>

#include "meshio/mesh_load.h"

namespace shatter {

namespace {

namespace fs = std::filesystem;

// The file's first `limit` bytes in lower case; a UTF-16 file's (a byte-order mark first) without
// its NULs, so that the names in it read as ASCII.
std::string read_lower(const fs::path& path, size_t limit) {
    std::string head = read_file_head(path.string(), limit);
    if (head.rfind("\xFF\xFE", 0) == 0 || head.rfind("\xFE\xFF", 0) == 0) std::erase(head, '\0');
    return lower_case(std::move(head));
}

bool companion_extension(const std::string& ext) {
    static constexpr std::array<std::string_view, 20> kExtensions = {
        ".png", ".jpg", ".jpeg", ".tga", ".bmp", ".gif", ".tif",  ".tiff", ".dds", ".ktx",
        ".ktx2", ".webp", ".hdr", ".psd", ".pic", ".pnm", ".ppm", ".pgm",  ".mtl", ".bin"};
    return std::find(kExtensions.begin(), kExtensions.end(), ext) != kExtensions.end();
}

}  // namespace

std::vector<fs::path> folders_beside(const fs::path& dir) {
    std::error_code ec;
    fs::path own = fs::absolute(dir.empty() ? fs::path(".") : dir, ec).lexically_normal();
    if (own.filename().empty()) own = own.parent_path();
    std::vector<fs::path> folders;
    if (!own.has_relative_path()) return folders;
    for (fs::directory_iterator it(own.parent_path(), fs::directory_options::skip_permission_denied, ec), end;
         !ec && it != end; it.increment(ec))
        if (it->is_directory(ec) && it->path() != own) folders.push_back(it->path());
    std::sort(folders.begin(), folders.end());
    if (folders.size() > kSiblingFolders) folders.resize(kSiblingFolders);
    return folders;
}

std::vector<std::string> companion_files(const std::string& mesh_path) {
    const fs::path mesh(mesh_path);
    const fs::path dir = mesh.has_parent_path() ? mesh.parent_path() : fs::path(".");
    std::error_code ec;
    std::vector<fs::path> candidates;
    for (fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec), end;
         !ec && it != end && candidates.size() < kCompanionCandidates; it.increment(ec)) {
        if (it.depth() >= 2) it.disable_recursion_pending();
        if (!it->is_regular_file(ec) || fs::equivalent(it->path(), mesh, ec)) continue;
        if (companion_extension(lower_extension(it->path().string()))) candidates.push_back(it->path());
    }
    // The folders beside the mesh file's own: their files, not below.
    for (const fs::path& folder : folders_beside(dir))
        for (fs::directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec), end;
             !ec && it != end && candidates.size() < kCompanionCandidates; it.increment(ec))
            if (it->is_regular_file(ec) && companion_extension(lower_extension(it->path().string())))
                candidates.push_back(dir / ".." / folder.filename() / it->path().filename());
    std::sort(candidates.begin(), candidates.end());
    std::string text = read_lower(mesh, kCompanionSearchBytes);
    std::vector<std::string> found;
    std::vector<char> taken(candidates.size(), 0);
    // Twice: material libraries named by the mesh file first, then what they name as well.
    for (int pass = 0; pass < 2; ++pass) {
        std::string more;
        for (size_t i = 0; i < candidates.size(); ++i) {
            if (taken[i] || text.find(lower_case(candidates[i].filename().string())) == std::string::npos) continue;
            taken[i] = 1;
            found.push_back(fs::relative(candidates[i], dir, ec).generic_string());
            if (lower_extension(candidates[i].string()) == ".mtl") more += read_lower(candidates[i], kCompanionSearchBytes);
        }
        if (more.empty()) break;
        text = std::move(more);
    }
    std::sort(found.begin(), found.end());
    return found;
}

}  // namespace shatter
