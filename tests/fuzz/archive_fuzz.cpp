// libFuzzer target: the archive reader in front of the mesh reader (meshio/archive.h, libarchive's
// ZIP, 7z, RAR and tar readers as a .zip name selects them: the archive's list of files, names that would leave the unpacked folder or clash, damaged and
// encrypted entries, the limits on what it unpacks). Input: a .zip file. Seeds:
// tests/fuzz/corpus/archive/ (a model site's glTF download of a cube, an archive whose names try
// to leave the folder).
#include <string_view>

#include "meshio/archive.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const std::string path = shatter::fuzz::scratch_file(bytes, "zip");
    shatter::fuzz::expect_value_or_error([&] { (void)shatter::MeshArchive::open(path); });
    return 0;
}
