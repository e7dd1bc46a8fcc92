// The [mesh], [generate] and [prescore] tables (core/setting_table.h): what prescore reads.
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/setting_builders.h"

namespace shatter::table {

namespace {

using ojson = nlohmann::ordered_json;

// A Length key: a number (fraction of the diagonal) or a string with a unit.
void read_length(TomlSection& s, const char* key, Length& out,
                 void (*check)(const std::string&, const Length&, bool), const std::string& also = "") {
    const toml::node* n = s.node(key);
    if (!n) return;
    const std::string fix = fmt::format("write {} = 0.01 (fraction of the diagonal) or {} = \"2mm\"{}", key, key, also);
    if (auto v = n->value<double>()) {
        out = Length{*v, true};
    } else if (auto len = n->is_string() ? Length::parse(n->as_string()->get()) : std::nullopt) {
        out = *len;
    } else {
        const std::string value = n->is_string() ? fmt::format(" = \"{}\"", n->as_string()->get()) : "";
        s.fail(n, fmt::format("{}{} is not a length", s.key_name(key), value), fix);
    }
    check(s.where(n), out, s.from_flag());
}

// hollow: a length, or false for solid.
void read_hollow(TomlSection& s, Shot& shot) {
    PrescoreSettings& p = shot.prescore;
    const toml::node* n = s.node("hollow");
    if (!n) return;
    if (n->is_boolean()) {
        if (n->as_boolean()->get())
            s.fail(n, "prescore.hollow = true does not say how thick the shell is",
                   "write hollow = 0.05 (fraction of the diagonal), hollow = \"12mm\", or hollow = false (solid)");
        p.hollow.reset();
        return;
    }
    Length thickness;
    read_length(s, "hollow", thickness, check_hollow, ", or hollow = false (solid)");
    p.hollow = thickness;
}

// seed_points = [[x, y, z], ...]: metres in the model's frame (seeds = "points").
void read_seed_points(TomlSection& s, Shot& shot) {
    const toml::node* n = s.node("seed_points");
    if (!n) return;
    const char* fix = "write seed_points = [[0.05, 0.02, 0], [-0.05, 0.02, 0]] (x, y, z in m, the model's frame)";
    const toml::array* a = n->as_array();
    if (!a || a->empty()) s.fail(n, s.key_name("seed_points") + " must be a non-empty array of [x, y, z]", fix);
    std::vector<std::array<double, 3>> points;
    for (size_t i = 0; i < a->size(); ++i) {
        const toml::node& e = *a->get(i);
        const std::string name = fmt::format("{}[{}]", s.key_name("seed_points"), i);
        const toml::array* p = e.as_array();
        if (!p || p->size() != 3) s.fail(&e, name + " must be an array of 3 numbers [x, y, z]", fix);
        std::array<double, 3> x{};
        for (size_t c = 0; c < 3; ++c) {
            const auto d = p->get(c)->value<double>();
            if (!d) s.fail(p->get(c), fmt::format("{}[{}] is not a number", name, c), fix);
            check_limits(s.where(p->get(c)), fmt::format("{}[{}]", name, c), *d, kPositionLimits, s.from_flag());
            x[c] = *d;
        }
        points.push_back(x);
    }
    shot.prescore.seed_points = std::move(points);
    shot.prescore.seed_points_where = s.where(n);
}

void read_mesh_path(TomlSection& s, Shot& shot) {
    std::string& path = shot.mesh.path;
    if (s.text("path", path) && !path.empty()) {
        std::filesystem::path p(path);
        if (p.is_relative()) path = (std::filesystem::path(s.file()).parent_path() / p).lexically_normal().string();
    }
}

void read_mesh_member(TomlSection& s, Shot& shot) {
    if (s.text("member", shot.mesh.member) && shot.mesh.member.empty())
        s.fail(s.node("member"), "mesh.member is empty", "name a file in the archive, e.g. member = \"scene.gltf\", or leave member out");
}

void read_generate_kind(TomlSection& s, Shot& shot) {
    std::string text;
    if (!s.text("kind", text)) s.fail(nullptr, "[generate] has no kind", "add kind = \"beam\", \"plate\" or \"chain\"");
    const auto kind = parse_generate_kind(text);
    if (!kind)
        s.fail(s.node("kind"), fmt::format("generate.kind = \"{}\" is not a generated object", text),
               "use \"beam\", \"plate\" or \"chain\"");
    *shot.generate = default_generate(*kind);  // the other keys default to the kind's values
}

void read_end_size(TomlSection& s, Shot& shot) {
    GenerateSettings& g = *shot.generate;
    if (s.number("end_size", g.end_size, kGenerateSizeLimits) && g.kind != GenerateKind::Chain)
        s.fail(s.node("end_size"), fmt::format("generate.end_size does not apply to kind = \"{}\"", to_string(g.kind)),
               "remove end_size (only a chain has end cubes)");
}

}  // namespace

SettingsSection mesh_section() {
    return {"mesh",
            {custom("path", "", "(required)", "", "the mesh file, or an archive holding one (.zip, .7z, .rar, .tar.gz); relative to the shot file's folder", read_mesh_path)
                 .json([](const Shot& s, ojson& j) { j["path"] = s.mesh.path; }),
             custom("member", "", "(chosen)", "", "the mesh file to read in an archive, by its name in it (e.g. "
                    "\"models/chair.obj\"); unset: the likeliest (meshio/archive.h: glTF, then FBX, Collada, OBJ, 3DS; "
                    "nearest the top; the largest)", read_mesh_member)
                 .json([](const Shot& s, ojson& j) {
                     if (!s.mesh.member.empty()) j["member"] = s.mesh.member;
                 }),
             optional_number("scale", "m per mesh unit", at(&Shot::mesh, &MeshSettings::scale), kScaleLimits,
                             "multiplies every coordinate", "(the file's units)", Unset::Auto)
                 .flag("--scale"),
             optional_number("size", "m", at(&Shot::mesh, &MeshSettings::size), kSizeLimits,
                             "the longest side of the mesh's bounding box; wins over `scale`", "(unset)", Unset::Omitted)
                 .flag("--size"),
             choice<RepairMode>("repair", at(&Shot::mesh, &MeshSettings::repair),
                                {{"auto", RepairMode::Auto}, {"always", RepairMode::Always}, {"never", RepairMode::Never}},
                                "alpha-wrap: only when Mesh_3 cannot take the mesh, always, or never (refuse)",
                                "a repair mode", "use \"auto\", \"always\" or \"never\"")
                 .flag("--repair"),
             number("wrap_alpha", "fraction of diagonal", at(&Shot::mesh, &MeshSettings::wrap_alpha), kWrapAlphaLimits,
                    "alpha-wrap ball radius")
                 .flag("--wrap-alpha"),
             number("wrap_offset", "fraction of diagonal", at(&Shot::mesh, &MeshSettings::wrap_offset),
                    kWrapOffsetLimits, "alpha-wrap offset from the input")
                 .flag("--wrap-offset"),
             choice<UpAxis>("up", at(&Shot::mesh, &MeshSettings::up),
                            {{"auto", UpAxis::Auto}, {"y", UpAxis::Y}, {"z", UpAxis::Z}},
                            "which way is up in the file (shatter's world is y-up; a z-up file is turned to stand "
                            "up): auto: z for STL, 3MF and AMF (CAD and 3D printing), Blender's .blend and the PLY files Blender "
                            "writes, and an FBX file whose settings say so; y for every other format",
                            "an up axis", "use \"auto\", \"y\" or \"z\"")
                 .json_unless_default()
                 .flag("--up"),
             boolean("adapt", at(&Shot::mesh, &MeshSettings::adapt),
                     "raise the resolution, thicken thin walls, join slivers to their pieces, give each separate body "
                     "a piece (false: refuse such meshes)")
                 .json_unless_default()
                 .flag("--no-adapt", FlagKind::SetsFalse)},
            {}};
}

SettingsSection generate_section() {
    return {"generate",
            {custom("kind", "", "(required)", "beam, plate, chain",
                    "beam: `count` boxes in a row along x; plate: `count` x `count` boxes in the xz plane; chain: "
                    "`count` links lying on y = 0 between two end cubes (pieces 0 and count + 1, for "
                    "`[[object.driven]]`)",
                    read_generate_kind)
                 .json([](const Shot& s, ojson& j) { j["kind"] = to_string(s.generate->kind); }),
             whole("count", "count", generated(&GenerateSettings::count), kGenerateCountLimits,
                   "boxes in the row / per side of the plate / links")
                 .shows("beam 2, plate 5, chain 10"),
             vec3("size", "m", generated(&GenerateSettings::size), kGenerateSizeLimits, "[0.3, 0.03, 0.03]",
                  "full extents of one box (link)")
                 .shows("beam [0.3, 0.03, 0.03], plate [0.03, 0.03, 0.03], chain [0.03, 0.01, 0.01]"),
             custom("end_size", "m", "0.05", "1e-4 to 100", "chain only: edge of the end cubes", read_end_size)
                 .json([](const Shot& s, ojson& j) {
                     if (s.generate->kind == GenerateKind::Chain) j["end_size"] = s.generate->end_size;
                 }),
             whole("constraints_per_side", "count", generated(&GenerateSettings::constraints_per_side),
                   kConstraintsPerSideLimits, "n: n x n constraints per shared face (1: a ball joint at its centre)")
                 .shows("beam 2, plate 2, chain 1"),
             number("density", "kg/m^3", generated(&GenerateSettings::density), kDensityLimits, "density of the boxes")},
            {}};
}

SettingsSection prescore_section() {
    const PrescoreSettings d;
    return {"prescore",
            {whole("pieces", "count", at(&Shot::prescore, &PrescoreSettings::pieces), kPiecesLimits, "number of pieces")
                 .flag("--pieces"),
             seed("seed", at(&Shot::prescore, &PrescoreSettings::seed), "seed of the random choice of seed tets")
                 .flag("--seed"),
             custom("hollow", "length", "false (solid)", "1e-4 to 0.5 of the diagonal, or > 0 m",
                    "shell thickness: a fraction of the bounding-box diagonal (0.05) or a length (\"12mm\", "
                    "\"1.5cm\", \"0.02m\"); false: solid",
                    read_hollow)
                 .json([](const Shot& s, ojson& j) {
                     j["hollow"] = s.prescore.hollow ? ojson(s.prescore.hollow->str()) : ojson("solid");
                 })
                 .flag("--hollow")
                 .flag("--solid", FlagKind::SetsFalse),
             number("resolution", "", at(&Shot::prescore, &PrescoreSettings::resolution), kResolutionLimits,
                    "tet size = bounding-box diagonal / resolution")
                 .flag("--resolution"),
             number("density", "kg/m^3", at(&Shot::prescore, &PrescoreSettings::density), kDensityLimits,
                    "material density for masses and inertia")
                 .flag("--density"),
             custom("collision_tolerance", "length", d.collision_tolerance.str().c_str(), "0 to 1 of the diagonal, or >= 0 m",
                    "most mean gap between a collision part's hull and the piece's real shape",
                    [](TomlSection& s, Shot& shot) {
                        read_length(s, "collision_tolerance", shot.prescore.collision_tolerance,
                                    check_collision_tolerance);
                    })
                 .json([](const Shot& s, ojson& j) { j["collision_tolerance"] = s.prescore.collision_tolerance.str(); })
                 .flag("--collision-tolerance"),
             whole("collision_max_parts", "count", at(&Shot::prescore, &PrescoreSettings::collision_max_parts),
                   kCollisionPartsLimits, "most convex parts per piece")
                 .flag("--collision-max-parts"),
             whole("constraints_per_pair", "count", at(&Shot::prescore, &PrescoreSettings::constraints_per_pair),
                   kConstraintsPerPairLimits,
                   "most constraints joining two pieces: farthest-point sampled, keeping the pair's total area")
                 .shows("0 (all)")
                 .flag("--constraints-per-pair"),
             boolean("render_surface", at(&Shot::prescore, &PrescoreSettings::render_surface),
                     "draw each piece with the input surface cut along its fracture faces, smooth-shaded (false: its "
                     "tet surface, flat)")
                 .json_unless_default()
                 .flag("--no-render-surface", FlagKind::SetsFalse),
             boolean("crack_fairing", at(&Shot::prescore, &PrescoreSettings::crack_fairing),
                     "render surfaces: the crack between two pieces drawn as one smooth surface (false: the zigzag of "
                     "the tet faces between them)")
                 .json_unless_default(),
             boolean("crack_split", at(&Shot::prescore, &PrescoreSettings::crack_split),
                     "faired cracks: their last cut made on the crack tets split in eight, so that a crack bends within "
                     "a tet: fewer creases (docs/results/cracks.md) for a longer prescore (the split triples the crack "
                     "triangles the cut works through)")
                 .json_unless_default(),
             number("crack_roughness", "tet sizes", at(&Shot::prescore, &PrescoreSettings::crack_roughness),
                    kCrackRoughnessLimits,
                    "faired cracks: the most a crack point moves, by a seeded relief faded in over one wavelength from the "
                    "surface, the same on both sides (0: smooth, as glass breaks; 0.3 to 1: stone or concrete); cells it "
                    "would fold keep the tet faces, logged")
                 .json_unless_default(),
             number("crack_roughness_scale", "tet sizes",
                    at(&Shot::prescore, &PrescoreSettings::crack_roughness_scale), kCrackRoughnessScaleLimits,
                    "faired cracks: the relief's wavelength")
                 .json_unless_default(),
             choice<SeedMode>("seeds", at(&Shot::prescore, &PrescoreSettings::seeds),
                              {{"uniform", SeedMode::Uniform}, {"impact", SeedMode::Impact}, {"points", SeedMode::Points}},
                              "where the seed tets go: uniform: anywhere, pieces of about one size; impact: denser "
                              "where the object first hits (a rigid flight of the shot before the split), small pieces "
                              "there and large ones far from it; a shot without a contact falls back to uniform; "
                              "points: a piece from each of seed_points (pieces is then their number)",
                              "a seed placement", "use \"uniform\", \"impact\" or \"points\"")
                 .json_unless_default()
                 .flag("--seeds"),
             optional_number("impact_ratio", "", at(&Shot::prescore, &PrescoreSettings::impact_ratio),
                             kImpactRatioLimits,
                             "impact seeds: the density of seeds at the contact over the density far from it (pieces "
                             "there about this many times smaller); \"auto\": from the impact's speed and the material "
                             "(\"Impact seeds\" below)",
                             "\"auto\"", Unset::Omitted),
             custom("impact_radius", "length", "\"auto\"", "1e-3 to 10 of the diagonal, or > 0 m, or \"auto\"",
                    "impact seeds: the density falls off as exp(-(d / radius)^2) with the distance d from the "
                    "contact; \"auto\": as impact_ratio",
                    [](TomlSection& s, Shot& shot) {
                        const toml::node* n = s.node("impact_radius");
                        if (n && n->is_string() && n->as_string()->get() == "auto") {
                            shot.prescore.impact_radius.reset();
                            return;
                        }
                        Length radius = shot.prescore.impact_radius.value_or(Length{});
                        read_length(s, "impact_radius", radius, [](const std::string& where, const Length& l,
                                                                    bool from_flag) {
                            check_length(where, "impact_radius", l, kImpactRadiusRelativeLimits,
                                         kImpactRadiusAbsoluteLimits, from_flag);
                        }, ", or impact_radius = \"auto\"");
                        if (n) shot.prescore.impact_radius = radius;
                    })
                 .json([](const Shot& s, ojson& j) {
                     if (s.prescore.impact_radius) j["impact_radius"] = s.prescore.impact_radius->str();
                 }),
             custom("seed_points", "m", "[]", "each -1e6 to 1e6",
                    "seeds = \"points\": [[x, y, z], ...] in the model's frame (the mesh's coordinates at its scale, "
                    "before [object] places it); each point's tet (or the nearest, within a tet's size) seeds one piece",
                    read_seed_points)
                 .json([](const Shot& s, ojson& j) {
                     if (s.prescore.seed_points.empty()) return;
                     ojson a = ojson::array();
                     for (const auto& p : s.prescore.seed_points) a.push_back({p[0], p[1], p[2]});
                     j["seed_points"] = a;
                 })},
            {}};
}

}  // namespace shatter::table
