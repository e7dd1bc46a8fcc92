#include "core/shot.h"

#include <filesystem>

#include <fmt/format.h>

#include "core/error.h"
#include "core/shot_sections.h"
#include "core/toml_reader.h"

namespace shatter {

namespace {

void read_mesh(TomlSection& s, MeshSettings& mesh, const std::string& shot_path) {
    if (s.text("path", mesh.path) && !mesh.path.empty()) {
        std::filesystem::path p(mesh.path);
        if (p.is_relative()) mesh.path = (std::filesystem::path(shot_path).parent_path() / p).lexically_normal().string();
    }
    double number = 0;
    if (s.number("scale", number, kScaleLimits)) mesh.scale = number;
    if (s.number("size", number, kSizeLimits)) mesh.size = number;
    s.boolean("adapt", mesh.adapt);
    std::string repair;
    if (s.text("repair", repair)) {
        auto mode = parse_repair_mode(repair);
        if (!mode) s.fail(s.node("repair"), fmt::format("mesh.repair = \"{}\" is not a repair mode", repair),
                          "use \"auto\", \"always\" or \"never\"");
        mesh.repair = *mode;
    }
    s.number("wrap_alpha", mesh.wrap_alpha, kWrapAlphaLimits);
    s.number("wrap_offset", mesh.wrap_offset, kWrapOffsetLimits);
    s.finish();
}

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
    check(s.where(n), out, false);
}

// hollow: a length, or false for solid.
void read_hollow(TomlSection& s, PrescoreSettings& p) {
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

void read_prescore(TomlSection& s, PrescoreSettings& p) {
    s.integer("pieces", p.pieces, kPiecesLimits);
    s.integer("seed", p.seed);
    read_hollow(s, p);
    s.number("resolution", p.resolution, kResolutionLimits);
    s.number("density", p.density, kDensityLimits);
    read_length(s, "collision_tolerance", p.collision_tolerance, check_collision_tolerance);
    s.integer("collision_max_parts", p.collision_max_parts, kCollisionPartsLimits);
    s.integer("constraints_per_pair", p.constraints_per_pair, kConstraintsPerPairLimits);
    s.finish();
}

}  // namespace

bool is_shot_path(const std::string& path) { return std::filesystem::path(path).extension() == ".toml"; }

void apply_shot_overrides(toml::table& root, const std::vector<std::string>& overrides) {
    for (const std::string& o : overrides) {
        const std::string where = "--set " + o;
        const size_t eq = o.find('=');
        const std::string key = o.substr(0, eq);
        const size_t dot = key.rfind('.');
        if (eq == std::string::npos || dot == std::string::npos || dot == 0 || dot + 1 == key.size())
            throw Error(ExitCode::Usage, fmt::format("{}: not SECTION.KEY=VALUE (fix: e.g. --set material.alpha=0.5; "
                                                     "the sections and keys are in docs/shot.md)", where));
        const std::string value = o.substr(eq + 1);
        toml::table parsed;
        try {
            parsed = toml::parse("v = " + value, where);
        } catch (const toml::parse_error&) {
            // A bare word (e.g. --set mesh.repair=never) is a string.
            if (value.empty() || value.find_first_of("\"'[]{}=\n") != std::string::npos)
                throw Error(ExitCode::Usage, fmt::format("{}: '{}' is not a value (fix: write a number, true/false, "
                                                         "a \"string\" or an [array] as in the shot file)", where, value));
            parsed = toml::parse("v = \"" + value + "\"", where);
        }
        // Walk (and create) the tables of the dotted section name, then set the key.
        toml::table* table = &root;
        size_t start = 0;
        while (start < dot) {
            const size_t next = std::min(key.find('.', start), dot);
            const std::string part = key.substr(start, next - start);
            toml::node* n = table->get(part);
            if (!n) n = &table->insert_or_assign(part, toml::table{}).first->second;
            if (!n->is_table())
                throw Error(ExitCode::Usage, fmt::format("{}: '{}' is not a table of the shot (fix: --set "
                                                         "SECTION.KEY=VALUE, see docs/shot.md)", where, part));
            table = n->as_table();
            start = next + 1;
        }
        table->insert_or_assign(key.substr(dot + 1), std::move(*parsed.get("v")));
    }
}

namespace {

Shot read_shot(toml::table& root, const std::string& path, const std::vector<std::string>& overrides) {
    apply_shot_overrides(root, overrides);
    Shot shot;
    shot.path = path;
    TomlSection top(root, path, "");
    auto section = [&](const char* name) -> const toml::table* {
        const toml::node* n = top.node(name);
        if (n && !n->is_table()) top.fail(n, fmt::format("'{}' must be a table: [{}]", name, name), "see docs/shot.md");
        return n ? n->as_table() : nullptr;
    };
    auto read = [&](const char* name, auto reader) {
        if (const toml::table* t = section(name)) {
            TomlSection s(*t, path, name);
            reader(s);
        }
    };
    read("mesh", [&](TomlSection& s) { read_mesh(s, shot.mesh, path); });
    read("generate", [&](TomlSection& s) {
        if (root.get("mesh"))
            s.fail(nullptr, "the shot has both [mesh] and [generate]",
                   "keep [mesh] (fracture a mesh file) or [generate] (a beam, plate or chain built from boxes)");
        read_generate_section(s, shot.generate.emplace());
    });
    read("prescore", [&](TomlSection& s) { read_prescore(s, shot.prescore); });
    read("scene", [&](TomlSection& s) { read_scene_section(s, shot.scene, path); });
    read("object", [&](TomlSection& s) { read_object_section(s, shot.object); });
    read("material", [&](TomlSection& s) { read_material_section(s, shot.material); });
    read("simulate", [&](TomlSection& s) { read_simulate_section(s, shot.simulate); });
    read("render", [&](TomlSection& s) { read_render_section(s, shot.render); });
    top.finish();
    return shot;
}

}  // namespace

Shot load_shot(const std::string& path, const std::vector<std::string>& overrides) {
    toml::table root = parse_toml_file(path);
    return read_shot(root, path, overrides);
}

Shot default_shot_for_mesh(const std::string& mesh_path, const std::vector<std::string>& overrides) {
    toml::table root = toml::parse(std::string_view(kDefaultShot), std::string_view("the default shot"));
    // The mesh path is taken as given (relative to the current folder), not as a shot's
    // relative path; the "path" key of an override still applies on top.
    root.insert_or_assign("mesh", toml::table{});
    Shot shot = read_shot(root, "", overrides);
    if (shot.mesh.path.empty()) shot.mesh.path = mesh_path;
    return shot;
}

Shot load_shot_or_mesh(const std::string& path, const std::vector<std::string>& overrides) {
    return is_shot_path(path) ? load_shot(path, overrides) : default_shot_for_mesh(path, overrides);
}

}  // namespace shatter
