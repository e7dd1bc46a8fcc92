// `--set SECTION.KEY=VALUE` overrides (shatter run, batch sweeps): applied before validation, so
// an override is checked exactly like the file's own value, and its errors name the override.
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/shot.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::TempDir;

const char* kShot = R"([mesh]
path = "m.obj"
[material]
alpha = 1.0
[render]
width = 1280
)";

std::string override_error(const std::string& path, const std::vector<std::string>& overrides) {
    try {
        load_shot(path, overrides);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(ShotOverrides, ReplaceAndAddKeysOfEveryType) {
    TempDir dir;
    const std::string path = dir.write("s.toml", kShot);
    const Shot s = load_shot(path, {"material.alpha=0.25", "render.width=640", "prescore.hollow=\"12mm\"",
                                    "mesh.repair=never", "object.position=[0, 2, 0]", "render.shadows=false"});
    EXPECT_DOUBLE_EQ(s.material.alpha, 0.25);
    EXPECT_EQ(s.render.width, 640u);
    ASSERT_TRUE(s.prescore.hollow);
    EXPECT_DOUBLE_EQ(s.prescore.hollow->value, 0.012);
    EXPECT_EQ(s.mesh.repair, RepairMode::Never);  // a bare word is a string
    EXPECT_DOUBLE_EQ(s.object.pose.position.y(), 2.0);
    EXPECT_FALSE(s.render.shadows);
    EXPECT_EQ(s.render.height, 720u);  // untouched keys keep the file's or the default value
}

TEST(ShotOverrides, BadValuesAreCheckedLikeTheFileAndNameTheOverride) {
    TempDir dir;
    const std::string path = dir.write("s.toml", kShot);
    const std::string range = override_error(path, {"material.alpha=-1"});
    EXPECT_NE(range.find("--set material.alpha=-1"), std::string::npos) << range;
    EXPECT_NE(range.find("outside"), std::string::npos) << range;
    const std::string type = override_error(path, {"render.width=wide"});
    EXPECT_NE(type.find("--set render.width=wide"), std::string::npos) << type;
    const std::string unknown = override_error(path, {"material.alpah=1"});
    EXPECT_NE(unknown.find("--set material.alpah=1"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("did you mean 'alpha'"), std::string::npos) << unknown;
    EXPECT_NE(override_error(path, {"alpha=1"}).find("not SECTION.KEY=VALUE"), std::string::npos);
    EXPECT_NE(override_error(path, {"material.alpha="}).find("is not a value"), std::string::npos);
    EXPECT_NE(override_error(path, {"material.alpha.x=1"}).find("'alpha' is not a table"), std::string::npos);
}

}  // namespace
}  // namespace shatter
