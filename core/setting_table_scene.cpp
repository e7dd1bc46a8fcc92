// The [scene], [object], [material] and [simulate] tables (core/setting_table.h): what simulate
// reads, and the tables of one entry of the arrays of tables of [scene] and [object]
// (core/shot_scene.cpp reads the entries and adds the checks that join keys).
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/material_presets.h"
#include "core/setting_builders.h"

namespace shatter::table {

namespace {

using ojson = nlohmann::ordered_json;

// duration: seconds, or "auto" (until the pieces rest, at most max_duration).
// A key that takes a number or "auto": "auto" sets `is_auto`; a number (read by `read_number`,
// with its limits) clears it, replacing an "auto" given before (a flag over the shot). `what`
// names the number in the message ("a number of seconds"), `fix` shows both forms.
template <class ReadNumber>
void read_number_or_auto(TomlSection& s, const char* key, bool& is_auto, const char* what, const char* fix,
                         ReadNumber read_number) {
    const toml::node* n = s.node(key);
    if (n && n->is_string()) {
        if (n->as_string()->get() != "auto")
            s.fail(n, fmt::format("{} must be {} or \"auto\"", s.key_name(key), what), fix);
        is_auto = true;
    } else if (read_number()) {
        is_auto = false;
    }
}

void read_duration(TomlSection& s, Shot& shot) {
    SimulateSettings& simulate = shot.simulate;
    read_number_or_auto(s, "duration", simulate.auto_duration, "a number of seconds",
                        "duration = 4.0, or duration = \"auto\" (until the pieces rest, at most max_duration)",
                        [&] { return s.number("duration", simulate.duration, kDurationLimits); });
}

void read_substeps(TomlSection& s, Shot& shot) {
    SimulateSettings& simulate = shot.simulate;
    read_number_or_auto(s, "substeps", simulate.auto_substeps, "a whole number of steps per frame",
                        "substeps = 8, or substeps = \"auto\" (the step chosen as the run goes)",
                        [&] { return s.integer("substeps", simulate.substeps, kSubstepsLimits); });
}

// The keys every body of the scene has, between its shape keys and its colour.
template <class Root>
std::vector<BasicSetting<Root>> pose_settings() {
    return {vec3<Root>("position", "m", at(&Root::pose, &Pose::position), kPositionLimits, "[0, 1, 0]",
                       "the shape's centre (plane: a point on it)"),
            vec3<Root>("rotation", "degrees", at(&Root::pose, &Pose::rotation_deg), kRotationLimits, "[0, 45, 0]",
                       "the shape's orientation (plane: its normal is the rotation of +Y)")};
}

template <class Root>
std::vector<BasicSetting<Root>> surface_settings() {
    return {number<Root>("friction", "1", at(&Root::surface, &SurfaceSettings::friction), kFrictionLimits,
                         "Coulomb friction coefficient"),
            number<Root>("restitution", "1", at(&Root::surface, &SurfaceSettings::restitution), kRestitutionLimits,
                         "bounciness")};
}

template <class Root>
BasicSetting<Root> name_setting() {
    return text<Root>("name", at(&Root::name), "a name for messages and render");
}

template <class Root>
std::vector<BasicSetting<Root>> joined(std::vector<std::vector<BasicSetting<Root>>> parts) {
    std::vector<BasicSetting<Root>> out;
    for (auto& part : parts) out.insert(out.end(), part.begin(), part.end());
    return out;
}

}  // namespace

}  // namespace shatter::table

