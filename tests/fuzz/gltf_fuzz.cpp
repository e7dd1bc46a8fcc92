// libFuzzer target: the glTF decoder in front of assimp (meshio/gltf_extensions.h: GLB chunks, the
// JSON, meshopt-compressed buffer views, quantized accessors, texture transforms), in this process
// (the mesh target reaches it only inside the import's child process, where a crash is reported,
// not found). Input: a .glb file. Seeds: tests/fuzz/corpus/gltf/ (gltfpack's quantized and
// compressed cubes, a cube whose texture coordinates a texture transform brings back, a cube
// with a WebP texture, three instances of a cube, a plain tetrahedron).
#include <string_view>

#include "meshio/gltf_extensions.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const std::string path = shatter::fuzz::scratch_file(bytes, "glb");
    shatter::fuzz::expect_value_or_error([&] { (void)shatter::plain_glb(path); });
    return 0;
}
