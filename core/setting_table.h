// Every setting of the shot, declared once. A section ([mesh], [prescore], [simulate], ...) is a
// table of settings; each entry gives the key, its unit, default, range, the text that explains
// it, the command-line flags that are aliases for it, and how to read it into the Shot. That one
// entry drives:
//   - the shot file reader and `--set SECTION.KEY=VALUE` (core/shot.cpp),
//   - the flags of the stage commands and their --help (cmd/, through apply_flag below),
//   - the settings JSON in model and trajectory files (settings_json: the table's order is the
//     JSON's key order, which files already written fix),
//   - the tables of docs/shot.md and docs/render.md (settings_markdown; a test keeps them equal).
// The definitions are in core/setting_table_*.cpp, one file per group of sections. Adding a
// setting is one entry there plus the field and the code that uses it.
//
// The arrays of tables ([[scene.colliders]], [[scene.kinematic]], [[object.driven]]) are declared
// the same way, by the table of one entry (collider_settings() below): it drives the entry's
// shot-file keys, its settings JSON, the reading of that JSON back (scene_from_json) and its docs
// table. core/shot_scene.cpp reads the arrays entry by entry and adds the checks that join keys.
// Composite values (render's piece_colours) keep hand-written readers (core/shot_render.cpp),
// called from their section's `read_extra`.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/shot.h"
#include "core/toml_reader.h"

namespace shatter {

// One object of a settings JSON read back strictly (scene_from_json): every key of its table must
// be there with its type, and no other key. `path` names the object in messages
// ("scene.colliders[1]"); errors are Error(BadInput) naming `source`. Values are checked for their
// type, not for the shot file's limits: the file was written from a shot that passed them. `j`
// must outlive the object.
class JsonObject {
public:
    JsonObject(const nlohmann::json& j, std::string source, std::string path);

    const nlohmann::json& at(const char* key);  // the value of a key that must be there
    bool has(const char* key) const { return j_.contains(key); }
    double number(const char* key);
    uint64_t whole(const char* key, uint64_t max);  // a whole number from 0 to max
    bool boolean(const char* key);
    std::string text(const char* key);
    Vec3 vec3(const char* key);
    std::array<float, 3> colour(const char* key);
    const nlohmann::json& array(const char* key);
    // Throws for a key that no getter asked for.
    void finish() const;

    std::string name(const char* key) const { return path_ + "." + key; }  // "scene.colliders[1].radius"
    [[noreturn]] void fail(const std::string& what, const std::string& problem) const;
    double number_value(const nlohmann::json& v, const std::string& what) const;
    const std::string& source() const { return source_; }

private:
    const nlohmann::json& j_;
    std::string source_;
    std::string path_;
    std::set<std::string> used_;
};

// How a command-line alias gives its setting a value: `--alpha 2` (Value), `--rollback`
// (SetsTrue), `--no-adapt` (SetsFalse).
enum class FlagKind { Value, SetsTrue, SetsFalse };

struct FlagAlias {
    std::string name;  // "--rate-limit"
    FlagKind kind = FlagKind::Value;
};

// One setting of a table whose values live in a Root: the Shot for the sections, an entry's
// struct for the arrays of tables ([[scene.colliders]]: ColliderSettings).
template <class Root>
struct BasicSetting {
    std::string key;           // "rate_limit"
    std::string unit;          // for the docs and --help ("s", "kg/m^3"; "" for none)
    std::string default_text;  // "0", "\"total\"", "(unset)"
    std::string range;         // "0 to 3600", "total, per_body"
    std::string help;          // what it means (docs and --help)
    std::vector<FlagAlias> flags;
    // Reads the key, when the section has it, into the root; checks it and throws with
    // TomlSection's messages ("WHERE: PROBLEM (fix: FIX)").
    std::function<void(TomlSection&, Root&)> read;
    // Writes the key into the settings JSON of model and trajectory files (or leaves it out,
    // e.g. a key that is written only when it is not the default, so that files made before it
    // existed keep their bytes).
    std::function<void(const Root&, nlohmann::ordered_json&)> write;
    std::function<bool(const Root&)> is_default;  // set by the builders that compare values
    // Reads the key back from the settings JSON (what `write` wrote), for the tables that are read
    // back: [scene] and its arrays of tables. Set by the builders but optional_number and custom.
    std::function<void(JsonObject&, Root&)> read_json;
    // False for a key of the settings JSON that the shot file does not have: the shot reader and
    // the docs table pass it by (a kinematic body's mesh and mesh_scale, written as a collider's).
    bool in_shot = true;