namespace shatter {

using namespace table;

const std::vector<BasicSetting<ColliderSettings>>& collider_settings() {
    using C = ColliderSettings;
    static const std::vector<BasicSetting<C>> settings = joined<C>(
        {{name_setting<C>(),
          choice<ShapeKind, C>("shape", at(&C::shape, &ShapeSettings::kind),
                               {{"box", ShapeKind::Box}, {"sphere", ShapeKind::Sphere}, {"plane", ShapeKind::Plane},
                                {"mesh", ShapeKind::Mesh}},
                               "the collider's shape"),
          vec3<C>("size", "m", at(&C::shape, &ShapeSettings::size), kSizeLimits, "[1, 0.1, 1]",
                  "box: full extents along its own axes"),
          number<C>("radius", "m", at(&C::shape, &ShapeSettings::radius), kSizeLimits, "sphere: radius"),
          text<C>("mesh", at(&C::shape, &ShapeSettings::mesh),
                  "mesh: the mesh file, relative to the shot file's folder")
              .shows("(required for mesh)"),
          number<C>("mesh_scale", "m per mesh unit", at(&C::shape, &ShapeSettings::mesh_scale), kScaleLimits,
                    "mesh: multiplies every coordinate")},
         pose_settings<C>(),
         surface_settings<C>(),
         {linear_colour<C>(&C::colour, "colour in render")}});
    return settings;
}

const std::vector<BasicSetting<KinematicSettings>>& kinematic_settings() {
    using K = KinematicSettings;
    static const std::vector<BasicSetting<K>> settings = joined<K>(
        {{name_setting<K>(),
          choice<ShapeKind, K>("shape", at(&K::shape, &ShapeSettings::kind),
                               {{"box", ShapeKind::Box}, {"sphere", ShapeKind::Sphere}}, "the body's shape"),
          vec3<K>("size", "m", at(&K::shape, &ShapeSettings::size), kSizeLimits, "[1, 0.1, 1]",
                  "box: full extents along its own axes"),
          number<K>("radius", "m", at(&K::shape, &ShapeSettings::radius), kSizeLimits, "sphere: radius"),
          // The settings JSON writes the body's shape as a collider's: with these two, which the
          // shot file does not have.
          text<K>("mesh", at(&K::shape, &ShapeSettings::mesh), "").json_only(),
          number<K>("mesh_scale", "", at(&K::shape, &ShapeSettings::mesh_scale), kScaleLimits, "").json_only()},
         pose_settings<K>(),
         {vec3<K>("velocity", "m/s", at(&K::velocity), kVelocityLimits, "[1, 0, 0]",
                  "constant velocity: the position at time t is position + velocity t"),
          key_frames<K>(&K::keys, "s, m", "(none)", "t 0 to 3600, strictly increasing; x, y, z -1e6 to 1e6",
                        "`[[t, x, y, z], ...]`: positions at times, linear in between, the first held before and "
                        "the last after; replaces `position` and `velocity`")},
         surface_settings<K>(),
         {linear_colour<K>(&K::colour, "colour in render")}});
    return settings;
}

const std::vector<BasicSetting<ProjectileSettings>>& projectile_settings() {
    using P = ProjectileSettings;
    static const std::vector<BasicSetting<P>> settings = joined<P>(
        {{name_setting<P>(),
          choice<ShapeKind, P>("shape", at(&P::shape, &ShapeSettings::kind),
                               {{"box", ShapeKind::Box}, {"sphere", ShapeKind::Sphere}}, "the body's shape"),
          vec3<P>("size", "m", at(&P::shape, &ShapeSettings::size), kSizeLimits, "[0.05, 0.05, 0.05]",
                  "box: full extents along its own axes"),
          number<P>("radius", "m", at(&P::shape, &ShapeSettings::radius), kSizeLimits, "sphere: radius")},
         pose_settings<P>(),
         {vec3<P>("velocity", "m/s", at(&P::velocity), kVelocityLimits, "[0, 0, 10]", "velocity at t = 0"),
          number<P>("density", "kg/m^3", at(&P::density), kDensityLimits, "its mass over its volume (steel 7,800)")},
         surface_settings<P>(),
         {linear_colour<P>(&P::colour, "colour in render")}});
    return settings;
}

const std::vector<BasicSetting<PieceDriveSettings>>& driven_settings() {
    using D = PieceDriveSettings;
    static const std::vector<BasicSetting<D>> settings = {
        whole<D>("piece", "", at(&D::piece), Limits{0, 1e9, "(piece index)"},
                 "which piece (`shatter info MODEL` lists them)")
            .shows("(required)")
            .range_is("a piece index of the model"),
        boolean<D>("fixed", at(&D::fixed), "true: never moves"),
        vec3<D>("velocity", "m/s", at(&D::velocity), kVelocityLimits, "[0.05, 0, 0]",
                "constant velocity (not with keys)"),
        key_frames<D>(&D::keys, "[s, m, m, m]", "none", "times increasing",
                      "offsets from the start position at times, linear between, held after the last")};
    return settings;
}

}  // namespace shatter

