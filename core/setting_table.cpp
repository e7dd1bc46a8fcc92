#include "core/setting_table.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/material_presets.h"
#include "core/setting_builders.h"

namespace shatter {

JsonObject::JsonObject(const nlohmann::json& j, std::string source, std::string path)
    : j_(j), source_(std::move(source)), path_(std::move(path)) {
    if (!j_.is_object()) fail(path_, "is not a JSON object");
}

const nlohmann::json& JsonObject::at(const char* key) {
    used_.insert(key);
    auto it = j_.find(key);
    if (it == j_.end()) fail(name(key), "is missing");
    return *it;
}

double JsonObject::number(const char* key) { return number_value(at(key), name(key)); }

uint64_t JsonObject::whole(const char* key, uint64_t max) {
    const auto& v = at(key);
    if (!v.is_number_unsigned() || v.get<uint64_t>() > max)
        fail(name(key), fmt::format("must be a whole number from 0 to {}", max));
    return v.get<uint64_t>();
}

bool JsonObject::boolean(const char* key) {
    const auto& v = at(key);
    if (!v.is_boolean()) fail(name(key), "must be true or false");
    return v.get<bool>();
}

std::string JsonObject::text(const char* key) {
    const auto& v = at(key);
    if (!v.is_string()) fail(name(key), "must be a string");
    return v.get<std::string>();
}

Vec3 JsonObject::vec3(const char* key) {
    const auto& v = at(key);
    if (!v.is_array() || v.size() != 3) fail(name(key), "must be an array of 3 numbers");
    return Vec3(number_value(v[0], name(key)), number_value(v[1], name(key)), number_value(v[2], name(key)));
}

std::array<float, 3> JsonObject::colour(const char* key) {
    const Vec3 c = vec3(key);
    return {static_cast<float>(c.x()), static_cast<float>(c.y()), static_cast<float>(c.z())};
}

const nlohmann::json& JsonObject::array(const char* key) {
    const auto& v = at(key);
    if (!v.is_array()) fail(name(key), "must be an array");
    return v;
}

void JsonObject::finish() const {
    for (auto it = j_.begin(); it != j_.end(); ++it)
        if (!used_.count(it.key())) fail(name(it.key().c_str()), "is not a known setting");
}

void JsonObject::fail(const std::string& what, const std::string& problem) const {
    throw_input_error(source_, "settings JSON: " + what + " " + problem,
                      "make the file again with this version of shatter");
}

double JsonObject::number_value(const nlohmann::json& v, const std::string& what) const {
    if (!v.is_number()) fail(what, "must be a number");
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(what, "is not a finite number");
    return d;
}

const std::vector<SettingsSection>& shot_settings() {
    static const std::vector<SettingsSection> sections = {
        table::mesh_section(),     table::generate_section(), table::prescore_section(), table::scene_section(),
        table::object_section(),   table::material_section(), table::simulate_section(), table::render_section()};
    return sections;
}

const SettingsSection* find_settings_section(const std::string& name) {
    for (const SettingsSection& s : shot_settings())
        if (s.name == name) return &s;
    return nullptr;
}

void read_settings_section(const SettingsSection& section, TomlSection& s, Shot& shot) {
    for (const Setting& setting : section.settings)
        if (setting.in_shot) setting.read(s, shot);
    if (section.read_extra) section.read_extra(s, shot);
    s.finish();
}

nlohmann::ordered_json settings_json(const std::string& name, const Shot& shot) {
    const SettingsSection* section = find_settings_section(name);
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (const Setting& setting : section->settings) setting.write(shot, j);
    if (section->write_extra) section->write_extra(shot, j);
    return j;
}

void read_settings_json(const std::string& name, JsonObject& o, Shot& shot) {
    const SettingsSection* section = find_settings_section(name);
    for (const Setting& setting : section->settings) setting.read_json(o, shot);
    if (section->read_json_extra) section->read_json_extra(o, shot);
    o.finish();
}

void apply_flag(const SettingsSection& section, const Setting& setting, const FlagAlias& alias,
                const std::string& text, Shot& shot) {
    toml::table value;
    if (alias.kind == FlagKind::Value) {
        toml::table parsed = parse_override_value(text, alias.name);
        value.insert_or_assign(setting.key, std::move(*parsed.get("v")));
    } else {
        value.insert_or_assign(setting.key, alias.kind == FlagKind::SetsTrue);
    }
    TomlSection s(value, alias.name, section.name, true);
    setting.read(s, shot);
}

namespace {

std::string without_exponent_padding(const std::string& text) {  // 1e+06 -> 1e6, 1e-06 -> 1e-6
    const size_t e = text.find('e');
    if (e == std::string::npos) return text;
    return text.substr(0, e) + "e" + std::to_string(std::stoi(text.substr(e + 1)));
}

}  // namespace

std::string short_number(double v) {
    const std::string plain = without_exponent_padding(fmt::format("{:g}", v));
    for (int digits = 0; digits <= 3 && v != 0; ++digits) {  // 100000 -> 1e5, when clearly shorter
        const std::string e = without_exponent_padding(fmt::format("{:.{}e}", v, digits));
        if (std::stod(e) == v) return e.size() + 2 <= plain.size() ? e : plain;
    }
    return plain;
}

namespace {

template <class Root>
std::string markdown(const std::vector<BasicSetting<Root>>& settings) {
    std::string out = "| key | unit | default | range | flag | meaning |\n| --- | --- | --- | --- | --- | --- |\n";
    for (const BasicSetting<Root>& s : settings) {
        if (!s.in_shot) continue;
        std::string flags;
        for (const FlagAlias& f : s.flags) flags += fmt::format("{}`{}`", flags.empty() ? "" : ", ", f.name);
        out += fmt::format("| {} | {} | {} | {} | {} | {} |\n", s.key, s.unit, s.default_text, s.range, flags, s.help);
    }
    return out;
}

}  // namespace

std::string settings_markdown(const std::string& name) {
    if (name == "scene.colliders") return markdown(collider_settings());
    if (name == "scene.kinematic") return markdown(kinematic_settings());
    if (name == "scene.projectile") return markdown(projectile_settings());
    if (name == "object.driven") return markdown(driven_settings());
    if (name == "material.presets") return material_presets_markdown();
    const SettingsSection* section = find_settings_section(name);
    if (!section) throw std::runtime_error("no settings section '" + name + "'");
    return markdown(section->settings);
}

std::string update_settings_docs(const std::string& doc) {
    std::string out;
    size_t pos = 0;
    const std::string open = "<!-- settings:";
    while (true) {
        const size_t begin = doc.find(open, pos);
        if (begin == std::string::npos) break;
        const size_t name_end = doc.find(" -->\n", begin);
        if (name_end == std::string::npos) throw std::runtime_error("a settings marker without its end: " + doc.substr(begin, 40));
        const std::string name = doc.substr(begin + open.size(), name_end - begin - open.size());
        const std::string close = "<!-- /settings:" + name + " -->";
        const size_t end = doc.find(close, name_end);
        if (end == std::string::npos) throw std::runtime_error("no closing marker " + close);
        out += doc.substr(pos, name_end + 5 - pos) + settings_markdown(name);
        pos = end;
    }
    return out + doc.substr(pos);
}

}  // namespace shatter
