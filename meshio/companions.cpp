#include "meshio/companions.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <string_view>

#include "meshio/mesh_load.h"

namespace shatter {

namespace {

namespace fs = std::filesystem;

std::string read_lower(const fs::path& path, size_t limit) { return lower_case(read_file_head(path.string(), limit)); }

bool companion_extension(const std::string& ext) {
    static constexpr std::array<std::string_view, 20> kExtensions = {
        ".png", ".jpg", ".jpeg", ".tga", ".bmp", ".gif", ".tif",  ".tiff", ".dds", ".ktx",
        ".ktx2", ".webp", ".hdr", ".psd", ".pic", ".pnm", ".ppm", ".pgm",  ".mtl", ".bin"};
    return std::find(kExtensions.begin(), kExtensions.end(), ext) != kExtensions.end();
}

}  // namespace

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
