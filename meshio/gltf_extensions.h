// glTF extensions the mesh reader (Debian's assimp 5.2) cannot read, refused before it reads the
// file. Both change how positions are stored, and both come from gltfpack, the usual optimizer
// for web assets:
//   KHR_mesh_quantization: integer positions scaled by the node's transform (gltfpack's default).
//     assimp takes the integers' bytes for floats: a 1 m cube came out 1e-4 m by 1e-45 m, refused
//     as a mesh without area, which is not the reason.
//   EXT_meshopt_compression: meshoptimizer's compressed buffers (gltfpack -c). assimp refuses them
//     as "a buffer with non-zero length missing the uri attribute".
// Draco (KHR_draco_mesh_compression) is read: Debian's assimp is built with it.
#pragma once

#include <string>

namespace shatter {

// For a .glb or .gltf file: the first of those extensions (the compression, then the quantization
// that comes with it) its extensionsRequired lists, or ""
// (also for a file that is not glTF or whose JSON does not parse: the reader says what is wrong).
std::string unreadable_gltf_extension(const std::string& path);

// Throws Error(BadInput) naming `path`, the extension and how to write the file without it, when
// unreadable_gltf_extension finds one.
void check_gltf_extensions(const std::string& path);

}  // namespace shatter