namespace shatter::table {

SettingsSection scene_section() {
    return {"scene",
            {vec3("gravity", "m/s^2", at(&Shot::scene, &SceneSettings::gravity), kGravityLimits, "[0, -9.81, 0]",
                  "gravitational acceleration"),
             boolean("ground", at(&Shot::scene, &SceneSettings::ground), "an infinite static ground plane y = ground_height"),
             number("ground_height", "m", at(&Shot::scene, &SceneSettings::ground_height), kPositionLimits,
                    "height of the ground plane"),
             number("ground_friction", "1", at(&Shot::scene, &SceneSettings::ground_surface, &SurfaceSettings::friction),
                    kFrictionLimits, "Coulomb friction coefficient of the ground"),
             number("ground_restitution", "1",
                    at(&Shot::scene, &SceneSettings::ground_surface, &SurfaceSettings::restitution), kRestitutionLimits,
                    "bounciness of the ground")},
            [](TomlSection& s, Shot& shot) { read_scene_arrays(s, shot.scene, s.file()); },
            [](const Shot& shot, ojson& j) {
                j["colliders"] = entries_json(collider_settings(), shot.scene.colliders);
                j["kinematic"] = entries_json(kinematic_settings(), shot.scene.kinematic);
                // Only when there are any: the settings of shots without them keep their bytes.
                if (!shot.scene.projectiles.empty())
                    j["projectile"] = entries_json(projectile_settings(), shot.scene.projectiles);
            },
            [](JsonObject& o, Shot& shot) {
                shot.scene.colliders = entries_from_json(collider_settings(), o, "colliders");
                shot.scene.kinematic = entries_from_json(kinematic_settings(), o, "kinematic");
                if (o.has("projectile"))
                    shot.scene.projectiles = entries_from_json(projectile_settings(), o, "projectile");
            }};
}

SettingsSection object_section() {
    return {"object",
            {vec3("position", "m", at(&Shot::object, &ObjectSettings::pose, &Pose::position), kPositionLimits, "[0, 1, 0]",
                  "translation of the model frame"),
             vec3("rotation", "degrees", at(&Shot::object, &ObjectSettings::pose, &Pose::rotation_deg), kRotationLimits,
                  "[0, 45, 0]", "rotation of the model frame, about its origin"),
             choice<Placement>("place", at(&Shot::object, &ObjectSettings::place),
                               {{"origin", Placement::Origin}, {"base", Placement::Base}},
                               "what `position` places: \"origin\": the model frame's origin; \"base\": the centre of "
                               "the bottom of the object's bounding box, after its rotation (`shatter run MESH`)")
                 .json_unless_default(),
             vec3("velocity", "m/s", at(&Shot::object, &ObjectSettings::velocity), kVelocityLimits, "[0, -1, 0]",
                  "initial linear velocity of every piece"),
             vec3("angular_velocity", "rad/s", at(&Shot::object, &ObjectSettings::angular_velocity),
                  kAngularVelocityLimits, "[0, 3.14, 0]",
                  "initial angular velocity about the object's centre of mass")},
            [](TomlSection& s, Shot& shot) { read_object_driven(s, shot.object); },
            [](const Shot& shot, ojson& j) { j["driven"] = entries_json(driven_settings(), shot.object.driven); }};
}

namespace {

// Which layer of the shot a value came from: 1 for `--set` (an override's node has the override
// as its source, core/shot.cpp), 0 for the shot file or the default shot. A later layer wins.
int layer(const toml::node* n) {
    const auto& path = n->source().path;
    return path && path->rfind("--set ", 0) == 0 ? 1 : 0;
}

std::string layer_name(const toml::node* n) { return layer(n) ? *n->source().path : "the shot"; }

// [material] preset = "NAME": the preset's numbers, set before the table's other keys.
void read_preset(TomlSection& s, Shot& shot) {
    std::string name;
    if (!s.text("preset", name)) return;
    if (name == "none") {
        shot.material.preset = name;
        return;
    }
    const MaterialPreset* p = find_material_preset(name);
    if (!p)
        s.fail(s.node("preset"), fmt::format("{} = \"{}\" is not a material preset", s.key_name("preset"), name),
               fmt::format("use one of {} (docs/shot.md, \"Material presets\")", material_preset_names()));
    apply_material_preset(*p, shot.material);
}

// The preset (`preset_key`: [material] preset, [simulate] method) given in a later layer than `n`
// (`--set material.preset=...` over the shot file's key), or null: the key is then the preset's
// to set.
const toml::node* later_preset(TomlSection& s, const char* preset_key, const toml::node* n) {
    const toml::node* p = s.node(preset_key);
    if (!p || !p->is_string() || p->as_string()->get() == "none" || layer(p) <= layer(n)) return nullptr;
    return p;
}

// A key a preset also sets: it overrides a preset given in the same layer (or an earlier one), and
// a preset given in a later layer replaces it.
Setting preset_overridable(Setting setting, const char* preset_key = "preset") {
    setting.read = [inner = setting.read, key = setting.key, preset_key](TomlSection& s, Shot& shot) {
        const toml::node* n = s.node(key.c_str());
        if (!n) return;
        if (const toml::node* p = later_preset(s, preset_key, n)) {
            spdlog::info("{} of {} replaced by the {} ({})", s.key_name(key.c_str()), layer_name(n), preset_key,
                         *p->source().path);
            return;
        }
        inner(s, shot);
    };
    return setting;
}

// stiffness: today's rule k = stiffness A; it turns the E A / l rule off (a preset's, or an
// earlier layer's youngs_modulus). Both keys in one layer are refused.
void read_stiffness(TomlSection& s, Shot& shot) {
    const toml::node* n = s.node("stiffness");
    if (!n) return;
    if (const toml::node* e = s.node("youngs_modulus")) {
        if (layer(e) == layer(n))
            s.fail(n, fmt::format("{} and {} are both given", s.key_name("stiffness"), s.key_name("youngs_modulus")),
                   "give youngs_modulus (Pa: k = E A / l) or stiffness (N/m^3: k = stiffness A), not both");
        if (layer(e) > layer(n)) {  // the later youngs_modulus wins
            spdlog::info("material: stiffness of {} replaced by youngs_modulus ({})", layer_name(n), layer_name(e));
            return;
        }
    }
    if (s.number("stiffness", shot.material.stiffness, kStiffnessLimits)) shot.material.youngs_modulus.reset();
}

}  // namespace

SettingsSection material_section() {
    Setting preset = custom("preset", "", "\"none\"", "", "", read_preset)
                         .json([](const Shot& s, ojson& j) {
                             if (s.material.preset != "none") j["preset"] = s.material.preset;
                         });
    preset.range = "none";
    for (const MaterialPreset& p : material_presets()) preset.range += std::string(", ") + p.name;
    preset.help =
        "a material's published numbers (" + preset.range.substr(6) +
        "; docs/shot.md, \"Material presets\"): sets youngs_modulus, strength, density, friction and restitution; any "
        "of them given beside it overrides the preset's, and a preset given with `--set` replaces the shot file's. "
        "\"none\": no preset (k = stiffness x A)";
    preset.flag("--preset");
    Setting youngs_modulus =
        custom("youngs_modulus", "Pa", "(unset: k = stiffness x A)", "", "", [](TomlSection& s, Shot& shot) {
            double e = 0;
            if (s.number("youngs_modulus", e, kYoungsModulusLimits)) shot.material.youngs_modulus = e;
        }).json([](const Shot& s, ojson& j) {
            if (s.material.youngs_modulus) j["youngs_modulus"] = *s.material.youngs_modulus;
        });
    youngs_modulus.range = range_of(kYoungsModulusLimits);
    youngs_modulus.help =
        "Young's modulus E: each constraint's stiffness is E A / l, A its area and l the distance between the centres "
        "of mass of the two pieces it joins (docs/physics.md section 2); not with stiffness";
    youngs_modulus.flag("--youngs-modulus");
    Setting stiffness = number("stiffness", "N/m^3", at(&Shot::material, &MaterialSettings::stiffness),
                               kStiffnessLimits,
                               "constraint stiffness per m^2 of area: k = stiffness x A (~ Young's modulus / l); "
                               "unused when youngs_modulus is set (by the key or a preset)")
                            .flag("--stiffness");
    stiffness.read = read_stiffness;
    stiffness.write = [w = stiffness.write](const Shot& s, ojson& j) {
        if (!s.material.youngs_modulus) w(s, j);  // the trajectory records the rule used
    };
    return {"material",
            {preset,
             preset_overridable(optional_number("density", "kg/m^3", at(&Shot::material, &MaterialSettings::density),
                                                kDensityLimits, "density of the pieces (overrides the one prescore used)",
                                                "the model's", Unset::Null)),
             preset_overridable(youngs_modulus),
             preset_overridable(stiffness),
             number("damping", "N s/m^3", at(&Shot::material, &MaterialSettings::damping), kDampingLimits,
                    "constraint damping per m^2 of area")
                 .flag("--damping"),
             preset_overridable(number("strength", "Pa", at(&Shot::material, &MaterialSettings::strength),
                                       kStrengthLimits, "tensile strength: breaking force per m^2 of area")
                                    .flag("--strength")),
             number("alpha", "1", at(&Shot::material, &MaterialSettings::alpha), kAlphaLimits,
                    "fraction of a broken constraint's stored energy given back as kinetic energy (0: plain breaking; "
                    "> 1 for artistic effect)")
                 .flag("--alpha"),
             preset_overridable(number("friction", "1",
                                       at(&Shot::material, &MaterialSettings::surface, &SurfaceSettings::friction),
                                       kFrictionLimits, "Coulomb friction coefficient of the pieces; two surfaces in contact take the geometric mean of theirs (docs/physics.md section 5d)")),
             preset_overridable(number("restitution", "1",
                                       at(&Shot::material, &MaterialSettings::surface, &SurfaceSettings::restitution),
                                       kRestitutionLimits, "bounciness of the pieces (restitution); two surfaces in contact take the larger of theirs")),
             boolean("stiffen", at(&Shot::material, &MaterialSettings::stiffen),
                     "raise a stiffness too soft for the step (CFM above max_cfm) to the least that converges, times "
                     "1.05, and log it, instead of refusing the shot; the default shot of `shatter run MESH` turns it on")
                 .json_unless_default()},
            {}};
}

namespace {

// [simulate] method = "exact" | "paper": sets energy_split, directions and exact_energy, which
// are read after it and override it (preset_overridable).
Setting method() {
    const std::vector<std::pair<const char*, EnergizeMethod>> names = {{"exact", EnergizeMethod::Exact},
                                                                       {"paper", EnergizeMethod::Paper}};
    Setting m = choice<EnergizeMethod>(
                    "method", at(&Shot::simulate, &SimulateSettings::method), names,
                    "how a break gives back alpha E (docs/physics.md section 4): \"exact\": the pair gains exactly "
                    "alpha E in its own frame, equal and opposite kicks passed through the joints (energy_split = "
                    "\"total\", directions = \"opposed\", exact_energy = true, kick_bodies = \"joined\"); "
                    "\"paper\": the paper as written, alpha E per body with its magnitudes and directions on the "
                    "two pieces (\"per_body\", \"paper\", false, \"pieces\"), for comparison. The four keys "
                    "given beside it override it")
                    .flag("--method")
                    .json_unless_default();
    m.read = [inner = m.read](TomlSection& s, Shot& shot) {
        if (!s.node("method")) return;
        inner(s, shot);
        apply_energize_method(shot.simulate.method, shot.simulate);
    };
    return m;
}

}  // namespace

SettingsSection simulate_section() {
    return {"simulate",
            {custom("duration", "s, or \"auto\"", "4", "0.001 to 3600, or \"auto\"",
                    "simulated time; frames are recorded at 0, 1/fps, ... up to duration. \"auto\": until every piece "
                    "has been at rest for 0.5 s (its centre no faster than the rest speed between frames, and no point "
                    "of it farther than the rest speed x 0.5 s from where it was; the rest speed 0.02 m/s, or 0.04 "
                    "object sizes per second for an object over 0.5 m across, and once it has landed 0.04 times the "
                    "spread of the 90% of its mass nearest its centre when that is more), checked at each frame, at most "
                    "max_duration; the movie then ends 0.5 s after the last piece comes to rest",
                    read_duration)
                 .json([](const Shot& s, ojson& j) {
                     j["duration"] = s.simulate.auto_duration ? ojson("auto") : ojson(s.simulate.duration);
                 })
                 .flag("--duration"),
             number("fps", "frames/s", at(&Shot::simulate, &SimulateSettings::fps), kFpsLimits,
                    "frames recorded per second")
                 .flag("--fps"),
             custom("substeps", "steps per frame, or \"auto\"", "\"auto\"", "1 to 10000, or \"auto\"",
                    "solver steps per frame: time step h = 1 / (fps substeps). \"auto\": each frame is cut into "
                    "blocks of at most 1/480 s, each run as one step while the joints carry less than half their "
                    "strength, in shorter steps while only their stretch (joined pieces turning) would pass half of "
                    "it, and otherwise in the steps the stiffest joint needs (omega h <= 2.5, in powers of two); once "
                    "the object has touched the scene, a calm step (loads low, every piece moving under a tenth of "
                    "its size) spans two blocks (docs/physics.md, \"The automatic step\")",
                    read_substeps)
                 .json([](const Shot& s, ojson& j) {
                     j["substeps"] = s.simulate.auto_substeps ? ojson("auto") : ojson(s.simulate.substeps);
                 })
                 .flag("--substeps"),
             whole("iterations", "count", at(&Shot::simulate, &SimulateSettings::iterations), kIterationsLimits,
                   "sequential-impulse iterations per step")
                 .flag("--iterations"),
             choice<JointSolve>("joints", at(&Shot::simulate, &SimulateSettings::joints),
                                {{"auto", JointSolve::Auto}, {"iterative", JointSolve::Iterative},
                                 {"direct", JointSolve::Direct}},
                                "\"iterative\": joint rows one at a time (Bullet's sequential impulses); \"direct\": "
                                "all joint rows solved at once in every iteration (a sparse LDL^T), so their forces "
                                "match their springs whatever the pieces' mass ratios; the contacts iterated around "
                                "them, and a contact that holds a light piece under heavy joined ones through the "
                                "joints (docs/physics.md, \"Direct joints\"); \"auto\": direct, at any piece count. "
                                "Iterative joints are warned before the run when two joined pieces' masses differ by "
                                "more than 10 times or two pieces of one island by more than 30 (where they start to "
                                "fail: docs/accuracy.md, \"The stability map\"), and after it when the joints that "
                                "broke held more than 1.1 times by their stretch what their forces stored")
                 .flag("--joints")
                 .json_unless_default(),
             method(),
             preset_overridable(
                 choice<EnergySplitMode>("energy_split", at(&Shot::simulate, &SimulateSettings::energy_split),
                                         {{"total", EnergySplitMode::Total}, {"per_body", EnergySplitMode::PerBody}},
                                         "\"total\": two bodies at rest gain alpha E together; \"per_body\": each gains "
                                         "alpha E (set by method)")
                     .flag("--energy-split"),
                 "method"),
             preset_overridable(
                 choice<KickDirectionMode>("directions", at(&Shot::simulate, &SimulateSettings::directions),
                                           {{"paper", KickDirectionMode::Paper},
                                            {"opposed", KickDirectionMode::Opposed},
                                            {"force", KickDirectionMode::Force}},
                                           "kick directions: \"paper\": -(t x f) per body; \"opposed\": "
                                           "momentum-conserving; \"force\": equal and opposite along the joint's load, "
                                           "never into the partner (momentum-conserving; docs/physics.md section 4; set "
                                           "by method)")
                     .flag("--directions"),
                 "method"),
             preset_overridable(
                 choice<KickBodiesMode>("kick_bodies", at(&Shot::simulate, &SimulateSettings::kick_bodies),
                                        {{"pieces", KickBodiesMode::Pieces}, {"joined", KickBodiesMode::Joined}},
                                        "what a break's kicks move: \"pieces\": the joint's two pieces, as free bodies; "
                                        "\"joined\": the two pieces and everything still joined to them, in the motion "
                                        "their joints allow, so that the joints do not swallow the kick; a break the "
                                        "joints hold rigidly keeps its energy until a later break parts its pieces "
                                        "(docs/physics.md section 4; set by method)")
                     .flag("--kick-bodies"),
                 "method"),
             number("rate_limit", "s", at(&Shot::simulate, &SimulateSettings::rate_limit), kRateLimitLimits,
                    "least time between two breaks of the object (the paper's chain: 0.3); 0: off")
                 .flag("--rate-limit"),
             boolean("rollback", at(&Shot::simulate, &SimulateSettings::rollback),
                     "re-run a step whose breaks were found, without the broken constraints")
                 .flag("--rollback", FlagKind::SetsTrue),
             preset_overridable(boolean("exact_energy", at(&Shot::simulate, &SimulateSettings::exact_energy),
                                        "solve the kick impulses for the bodies' motion so that the gained kinetic "
                                        "energy is exactly alpha E in the pair's frame (set by method)")
                                    .flag("--no-exact-energy", FlagKind::SetsFalse),
                                "method"),
             seed("seed", at(&Shot::simulate, &SimulateSettings::seed), "seed of the random kick directions").flag("--seed"),
             number("max_cfm", "1", at(&Shot::simulate, &SimulateSettings::max_cfm), kMaxCfmLimits,
                    "refuse settings whose constraints would need a larger constraint-force mixing"),
             choice<BreakCriterion>("break_criterion", at(&Shot::simulate, &SimulateSettings::break_criterion),
                                    {{"force", BreakCriterion::Force}, {"bullet_impulse", BreakCriterion::BulletImpulse}},
                                    "when a constraint is overloaded: \"force\": the norm of its force exceeds strength "
                                    "x area; \"bullet_impulse\": Bullet's per-row impulse test, for comparison "
                                    "(docs/accuracy.md)")
                 .json_unless_default(),
             choice<InstabilityMode>("on_instability", at(&Shot::simulate, &SimulateSettings::on_instability),
                                     {{"stop", InstabilityMode::Stop}, {"clamp", InstabilityMode::Clamp}},
                                     "when a piece's state turns NaN/Inf or the kinetic energy exceeds what the scene "
                                     "can supply (docs/reliability.md): \"stop\": end there, keep the frames before, "
                                     "trajectory marked incomplete, exit code 5; \"clamp\": scale the velocities down "
                                     "to the limit and go on (counted and logged; a NaN still stops)")
                 .json_unless_default()
                 .flag("--on-instability"),
             boolean("rigid_flight", at(&Shot::simulate, &SimulateSettings::rigid_flight),
                     "an object that starts without spin and touching nothing falls as one rigid body, its joints "
                     "unsolved (in free fall they carry no load), until something comes within contact reach; "
                     "false: every joint is solved in every step of the fall (docs/physics.md section 6)")
                 .json_unless_default(),
             boolean("sleep", at(&Shot::simulate, &SimulateSettings::sleep),
                     "pieces that have moved slower than 0.01 m/s (centre, and rim as they turn) for 0.25 s, with "
                     "everything they touch or are joined to, sleep: they are neither solved nor moved until "
                     "something touches them or a break kicks them; a piece joined to a driven piece never sleeps; "
                     "false: every piece is solved in every step (docs/physics.md section 6)")
                 .json_unless_default(),
             number("max_duration", "s", at(&Shot::simulate, &SimulateSettings::max_duration), kDurationLimits,
                    "the cap of duration = \"auto\" (unused otherwise)")
                 .json([](const Shot& s, ojson& j) {
                     if (s.simulate.auto_duration) j["max_duration"] = s.simulate.max_duration;
                 })},
            {}};
}

}  // namespace shatter::table
