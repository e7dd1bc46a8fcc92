// [material] preset and youngs_modulus (core/material_presets.h): a preset's stiffness and
// strength for a real constraint against a hand calculation, explicit keys and later layers over
// the preset, the refusals, and the settings JSON (unchanged without a preset; a round trip with one).
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/material_presets.h"
#include "core/shot.h"
#include "scenes/paper_scenes.h"
#include "simulate/bullet_world.h"
#include "simulate/simulate.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::TempDir;

// The paper's beam from [generate]: two 0.3 x 0.03 x 0.03 m boxes in a row along x, joined by 2 x 2
// constraints at the Gauss points of their 0.03 x 0.03 m shared face.
const char* kBeam = "[generate]\nkind = \"beam\"\n";

Shot shot_of(TempDir& dir, const std::string& material, const std::vector<std::string>& overrides = {}) {
    return load_shot(dir.write("s.toml", std::string(kBeam) + "[material]\n" + material), overrides);
}

std::unique_ptr<BulletWorld> world_of(const Model& model, const Shot& shot) {
    WorldSetup setup;
    setup.scene = shot.scene;
    setup.object = shot.object;
    setup.material = shot.material;
    setup.h = 1.0 / 480;
    setup.iterations = 20;
    return std::make_unique<BulletWorld>(model, setup);
}

std::string error_of(const std::function<void()>& f, ExitCode* code = nullptr) {
    try {
        f();
    } catch (const Error& e) {
        if (code) *code = e.code();
        return e.what();
    }
    return "";
}

TEST(MaterialPresets, GlassOnThePaperBeamGivesEAOverLAndTheTensileStrengthTimesA) {
    TempDir dir;
    const Shot shot = shot_of(dir, "preset = \"glass\"\n");
    const Model model = generate_model(*shot.generate);
    ASSERT_EQ(model.constraints.size(), 4u);
    const Constraint& c = model.constraints[0];
    // Hand calculation. The model: each of the 4 Gauss points stands for a quarter of the shared
    // face, A = 0.03 x 0.03 / 4 = 2.25e-4 m^2; the boxes' centres are at x = -0.15 and +0.15 m,
    // l = 0.3 m. Glass: E = 70 GPa, tensile strength 40 MPa.
    //   k = E A / l = 7e10 x 2.25e-4 / 0.3 = 5.25e7 N/m
    //   strength = 4e7 x 2.25e-4 = 9,000 N
    EXPECT_NEAR(c.area, 2.25e-4, 1e-9 * 2.25e-4);
    EXPECT_NEAR(constraint_length(model, c), 0.3, 1e-9 * 0.3);
    ASSERT_TRUE(shot.material.youngs_modulus);
    EXPECT_EQ(*shot.material.youngs_modulus, 7e10);
    const ConstraintMaterial cm = constraint_material(shot.material, model, c);
    EXPECT_NEAR(cm.stiffness, 5.25e7, 1e-9 * 5.25e7);
    EXPECT_NEAR(cm.strength, 9000, 1e-9 * 9000);
    // What the simulation builds: the joint has exactly the rule's numbers.
    const auto world = world_of(model, shot);
    for (size_t i = 0; i < model.constraints.size(); ++i) {
        EXPECT_NEAR(world->stiffness(i), 5.25e7, 1e-9 * 5.25e7) << i;
        EXPECT_NEAR(world->strength(i), 9000, 1e-9 * 9000) << i;
    }
    // Density, friction and restitution are the preset's.
    ASSERT_TRUE(shot.material.density);
    EXPECT_EQ(*shot.material.density, 2500);
    EXPECT_EQ(shot.material.surface.friction, 0.9);
    EXPECT_EQ(shot.material.surface.restitution, 0.3);
    EXPECT_EQ(shot.material.preset, "glass");
}

TEST(MaterialPresets, AKeyBesideThePresetOverridesItAndAnExplicitStiffnessKeepsKEqualsStiffnessTimesA) {
    TempDir dir;
    const Shot shot = shot_of(dir, "preset = \"glass\"\nstrength = 2e7\nstiffness = 5e11\nfriction = 0.4\n");
    const Model model = generate_model(*shot.generate);
    const Constraint& c = model.constraints[0];
    EXPECT_FALSE(shot.material.youngs_modulus);  // stiffness given: today's rule
    const ConstraintMaterial cm = constraint_material(shot.material, model, c);
    EXPECT_DOUBLE_EQ(cm.stiffness, 5e11 * c.area);
    EXPECT_DOUBLE_EQ(cm.strength, 2e7 * c.area);
    EXPECT_EQ(*shot.material.density, 2500);     // not given: the preset's
    EXPECT_EQ(shot.material.surface.friction, 0.4);
    EXPECT_EQ(shot.material.surface.restitution, 0.3);
    // youngs_modulus beside the preset replaces its E.
    const Shot e = shot_of(dir, "preset = \"glass\"\nyoungs_modulus = 3.5e10\n");
    EXPECT_NEAR(constraint_material(e.material, model, c).stiffness, 5.25e7 / 2, 1e-9 * 5.25e7);
}

