// Meshes in an archive (meshio/archive.h): the archive is unpacked into a temporary folder that
// goes with the MeshArchive, its likeliest mesh is chosen (glTF before OBJ), the files beside it
// (textures, the .bin) are where it names them, and entries that would leave the folder are
// never written.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/error.h"
#include "meshio/appearance.h"
#include "meshio/archive.h"
#include "meshio/mesh_load.h"

namespace shatter {
namespace {

namespace fs = std::filesystem;

const std::string kFixtures = SHATTER_SOURCE_DIR "/tests/fixtures/";

// A model site's glTF download (scene.gltf, scene.bin, textures/) with the OBJ it came from under
// source/, zipped and as a .tar.gz: the glTF is read, textured, and the folder is gone with the
// archive.
class Downloads : public testing::TestWithParam<const char*> {};
INSTANTIATE_TEST_SUITE_P(MeshArchive, Downloads, testing::Values("textured_cube.zip", "textured_cube.tar.gz"));

TEST_P(Downloads, TheGltfIsChosenAndItsFilesAreBesideIt) {
    fs::path folder;
    {
        std::optional<MeshArchive> a = MeshArchive::open(kFixtures + "archive/" + GetParam());
        ASSERT_TRUE(a.has_value());
        EXPECT_EQ(a->mesh_name(), "scene.gltf");
        ASSERT_EQ(a->other_meshes().size(), 1u);
        EXPECT_EQ(a->other_meshes()[0], "source/textured_cube.obj");
        folder = fs::path(a->mesh_path()).parent_path();
        EXPECT_TRUE(fs::exists(folder / "textures" / "quadrants.png"));
        EXPECT_EQ(load_mesh_file(a->mesh_path()).mesh.triangles.size(), 12u);
        const Appearance look = load_appearance(a->mesh_path());
        EXPECT_TRUE(look.warnings.empty()) << look.warnings.front();
        size_t textured = 0;
        for (const Material& m : look.materials) textured += !m.texture.empty();
        EXPECT_EQ(textured, 1u);
        // Moved, the folder stays until the last owner goes.
        MeshArchive moved = std::move(*a);
        a.reset();
        EXPECT_TRUE(fs::exists(folder));
    }
    EXPECT_FALSE(fs::exists(folder));
}

// [mesh] member picks another mesh in the archive; one it does not hold is refused with the list.
TEST(MeshArchive, AMemberNamedIsReadAndOneNotThereIsRefused) {
    const std::string zip = kFixtures + "archive/textured_cube.zip";
    const std::optional<MeshArchive> a = MeshArchive::open(zip, "source/textured_cube.obj");
    ASSERT_TRUE(a.has_value());
    EXPECT_EQ(a->mesh_name(), "source/textured_cube.obj");
    EXPECT_EQ(a->other_meshes(), std::vector<std::string>{"scene.gltf"});
    EXPECT_EQ(load_mesh_file(a->mesh_path()).mesh.triangles.size(), 12u);
    try {
        (void)MeshArchive::open(zip, "chair.obj");
        ADD_FAILURE() << "a member the archive does not hold was taken";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        EXPECT_NE(std::string(e.what()).find("use one of its mesh files: scene.gltf, source/textured_cube.obj"),
                  std::string::npos) << e.what();
    }
}

TEST(MeshArchive, AFileThatIsNoArchiveIsReadAsItIs) {
    EXPECT_FALSE(MeshArchive::open(kFixtures + "gltfpack/textured_cube.obj").has_value());
}

// Entries named "../x" or "/x" are not written outside the folder; an archive with no mesh file
// left is refused naming it.
TEST(MeshArchive, EntriesThatWouldLeaveTheFolderAreNotWritten) {
    const std::string path = SHATTER_SOURCE_DIR "/tests/bad_inputs/archive-escape.zip";
    try {
        (void)MeshArchive::open(path);
        ADD_FAILURE() << "an archive without a mesh inside its folder was taken";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        EXPECT_NE(std::string(e.what()).find("holds no mesh file"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(fs::temp_directory_path() / "shatter-escaped-test.obj"));
    EXPECT_FALSE(fs::exists("/tmp/shatter-absolute-test.obj"));
}

}  // namespace
}  // namespace shatter