    BasicSetting& flag(std::string name, FlagKind kind = FlagKind::Value) {
        flags.push_back({std::move(name), kind});
        return *this;
    }
    BasicSetting& shows(std::string text) {  // the default as the docs and --help say it
        default_text = std::move(text);
        return *this;
    }
    BasicSetting& range_is(std::string text) {
        range = std::move(text);
        return *this;
    }
    BasicSetting& json(std::function<void(const Root&, nlohmann::ordered_json&)> writer) {
        write = std::move(writer);
        return *this;
    }
    BasicSetting& json_only() {  // in_shot = false
        in_shot = false;
        return *this;
    }
    // In the JSON only when not the default; read back as the default when absent.
    BasicSetting& json_unless_default() {
        write = [w = write, d = is_default](const Root& s, nlohmann::ordered_json& j) {
            if (!d(s)) w(s, j);
        };
        if (read_json)
            read_json = [r = read_json, k = key](JsonObject& o, Root& root) {
                if (o.has(k.c_str())) r(o, root);
            };
        return *this;
    }
};

using Setting = BasicSetting<Shot>;

struct SettingsSection {
    std::string name;  // "simulate"
    std::vector<Setting> settings;
    // Keys the table does not hold (the arrays of tables, each entry read by its own table) and
    // checks that join several keys; runs after the table's keys, before the unknown-key check.
    std::function<void(TomlSection&, Shot&)> read_extra = {};
    // Writes what read_extra reads, after the table's keys.
    std::function<void(const Shot&, nlohmann::ordered_json&)> write_extra = {};
    // Reads back what write_extra wrote (read_settings_json), for a section that is read back.
    std::function<void(JsonObject&, Shot&)> read_json_extra = {};
};

// The keys of one entry of [[scene.colliders]] and [[scene.kinematic]] (read by
// core/shot_scene.cpp, which adds the checks that join keys: a key the shape does not use,
// keys with velocity). The table's order is the entry's key order in the settings JSON.
const std::vector<BasicSetting<ColliderSettings>>& collider_settings();
const std::vector<BasicSetting<KinematicSettings>>& kinematic_settings();
const std::vector<BasicSetting<ProjectileSettings>>& projectile_settings();
// The keys of one [[object.driven]] entry (core/shot_scene.cpp adds: keys or velocity, not
// both, and no motion for a fixed piece).
const std::vector<BasicSetting<PieceDriveSettings>>& driven_settings();

// Reads the shot file's keys of one entry of an array of tables into `entry`; the caller adds its
// checks, then s.finish().
template <class Root>
void read_entry(const std::vector<BasicSetting<Root>>& table, TomlSection& s, Root& entry) {
    for (const BasicSetting<Root>& setting : table)
        if (setting.in_shot) setting.read(s, entry);
}

// The settings JSON of an array of tables: one object per entry, its table's keys in table order.
template <class Root>
nlohmann::ordered_json entries_json(const std::vector<BasicSetting<Root>>& table, const std::vector<Root>& entries) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const Root& entry : entries) {
        nlohmann::ordered_json j = nlohmann::ordered_json::object();
        for (const BasicSetting<Root>& setting : table) setting.write(entry, j);
        out.push_back(std::move(j));
    }
    return out;
}

// The inverse of entries_json: the array under `key` of `parent`, each entry named
// "PARENT.KEY[i]" in messages and read strictly (every key of the table, no other).
template <class Root>
std::vector<Root> entries_from_json(const std::vector<BasicSetting<Root>>& table, JsonObject& parent, const char* key) {
    const nlohmann::json& a = parent.array(key);
    std::vector<Root> out;
    for (size_t i = 0; i < a.size(); ++i) {
        JsonObject o(a[i], parent.source(), fmt::format("{}[{}]", parent.name(key), i));
        out.emplace_back();
        for (const BasicSetting<Root>& setting : table) setting.read_json(o, out.back());
        o.finish();
    }
    return out;
}

// The sections in shot-file order: mesh, generate, prescore, scene, object, material, simulate,
// render.
const std::vector<SettingsSection>& shot_settings();
const SettingsSection* find_settings_section(const std::string& name);

// Reads one section's table into the shot: every entry, then read_extra, then finish().
void read_settings_section(const SettingsSection& section, TomlSection& s, Shot& shot);

// The settings JSON of a section of `shot` (written into model and trajectory files): the
// table's keys in table order, then write_extra. The to_json functions of the settings structs
// call it.
nlohmann::ordered_json settings_json(const std::string& section, const Shot& shot);

// The inverse of settings_json for a section that is read back ([scene]: scene_from_json): the
// table's keys, then read_json_extra, then o.finish().
void read_settings_json(const std::string& section, JsonObject& o, Shot& shot);

// A flag's text as a TOML value, as `--set` takes it: 0.5, "12mm", [0, 1, 0], false; a bare
// word is a string. Throws Error(Usage) naming `where` when it is none of these.
toml::table parse_override_value(const std::string& value, const std::string& where);

// Applies one command-line alias of `setting` (in `section`) to the shot: `text` is the flag's
// value (ignored for SetsTrue/SetsFalse). Errors name the flag and are usage errors.
void apply_flag(const SettingsSection& section, const Setting& setting, const FlagAlias& alias,
                const std::string& text, Shot& shot);

// A shot with the defaults of every section and `overrides` (SECTION.KEY=VALUE, as load_shot
// takes them): the stage commands' --set without --shot.
Shot shot_from_overrides(const std::vector<std::string>& overrides);

// The Markdown table (| key | unit | default | range | flag | meaning |) of a section ("simulate")
// or an array of tables ("scene.colliders"), or the table of material presets
// ("material.presets", core/material_presets.h). Throws std::runtime_error on an unknown name.
std::string settings_markdown(const std::string& name);
// `doc` with the text between each "<!-- settings:NAME -->" and "<!-- /settings:NAME -->"
// replaced by settings_markdown(NAME).
std::string update_settings_docs(const std::string& doc);

// A number as the docs write it: 0.5, 3600, 1e-6, 1e10.
std::string short_number(double v);

}  // namespace shatter
