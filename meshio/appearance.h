// The input's appearance: what its surface looks like, beside load_mesh's positions (which the
// tet mesh needs joined by position, without normals, UVs or colours).
//
// load_appearance imports the same file with assimp (in a child process with a deadline, as
// load_mesh does), keeping texture coordinates (channel 0), vertex colours (set 0) and
// materials, and walks the node tree as load_mesh does (same order, same transforms), so that its
// triangles lie exactly where load_mesh's do (in the file's units: the caller scales both
// alike). Vertices are not joined: a vertex on a UV seam or a material boundary keeps one copy
// per side. Each material's base colour is AI_MATKEY_BASE_COLOR (glTF) or else the diffuse
// colour (white for assimp's default material), and its base colour texture the first BASE_COLOR or DIFFUSE texture: an embedded one
// ("*0" in glTF binaries, compressed: its file's bytes) or a file named relative to the mesh
// file. A texture that cannot be found or read is a warning (in `warnings`), not an error: the
// material keeps its base colour.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/model.h"

namespace shatter {

struct Appearance {
    TriangleMesh mesh;                         // in the file's units, vertices not joined
    std::vector<std::array<float, 2>> uv;      // per vertex of `mesh`; empty when no mesh has channel 0
    std::vector<std::array<float, 4>> colour;  // per vertex, linear RGBA; empty when no mesh has colours
    std::vector<uint32_t> material;            // per triangle, into `materials`
    std::vector<Material> materials;           // the file's materials (assimp's default one included)
    std::vector<std::string> warnings;         // textures not found or not read, and why

    // A file with nothing to show beyond its shape: no texture coordinates with a texture, no
    // colours, and every material white or assimp's default grey.
    bool plain() const;
};

// Throws shatter::Error(BadInput) as load_mesh does, for the same files.
Appearance load_appearance(const std::string& path);

// The MIME type of an encoded image by its first bytes ("image/png", "image/jpeg", "image/webp"), else by
// the file name's extension ("image/x-tga", "image/bmp", ...); "" when unknown.
std::string image_mime(const std::string& bytes, const std::string& name);

}  // namespace shatter
