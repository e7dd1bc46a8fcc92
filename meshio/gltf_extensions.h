// glTF files as web tools write them, made readable for the mesh reader (Debian's assimp 5.2).
// gltfpack, the usual optimizer for web assets, stores positions in two ways assimp cannot read:
//   KHR_mesh_quantization: integer attributes (positions scaled back by the node's transform;
//     gltfpack's default). assimp takes the integers' bytes for floats: a 1 m cube came out
//     1e-4 m by 1e-45 m.
//   EXT_meshopt_compression: meshoptimizer's compressed buffer views (gltfpack -c). assimp refuses
//     them as "a buffer with non-zero length missing the uri attribute".
// plain_glb decodes both (meshoptimizer's decoders, its filters for normals, rotations and
// exponents) into a GLB with float attributes and plain buffer views, which assimp then reads
// from memory: the same file otherwise (nodes, their transforms, materials, embedded images; a
// .gltf's images keep their uri, which the appearance reader resolves beside the file). Draco
// (KHR_draco_mesh_compression) needs none of this: Debian's assimp links libdraco.
// A third extension assimp reads but gets wrong: KHR_texture_transform (an offset, rotation and
// scale of the texture coordinates; gltfpack's quantized coordinates come with one, Blender
// writes one for a mapping node). assimp 5.2 turns the coordinates the other way round (the
// Khronos test asset's arrow points at its red marker) and shifts gltfpack's scaled ones; plain_glb
// applies the transform to the coordinates instead, also in a file that needs nothing else.
// And one assimp 5.2 does not know: EXT_texture_webp (a texture's WebP image, often without a PNG
// fallback; glTF-Transform's and gltfpack's WebP texture compression), which plain_glb makes the
// texture's source (meshio/image_decode.h decodes WebP; a KTX2 image of KHR_texture_basisu, which
// nothing here decodes, too, so that the appearance reader names it); and EXT_mesh_gpu_instancing (one node
// drawing its mesh at many places; glTF-Transform's `optimize` writes every repeated mesh so),
// which assimp 5.2 draws once: plain_glb makes each instance a child node.
#pragma once

#include <optional>
#include <string>

namespace shatter {

// The first of those extensions that a .glb's or .gltf's extensionsRequired lists (the compression
// before the quantization that comes with it), or "" (also for a file that is not glTF, or whose
// JSON does not parse: the reader says what is wrong with it).
std::string unreadable_gltf_extension(const std::string& path);

// The file as a plain GLB when unreadable_gltf_extension finds one, a material's base colour
// texture has a texture transform, a texture a WebP image or a node instances, else nullopt. Throws Error(BadInput) naming the file and what
// is out of bounds or not decodable, with the gltfpack command that writes the file without
// them; a file that needs decoding only for those textures or instances and cannot be decoded is left
// to assimp (nullopt), which reads it as before.
std::optional<std::string> plain_glb(const std::string& path);

}  // namespace shatter
