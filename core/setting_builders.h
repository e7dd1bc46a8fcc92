// The kinds of setting a section table declares (private to core/setting_table_*.cpp): each
// builder makes one Setting from the key, where its value lives in the Shot, its limits and its
// help, and fills the default and range columns from them.
//
//   at(&Shot::material, &MaterialSettings::alpha)    the field a setting reads into
//   number / whole / seed / boolean / choice / optional_number / vec3 / text / key_frames /
//   linear_colour / custom
// A builder's Root is the Shot for a section's table, an entry's struct for an array of tables
// (number<ColliderSettings>(...)). The builders but optional_number and custom also read their
// key back from the settings JSON (read_json).
#pragma once

#include <charconv>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/setting_table.h"
#include "core/shot_sections.h"

namespace shatter::table {

// The field at a path of member pointers from the Shot: at(&Shot::scene, &SceneSettings::ground).
template <class... M>
auto at(M... members) {
    return [=](auto& root) -> auto& { return (root .* ... .* members); };
}

// The field of the [generate] section (set while that section is read).
template <class M>
auto generated(M member) {
    return [=](Shot& s) -> auto& { return (*s.generate).*member; };
}

// The defaults every table's default column is taken from.
template <class Root>
Root& defaults() {
    static Root root;
    return root;
}
template <>
inline Shot& defaults<Shot>() {
    static Shot shot = [] {
        Shot s;
        s.generate = GenerateSettings{};
        return s;
    }();
    return shot;
}

inline std::string range_of(const Limits& l) { return short_number(l.min) + " to " + short_number(l.max); }

// The value as it is (a number keeps its C++ type: uint32_t, uint64_t or double), and the
// comparison with the default.
template <class Root, class Get>
BasicSetting<Root> with_value_json(BasicSetting<Root> s, const char* key, Get get) {
    s.write = [key, get](const Root& root, nlohmann::ordered_json& j) { j[key] = get(const_cast<Root&>(root)); };
    s.is_default = [get](const Root& root) { return get(const_cast<Root&>(root)) == get(defaults<Root>()); };
    return s;
}

template <class Root = Shot, class Get>
BasicSetting<Root> number(const char* key, const char* unit, Get get, Limits limits, const char* help) {
    BasicSetting<Root> s{key, unit, short_number(get(defaults<Root>())), range_of(limits), help, {}, {}, {}, {}, {}, true};
    s.read = [key, get, limits](TomlSection& t, Root& shot) { t.number(key, get(shot), limits); };
    s.read_json = [key, get](JsonObject& o, Root& root) { get(root) = o.number(key); };
    return with_value_json(s, key, get);
}

// Reads a whole number of the field's type back from the JSON.
template <class Root, class Get>
void whole_json(BasicSetting<Root>& s, const char* key, Get get) {
    s.read_json = [key, get](JsonObject& o, Root& root) {
        using T = std::remove_reference_t<decltype(get(root))>;
        get(root) = static_cast<T>(o.whole(key, std::numeric_limits<T>::max()));
    };
}

template <class Root = Shot, class Get>
BasicSetting<Root> whole(const char* key, const char* unit, Get get, Limits limits, const char* help) {
    BasicSetting<Root> s{key, unit, std::to_string(get(defaults<Root>())), range_of(limits), help, {}, {}, {}, {}, {}, true};
    s.read = [key, get, limits](TomlSection& t, Root& shot) { t.integer(key, get(shot), limits); };
    whole_json(s, key, get);
    return with_value_json(s, key, get);
}

template <class Root = Shot, class Get>
BasicSetting<Root> seed(const char* key, Get get, const char* help) {
    BasicSetting<Root> s{key, "", std::to_string(get(defaults<Root>())), ">= 0", help, {}, {}, {}, {}, {}, true};
    s.read = [key, get](TomlSection& t, Root& shot) { t.integer(key, get(shot)); };
    whole_json(s, key, get);
    return with_value_json(s, key, get);
}

template <class Root = Shot, class Get>
BasicSetting<Root> boolean(const char* key, Get get, const char* help) {
    BasicSetting<Root> s{key, "", get(defaults<Root>()) ? "true" : "false", "true, false", help, {}, {}, {}, {}, {}, true};
    s.read = [key, get](TomlSection& t, Root& shot) { t.boolean(key, get(shot)); };
    s.read_json = [key, get](JsonObject& o, Root& root) { get(root) = o.boolean(key); };
    return with_value_json(s, key, get);
}

// A string (a name, a file).
template <class Root = Shot, class Get>
BasicSetting<Root> text(const char* key, Get get, const char* help) {
    BasicSetting<Root> s{key, "", fmt::format("\"{}\"", get(defaults<Root>())), "", help, {}, {}, {}, {}, {}, true};
    s.read = [key, get](TomlSection& t, Root& root) { t.text(key, get(root)); };
    s.read_json = [key, get](JsonObject& o, Root& root) { get(root) = o.text(key); };
    return with_value_json(s, key, get);
}

// A string that must be one of `names`. `noun` ("a repair mode") and `fix` replace the generic
// "is not one of ..." and "use ..." in the message when given.
template <class E, class Root = Shot, class Get>
BasicSetting<Root> choice(const char* key, Get get, std::vector<std::pair<const char*, E>> names, const char* help,
               const char* noun = "", const char* fix = "") {
    std::vector<std::string> plain, quoted;
    std::string def;
    for (const auto& [name, value] : names) {
        plain.push_back(name);
        quoted.push_back(fmt::format("\"{}\"", name));
        if (value == get(defaults<Root>())) def = quoted.back();
    }
    BasicSetting<Root> s{key, "", def, fmt::format("{}", fmt::join(plain, ", ")), help, {}, {}, {}, {}, {}, true};
    s.read = [=](TomlSection& t, Root& shot) {
        std::string text;
        if (!t.text(key, text)) return;
        for (const auto& [name, value] : names)
            if (text == name) {
                get(shot) = value;
                return;
            }
        const std::string problem = *noun ? fmt::format("{} = \"{}\" is not {}", t.key_name(key), text, noun)
                                          : fmt::format("{} = \"{}\" is not one of {}", t.key_name(key), text,
                                                        fmt::join(quoted, ", "));
        t.fail(t.node(key), problem, *fix ? std::string(fix) : fmt::format("use {}", fmt::join(quoted, " or ")));
    };
    s.write = [key, get, names](const Root& shot, nlohmann::ordered_json& j) {
        for (const auto& [name, value] : names)
            if (value == get(const_cast<Root&>(shot))) j[key] = name;
    };
    std::string alternatives = plain.front();  // "box, sphere, plane or mesh"
    for (size_t i = 1; i < plain.size(); ++i) alternatives += (i + 1 < plain.size() ? ", " : " or ") + plain[i];
    s.read_json = [key, get, names, alternatives](JsonObject& o, Root& root) {
        const std::string text = o.text(key);
        for (const auto& [name, value] : names)
            if (text == name) {
                get(root) = value;
                return;
            }
        o.fail(o.name(key), fmt::format("= \"{}\" is not {}", text, alternatives));
    };
    s.is_default = [get](const Root& shot) { return get(const_cast<Root&>(shot)) == get(defaults<Root>()); };
    return s;
}

// How the JSON says an optional number is unset.
enum class Unset { Auto, Null, Omitted };

// An optional number: unset by default ("auto" in the file unsets it too).
template <class Root = Shot, class Get>
BasicSetting<Root> optional_number(const char* key, const char* unit, Get get, Limits limits, const char* help,
                        const char* unset_text, Unset unset_json) {
    BasicSetting<Root> s{key, unit, unset_text, range_of(limits) + ", or \"auto\"", help, {}, {}, {}, {}, {}, true};
    s.read = [key, get, limits](TomlSection& t, Root& shot) {
        const toml::node* n = t.node(key);
        if (n && n->is_string() && n->as_string()->get() == "auto") {
            get(shot).reset();
            return;
        }
        double v = 0;
        if (t.number(key, v, limits)) get(shot) = v;
    };
    s.write = [key, get, unset_json](const Root& shot, nlohmann::ordered_json& j) {
        const std::optional<double>& v = get(const_cast<Root&>(shot));
        if (v)
            j[key] = *v;
        else if (unset_json == Unset::Auto)
            j[key] = "auto";
        else if (unset_json == Unset::Null)
            j[key] = nullptr;
    };
    return s;
}

template <class Root = Shot, class Get>
BasicSetting<Root> vec3(const char* key, const char* unit, Get get, Limits limits, const char* example, const char* help) {
    const Vec3 d = get(defaults<Root>());
    BasicSetting<Root> s{key, unit, fmt::format("[{}, {}, {}]", short_number(d.x()), short_number(d.y()), short_number(d.z())),
              "each " + range_of(limits), help, {}, {}, {}, {}, {}, true};
    s.read = [key, get, limits, example](TomlSection& t, Root& shot) {
        read_numbers(t, key, get(shot).data(), 3, limits, example);
    };
    s.write = [key, get](const Root& shot, nlohmann::ordered_json& j) {
        const Vec3& v = get(const_cast<Root&>(shot));
        j[key] = nlohmann::ordered_json::array({v.x(), v.y(), v.z()});
    };
    s.read_json = [key, get](JsonObject& o, Root& root) { get(root) = o.vec3(key); };
    return s;
}

// A setting with its own reader; the docs columns are given, and its JSON with .json().
template <class T>
struct not_deduced {
    using type = T;
};

template <class Root = Shot>
BasicSetting<Root> custom(const char* key, const char* unit, const char* def, const char* range, const char* help,
                          std::function<void(TomlSection&, typename not_deduced<Root>::type&)> read) {
    BasicSetting<Root> s{key, unit, def, range, help, {}, std::move(read), {}, {}, {}, true};
    return s;
}

// keys = [[t, x, y, z], ...] (read_keys, core/shot_scene.cpp); the JSON has [] for none.
template <class Root>
BasicSetting<Root> key_frames(std::vector<KeyFrame> Root::*member, const char* unit, const char* def,
                              const char* range, const char* help) {
    BasicSetting<Root> s{"keys", unit, def, range, help, {}, {}, {}, {}, {}, true};
    s.read = [member](TomlSection& t, Root& root) { read_keys(t, root.*member); };
    s.write = [member](const Root& root, nlohmann::ordered_json& j) { j["keys"] = keys_json(root.*member); };
    s.read_json = [member](JsonObject& o, Root& root) { root.*member = keys_from_json(o, "keys"); };
    return s;
}

// A float as the shortest decimal that reads back as the same float (0.6f is written 0.6).
inline double short_float(float f) {
    const std::string text = fmt::format("{}", f);
    double d = f;
    std::from_chars(text.data(), text.data() + text.size(), d);
    return d;
}

// A colour in linear RGB, [r, g, b] each 0 to 1 (colliders and kinematic bodies).
template <class Root>
BasicSetting<Root> linear_colour(std::array<float, 3> Root::*member, const char* help) {
    const std::array<float, 3>& d = defaults<Root>().*member;
    BasicSetting<Root> s{"colour", "linear RGB",
                         fmt::format("[{}, {}, {}]", short_number(d[0]), short_number(d[1]), short_number(d[2])),
                         "each 0 to 1", help, {}, {}, {}, {}, {}, true};
    s.read = [member](TomlSection& t, Root& root) {
        Vec3 c;
        if (!read_numbers(t, "colour", c.data(), 3, Limits{0, 1, "(linear RGB)"}, "[0.8, 0.2, 0.1]")) return;
        root.*member = {static_cast<float>(c.x()), static_cast<float>(c.y()), static_cast<float>(c.z())};
    };
    s.write = [member](const Root& root, nlohmann::ordered_json& j) {
        const std::array<float, 3>& c = root.*member;
        j["colour"] = nlohmann::ordered_json::array({short_float(c[0]), short_float(c[1]), short_float(c[2])});
    };
    s.read_json = [member](JsonObject& o, Root& root) { root.*member = o.colour("colour"); };
    return s;
}

// The sections, one function each (core/setting_table_prescore.cpp, _scene.cpp, _render.cpp).
SettingsSection mesh_section();
SettingsSection generate_section();
SettingsSection prescore_section();
SettingsSection scene_section();
SettingsSection object_section();
SettingsSection material_section();
SettingsSection simulate_section();
SettingsSection render_section();

}  // namespace shatter::table
