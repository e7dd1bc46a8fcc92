#include "core/shot.h"

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/error.h"
#include "core/setting_table.h"
#include "core/toml_reader.h"

namespace shatter {

toml::table parse_override_value(const std::string& value, const std::string& where) {
    try {
        return toml::parse("v = " + value, where);
    } catch (const toml::parse_error&) {
        // A bare word (e.g. --set mesh.repair=never) is a string.
        if (value.empty() || value.find_first_of("\"'[]{}=\n") != std::string::npos)
            throw Error(ExitCode::Usage, fmt::format("{}: '{}' is not a value (fix: write a number, true/false, "
                                                     "a \"string\" or an [array] as in the shot file)", where, value));
        return toml::parse("v = \"" + value + "\"", where);
    }
}

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
        toml::table parsed = parse_override_value(o.substr(eq + 1), where);
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
    for (const SettingsSection& settings : shot_settings()) {
        const toml::table* t = section(settings.name.c_str());
        if (!t) continue;
        TomlSection s(*t, path, settings.name);
        if (settings.name == "generate") {
            if (root.get("mesh"))
                s.fail(nullptr, "the shot has both [mesh] and [generate]",
                       "keep [mesh] (fracture a mesh file) or [generate] (a beam, plate or chain built from boxes)");
            shot.generate.emplace();
        }
        read_settings_section(settings, s, shot);
    }
    top.finish();
    return shot;
}

}  // namespace

Shot shot_from_overrides(const std::vector<std::string>& overrides) {
    toml::table root;
    return read_shot(root, "", overrides);
}

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