TEST(MaterialPresets, APresetFromSetReplacesTheFilesNumbersAndASetKeyBesideItOverridesIt) {
    TempDir dir;
    const std::string file = "stiffness = 3e9\nstrength = 2e4\nfriction = 0.6\nrestitution = 0.1\nalpha = 0.5\n";
    const Shot p = shot_of(dir, file, {"material.preset=porcelain"});
    ASSERT_TRUE(p.material.youngs_modulus);
    EXPECT_EQ(*p.material.youngs_modulus, 7e10);
    EXPECT_EQ(p.material.strength, 4e7);
    EXPECT_EQ(p.material.surface.friction, 0.6);
    EXPECT_EQ(p.material.surface.restitution, 0.3);
    EXPECT_EQ(p.material.alpha, 0.5);  // never the preset's
    const Shot s = shot_of(dir, file, {"material.preset=porcelain", "material.strength=1e6"});
    EXPECT_EQ(s.material.strength, 1e6);
    EXPECT_EQ(*s.material.youngs_modulus, 7e10);
    // A preset in the file under a stiffness from --set: the stiffness rule.
    const Shot k = shot_of(dir, "preset = \"ice\"\n", {"material.stiffness=1e11"});
    EXPECT_FALSE(k.material.youngs_modulus);
    EXPECT_EQ(k.material.stiffness, 1e11);
    EXPECT_EQ(k.material.strength, 1e6);  // ice's
    // youngs_modulus from --set over the file's stiffness: the E A / l rule.
    const Shot e = shot_of(dir, file, {"material.youngs_modulus=2e8"});
    ASSERT_TRUE(e.material.youngs_modulus);
    EXPECT_EQ(*e.material.youngs_modulus, 2e8);
    EXPECT_EQ(e.material.strength, 2e4);
    // No preset: the file's numbers as they are.
    const Shot none = shot_of(dir, file, {"material.preset=none"});
    EXPECT_FALSE(none.material.youngs_modulus);
    EXPECT_EQ(none.material.stiffness, 3e9);
    EXPECT_EQ(none.material.strength, 2e4);
}

TEST(MaterialPresets, AnUnknownPresetIsRefusedNamingTheKeyTheValueAndTheValidNames) {
    TempDir dir;
    ExitCode code = ExitCode::Ok;
    const std::string file_error = error_of([&] { shot_of(dir, "preset = \"granit\"\n"); }, &code);
    EXPECT_EQ(code, ExitCode::BadInput);
    for (const char* part : {"s.toml:4", "material.preset = \"granit\" is not a material preset", "\"none\"",
                             "\"glass\"", "\"porcelain\"", "\"ceramic_tile\"", "\"gypsum_plaster\"", "\"concrete\"",
                             "\"stone\"", "\"ice\"", "\"weak_cast\""})
        EXPECT_NE(file_error.find(part), std::string::npos) << part << " not in: " << file_error;
    code = ExitCode::Ok;
    const std::string set_error = error_of([&] { shot_of(dir, "", {"material.preset=marble"}); }, &code);
    EXPECT_EQ(code, ExitCode::BadInput);
    EXPECT_NE(set_error.find("--set material.preset=marble"), std::string::npos) << set_error;
    EXPECT_NE(set_error.find("\"weak_cast\""), std::string::npos) << set_error;
    // youngs_modulus and stiffness in one place: which rule is meant is not clear.
    const std::string both = error_of([&] { shot_of(dir, "youngs_modulus = 7e10\nstiffness = 1e10\n"); });
    EXPECT_NE(both.find("material.stiffness and material.youngs_modulus are both given"), std::string::npos) << both;
}

// The settings JSON of the trajectory: a shot without a preset writes what it wrote before the
// presets existed; with one, the preset and the numbers used, and reading that back as [material]
// gives the same JSON.
TEST(MaterialPresets, TheSettingsJsonIsUnchangedWithoutAPresetAndRoundTripsWithOne) {
    TempDir dir;
    const Shot plain = shot_of(dir, "stiffness = 3e9\nstrength = 2e4\n");
    EXPECT_EQ(to_json(plain.material).dump(),
              R"({"density":null,"stiffness":3000000000.0,"damping":0.0,"strength":20000.0,"alpha":1.0,)"
              R"("friction":0.5,"restitution":0.1})");
    const Shot glass = shot_of(dir, "preset = \"glass\"\nalpha = 0.5\n");
    const nlohmann::ordered_json j = to_json(glass.material);
    EXPECT_EQ(j.dump(),
              R"({"preset":"glass","density":2500.0,"youngs_modulus":70000000000.0,"damping":0.0,)"
              R"("strength":40000000.0,"alpha":0.5,"friction":0.9,"restitution":0.3})");
    std::string toml;
    for (const auto& [key, value] : j.items()) toml += key + " = " + value.dump() + "\n";
    EXPECT_EQ(to_json(shot_of(dir, toml).material).dump(), j.dump());
    // The trajectory records it.
    SimulationInput in{glass.scene, glass.object, glass.material, glass.simulate};
    in.simulate.duration = 1.0 / 30;
    const SimulationResult r = simulate(generate_model(*glass.generate), in, "0");
    const nlohmann::json t = nlohmann::json::parse(r.trajectory.settings_json);
    EXPECT_EQ(t["material"]["preset"], "glass");
    EXPECT_EQ(t["material"]["youngs_modulus"], 7e10);
    EXPECT_FALSE(t["material"].contains("stiffness"));
}

}  // namespace
}  // namespace shatter
