// The files beside a mesh that its import may read (meshio/companions.h): what the mesh file or a
// material library it names names, in its folder or below, whatever the case; not what nobody
// names, not the mesh itself.
#include <gtest/gtest.h>

#include <filesystem>

#include "meshio/companions.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::TempDir;

TEST(CompanionFiles, AreTheFilesTheMeshOrItsMaterialLibraryName) {
    TempDir dir;
    std::filesystem::create_directories(dir.file("textures"));
    const std::string obj = dir.write("thing.obj", "mtllib thing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
    dir.write("thing.mtl", "newmtl a\nmap_Kd Skin.PNG\nnewmtl b\nmap_Kd textures/deep.jpg\n");
    dir.write("skin.png", "not really a png");
    dir.write("textures/deep.jpg", "nor a jpeg");
    dir.write("other.png", "named by nobody");
    dir.write("notes.txt", "thing.obj skin.png: not a companion kind of file");
    EXPECT_EQ(companion_files(obj), (std::vector<std::string>{"skin.png", "textures/deep.jpg", "thing.mtl"}));
}

// models/ and textures/ side by side (the appearance reader finds the texture there), and a
// mesh file saved as UTF-16 naming its material library.
TEST(CompanionFiles, IncludeWhatIsNamedInAFolderBesideTheMeshFilesOwnAndWhatUtf16Names) {
    TempDir dir;
    std::filesystem::create_directories(dir.file("models"));
    std::filesystem::create_directories(dir.file("textures"));
    std::string utf16 = "\xFF\xFE";
    for (char c : std::string("mtllib cart.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")) utf16 += std::string{c, '\0'};
    const std::string obj = dir.write("models/cart.obj", utf16);
    dir.write("models/cart.mtl", "newmtl a\nmap_Kd wood.png\n");
    dir.write("textures/wood.png", "not really a png");
    dir.write("textures/iron.png", "named by nobody");
    EXPECT_EQ(companion_files(obj), (std::vector<std::string>{"../textures/wood.png", "cart.mtl"}));
}

TEST(CompanionFiles, AMeshThatNamesNothingHasNone) {
    TempDir dir;
    const std::string off = dir.write("tri.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    dir.write("tri.png", "an image beside it, which it does not name");
    EXPECT_TRUE(companion_files(off).empty());
}

}  // namespace
}  // namespace shatter
