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
// Arrays of tables ([[scene.colliders]], [[scene.kinematic]], [[object.driven]]) and composite
// values (render's piece_colours) keep hand-written readers (core/shot_scene.cpp,
// core/shot_render.cpp), called from their section's `read_extra`.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/shot.h"
#include "core/toml_reader.h"

namespace shatter {

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
    // In the JSON only when not the default.
    BasicSetting& json_unless_default() {
        write = [w = write, d = is_default](const Root& s, nlohmann::ordered_json& j) {
            if (!d(s)) w(s, j);
        };
        return *this;
    }
};

using Setting = BasicSetting<Shot>;

struct SettingsSection {
    std::string name;  // "simulate"
    std::vector<Setting> settings;
    // Keys the table does not hold (arrays of tables) and checks that join several keys; runs
    // after the table's keys, before the unknown-key check.
    std::function<void(TomlSection&, Shot&)> read_extra;
    // Writes what read_extra reads, after the table's keys.
    std::function<void(const Shot&, nlohmann::ordered_json&)> write_extra;
};

// The keys of one entry of [[scene.colliders]] and [[scene.kinematic]] (read by
// core/shot_scene.cpp, which adds the checks that join keys: a key the shape does not use,
// keys with velocity).
const std::vector<BasicSetting<ColliderSettings>>& collider_settings();
const std::vector<BasicSetting<KinematicSettings>>& kinematic_settings();
// The keys of one [[object.driven]] entry (core/shot_scene.cpp adds: keys or velocity, not
// both, and no motion for a fixed piece).
const std::vector<BasicSetting<PieceDriveSettings>>& driven_settings();

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
