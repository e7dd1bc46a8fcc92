// The settings tables of docs/shot.md and docs/render.md are generated from the declarations
// (core/setting_table.h); this keeps them equal, and checks what every declaration must have.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/setting_table.h"

namespace shatter {
namespace {

std::string slurp_source(const std::string& relative) {
    std::ifstream in(std::string(SHATTER_SOURCE_DIR) + "/" + relative, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(SettingsDoc, TheDocsTablesAreTheDeclarations) {
    for (const char* doc : {"docs/shot.md", "docs/render.md"}) {
        const std::string text = slurp_source(doc);
        ASSERT_NE(text.find("<!-- settings:"), std::string::npos) << doc;
        EXPECT_EQ(update_settings_docs(text), text)
            << doc << " differs from the declarations: run `build/bin/shatter settings-doc docs/shot.md docs/render.md`";
    }
}

TEST(SettingsTable, EverySettingHasHelpAReaderAJsonWriterAndFlagsUniqueInItsCommand) {
    const std::vector<std::vector<std::string>> commands = {
        {"mesh", "generate", "prescore"}, {"scene", "object", "material", "simulate"}, {"render"}};
    for (const auto& sections : commands) {
        std::set<std::string> flags;
        for (const std::string& name : sections) {
            const SettingsSection* section = find_settings_section(name);
            ASSERT_NE(section, nullptr) << name;
            std::set<std::string> keys;
            for (const Setting& s : section->settings) {
                EXPECT_FALSE(s.help.empty()) << name << "." << s.key;
                EXPECT_TRUE(bool(s.read)) << name << "." << s.key;
                EXPECT_TRUE(bool(s.write)) << name << "." << s.key << " has no JSON";
                EXPECT_TRUE(keys.insert(s.key).second) << name << "." << s.key << " declared twice";
                for (const FlagAlias& f : s.flags) EXPECT_TRUE(flags.insert(f.name).second) << f.name;
            }
        }
    }
}

TEST(SettingsTable, AFlagReadsLikeTheFileAndItsErrorsNameTheFlag) {
    Shot shot;
    const SettingsSection* material = find_settings_section("material");
    const SettingsSection* simulate = find_settings_section("simulate");
    auto setting = [](const SettingsSection* section, const std::string& key) -> const Setting& {
        for (const Setting& s : section->settings)
            if (s.key == key) return s;
        throw std::runtime_error("no " + key);
    };
    const Setting& alpha = setting(material, "alpha");
    apply_flag(*material, alpha, alpha.flags[0], "2", shot);
    EXPECT_DOUBLE_EQ(shot.material.alpha, 2.0);
    try {
        apply_flag(*material, alpha, alpha.flags[0], "-1", shot);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Usage);
        EXPECT_EQ(std::string(e.what()),
                  "--alpha = -1 is outside [0, 100] (fraction of stored energy) (fix: give a value from 0 to 100)");
    }
    const Setting& split = setting(simulate, "energy_split");
    apply_flag(*simulate, split, split.flags[0], "per_body", shot);
    EXPECT_EQ(shot.simulate.energy_split, EnergySplitMode::PerBody);
    const Setting& rollback = setting(simulate, "rollback");
    apply_flag(*simulate, rollback, rollback.flags[0], "", shot);
    EXPECT_TRUE(shot.simulate.rollback);
    shot.simulate.auto_duration = true;
    const Setting& duration = setting(simulate, "duration");
    apply_flag(*simulate, duration, duration.flags[0], "2", shot);
    EXPECT_FALSE(shot.simulate.auto_duration);  // seconds from a flag replace the shot's "auto"
    EXPECT_DOUBLE_EQ(shot.simulate.duration, 2.0);
}

TEST(SettingsTable, NumbersAreWrittenAsTheDocsWriteThem) {
    EXPECT_EQ(short_number(0.5), "0.5");
    EXPECT_EQ(short_number(3600), "3600");
    EXPECT_EQ(short_number(1e-6), "1e-6");
    EXPECT_EQ(short_number(0.001), "0.001");
    EXPECT_EQ(short_number(1e-4), "1e-4");
    EXPECT_EQ(short_number(1e5), "1e5");
    EXPECT_EQ(short_number(1000), "1000");
    EXPECT_EQ(short_number(1e10), "1e10");
    EXPECT_EQ(short_number(-9.81), "-9.81");
}

}  // namespace
}  // namespace shatter
