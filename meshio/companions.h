// The files beside a mesh file that its import may read as well: an OBJ's material library and
// the images it names, a glTF's buffers and images, the textures a Collada, FBX or 3DS file
// names. Found without importing: every regular file in the mesh file's folder or below it (two
// levels down), or in a folder beside that folder (the first kSiblingFolders in name order:
// models/ and textures/ side by side, where the appearance reader looks too), with an image,
// material-library or buffer extension whose name appears in the mesh file (read as text, a
// UTF-16 file's NULs left out), or in a material library found so, compared without case. So a
// stage cache keyed by the mesh file's bytes also sees a texture or a buffer change.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace shatter {

// At most this many files are looked at, and only the first 256 MB of a mesh file is read for
// names: a folder or a file past either gives the files found within them.
inline constexpr size_t kCompanionCandidates = 4096;
inline constexpr size_t kCompanionSearchBytes = size_t(256) << 20;
// Folders beside the mesh file's own searched for the files it names (not below them).
inline constexpr size_t kSiblingFolders = 64;

// The folders beside `dir` (the other folders in its parent, as absolute paths), the first
// kSiblingFolders in name order: where models/ and textures/ sit side by side. Empty for a root.
std::vector<std::filesystem::path> folders_beside(const std::filesystem::path& dir);

// Paths relative to the mesh file's folder ("../textures/wood.png" for one beside it),
// '/'-separated, sorted.
std::vector<std::string> companion_files(const std::string& mesh_path);

}  // namespace shatter
