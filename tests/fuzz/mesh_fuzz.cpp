// libFuzzer target: mesh loading as prescore does it (prescore/prescore.cpp): assimp reads the
// file with its extension as the format hint (load_mesh), then the mesh checks (topology,
// degeneracies, CGAL self-intersections, volume), orientation and the Mesh_3 admission test.
// Mesh_3 itself is not run (seconds per input).
//
// Input: byte 0 picks the format (the extension of the scratch file), the rest is the file.
// Seeds: tests/fuzz/corpus/mesh/ are mesh files with that byte in front.
#include <cstdlib>
#include <string>
#include <string_view>

#include "meshio/mesh_load.h"
#include "prescore/mesh_check.h"
#include "tests/fuzz/fuzz_support.h"

namespace {
// The formats the README promises (assimp reads more; these are the ones users are told about).
const char* const kExtensions[] = {"obj", "ply", "stl", "off", "glb", "gltf", "3ds", "fbx"};
constexpr size_t kFormats = sizeof(kExtensions) / sizeof(kExtensions[0]);
// Self-intersection search is O(n log n) with a large constant; bounded so an iteration stays fast.
constexpr size_t kMaxCheckedTriangles = 20000;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // A reader that spins is killed at the import deadline and the file refused, as in
    // `shatter prescore` (meshio/mesh_load.cpp); here the deadline is 2 s, under libFuzzer's
    // 10 s hang limit, so that the target checks what shatter does with such a file.
    static const bool deadline_set = ::setenv("SHATTER_MESH_IMPORT_TIMEOUT", "2", 0) == 0;
    (void)deadline_set;
    if (size < 1) return 0;
    const std::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
    const std::string path = shatter::fuzz::scratch_file(bytes, kExtensions[data[0] % kFormats]);
    shatter::fuzz::expect_value_or_error([&] {
        shatter::TriangleMesh mesh = shatter::load_mesh(path, 1.0);
        if (mesh.triangles.size() > kMaxCheckedTriangles) return;
        const shatter::MeshCheck check = shatter::check_mesh(mesh);
        shatter::describe(check);
        if (check.closed() && check.volume < 0) shatter::orient_outward(mesh);
        std::string why;
        shatter::can_tetrahedralize(shatter::check_mesh(mesh, false), &why);
    });
    return 0;
}
