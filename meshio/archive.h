// A mesh that comes in an archive, as model sites hand them out (Sketchfab's "glTF" download:
// scene.gltf, scene.bin and textures/ in one .zip; others pack an OBJ with its .mtl and images as
// .zip, .rar or .7z). ZIP, 7z, RAR (4 and 5) and tar (plain, gzip, bzip2, xz) are read, by
// libarchive, by the file name's ending.
// The archive is unpacked into a temporary folder that lives as long as the MeshArchive, and one
// mesh file in it is chosen: the format most likely to carry the model whole (glTF, then FBX,
// Collada, OBJ, 3DS, Blender's .blend, then any other file assimp reads), then the one nearest the
// archive's top, then the largest (a model's finest level of detail), then by name.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace shatter {

class MeshArchive {
public:
    // nullopt when `path` is not named as one of those archives (formats that are ZIP archives
    // inside, 3MF, Collada's .zae, USDZ, are the mesh reader's to take or refuse). Throws
    // Error(BadInput) naming the archive when it cannot be read, holds no mesh file, or unpacks
    // past kMaxArchiveBytes or kMaxArchiveEntries; links, and entries whose names would leave the
    // folder ("..", absolute) or clash with an earlier entry's (a file where a folder was, or the
    // other way round), are skipped.
    // `member`: the mesh file to read, by its name in the archive (BadInput, listing the archive's
    // mesh files, when it is not there); "": the likeliest.
    static std::optional<MeshArchive> open(const std::string& path, const std::string& member = "");

    const std::string& mesh_path() const { return mesh_; }  // the chosen mesh, in the unpacked folder
    const std::string& mesh_name() const { return name_; }  // its name inside the archive
    const std::vector<std::string>& other_meshes() const { return others_; }  // names of the rest

    MeshArchive(MeshArchive&& other) noexcept;
    MeshArchive& operator=(MeshArchive&& other) noexcept;
    MeshArchive(const MeshArchive&) = delete;
    MeshArchive& operator=(const MeshArchive&) = delete;
    ~MeshArchive();

private:
    MeshArchive() = default;
    void remove_folder();
    std::string folder_, mesh_, name_;
    std::vector<std::string> others_;
};

// How the mesh is chosen, for the messages that say so.
inline constexpr const char* kArchiveChoice = "glTF, then FBX, Collada, OBJ, 3DS; nearest the top; the largest";

inline constexpr unsigned long long kMaxArchiveBytes = 4ull << 30;  // unpacked, in all
inline constexpr size_t kMaxArchiveEntries = 100000;

}  // namespace shatter
