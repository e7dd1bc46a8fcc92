// The shot file's arrays of tables: [[scene.colliders]], [[scene.kinematic]] and
// [[object.driven]] (docs/shot.md). The keys of an entry are declared by its table
// (collider_settings() ..., core/setting_table_scene.cpp); this file reads the entries and adds
// the checks that join keys. Every key is checked against its limits where it is read; each
// entry of an array of tables is read as its own section, named "scene.colliders[2]"
// (0-based), so that an unknown key there is an error with file:line.
#include <filesystem>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/setting_table.h"
#include "core/shot_sections.h"

namespace shatter {

namespace {

constexpr Limits kKeyTimeLimits{0, 3600, "s"};

// An array of `n` numbers, each within `limits`; `example` is a valid value for the fix.
bool numbers(TomlSection& s, const char* key, double* out, size_t n, const Limits& limits, const char* example) {
    const toml::node* node = s.node(key);
    if (!node) return false;
    const toml::array* a = node->as_array();
    if (!a || a->size() != n)
        s.fail(node, fmt::format("{} must be an array of {} numbers ({})", s.key_name(key), n, limits.unit),
               fmt::format("write e.g. {} = {}", key, example));
    std::vector<double> values(n);
    for (size_t i = 0; i < n; ++i) {
        const toml::node& e = *a->get(i);
        const std::string name = fmt::format("{}[{}]", s.key_name(key), i);
        auto v = e.value<double>();
        if (!v) s.fail(&e, name + " is not a number", fmt::format("write e.g. {} = {}", key, example));
        check_limits(s.where(&e), name, *v, limits, s.from_flag());
        values[i] = *v;
    }
    std::copy(values.begin(), values.end(), out);
    return true;
}

std::string beside_shot(const std::string& path, const std::string& shot_path) {
    std::filesystem::path p(path);
    if (p.is_relative()) return (std::filesystem::path(shot_path).parent_path() / p).lexically_normal().string();
    return path;
}

// Refuses a key that the chosen shape does not read, instead of ignoring it.
void refuse_for_shape(TomlSection& s, bool given, const char* key, ShapeKind kind) {
    if (!given) return;
    s.fail(s.node(key), fmt::format("{} does not apply to shape = \"{}\"", s.key_name(key), to_string(kind)),
           fmt::format("remove {} or choose the shape it belongs to (docs/shot.md)", key));
}

// After the table's keys (core/setting_table_scene.cpp): refuses a key the shape does not use
// and resolves a mesh collider's file.
void check_shape(TomlSection& s, ShapeSettings& shape, const std::string& shot_path, bool kinematic) {
    const ShapeKind k = shape.kind;
    refuse_for_shape(s, s.node("size") && k != ShapeKind::Box, "size", k);
    refuse_for_shape(s, s.node("radius") && k != ShapeKind::Sphere, "radius", k);
    if (kinematic) return;  // mesh and mesh_scale are unknown keys there
    const bool mesh = s.node("mesh");
    refuse_for_shape(s, mesh && k != ShapeKind::Mesh, "mesh", k);
    refuse_for_shape(s, s.node("mesh_scale") && k != ShapeKind::Mesh, "mesh_scale", k);
    if (k == ShapeKind::Mesh) {
        if (shape.mesh.empty())
            s.fail(mesh ? s.node("mesh") : s.node("shape"),
                   fmt::format("{} = \"mesh\" needs a mesh file", s.key_name("shape")),
                   "add mesh = \"FILE\" (relative to the shot file's folder)");
        shape.mesh = beside_shot(shape.mesh, shot_path);
    }
}

void read_collider(TomlSection& s, ColliderSettings& c, const std::string& shot_path) {
    read_entry(collider_settings(), s, c);
    check_shape(s, c.shape, shot_path, false);
    s.finish();
}

}  // namespace

// keys = [[t, x, y, z], ...]: times in seconds, strictly increasing.
void read_keys(TomlSection& s, std::vector<KeyFrame>& keys) {
    const toml::node* n = s.node("keys");
    if (!n) return;
    const char* fix = "write keys = [[0, 0, 1, 0], [2, 1, 1, 0]] (time in s, then x, y, z in m)";
    const toml::array* a = n->as_array();
    if (!a || a->empty()) s.fail(n, s.key_name("keys") + " must be a non-empty array of [t, x, y, z]", fix);
    for (size_t i = 0; i < a->size(); ++i) {
        const toml::node& e = *a->get(i);
        const std::string name = fmt::format("{}[{}]", s.key_name("keys"), i);
        const toml::array* k = e.as_array();
        if (!k || k->size() != 4) s.fail(&e, name + " must be an array of 4 numbers [t, x, y, z]", fix);
        KeyFrame f;
        for (size_t c = 0; c < 4; ++c) {
            const toml::node& v = *k->get(c);
            auto d = v.value<double>();
            if (!d) s.fail(&v, fmt::format("{}[{}] is not a number", name, c), fix);
            check_limits(s.where(&v), fmt::format("{}[{}]", name, c), *d, c ? kPositionLimits : kKeyTimeLimits, false);
            (c ? f.position[c - 1] : f.time) = *d;
        }
        if (!keys.empty() && !(f.time > keys.back().time))
            s.fail(&e, fmt::format("{} has time {:g} s, not after the key before it ({:g} s)", name, f.time,
                                   keys.back().time),
                   "list the keys in increasing time, each time once");
        keys.push_back(f);
    }
}

nlohmann::ordered_json keys_json(const std::vector<KeyFrame>& keys) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const KeyFrame& f : keys) out.push_back({f.time, f.position.x(), f.position.y(), f.position.z()});
    return out;
}

std::vector<KeyFrame> keys_from_json(JsonObject& o, const char* key) {
    const nlohmann::json& a = o.array(key);
    std::vector<KeyFrame> keys;
    for (size_t i = 0; i < a.size(); ++i) {
        const std::string what = fmt::format("{}[{}]", o.name(key), i);
        if (!a[i].is_array() || a[i].size() != 4) o.fail(what, "must be an array [t, x, y, z]");
        KeyFrame f;
        f.time = o.number_value(a[i][0], what);
        for (int c = 0; c < 3; ++c) f.position[c] = o.number_value(a[i][c + 1], what);
        if (!keys.empty() && !(f.time > keys.back().time)) o.fail(what, "has a time not after the key before it");
        keys.push_back(f);
    }
    return keys;
}

namespace {

void read_kinematic(TomlSection& s, KinematicSettings& k, const std::string& shot_path) {
    read_entry(kinematic_settings(), s, k);
    check_shape(s, k.shape, shot_path, true);
    if (!k.keys.empty()) {
        const char* clash = s.node("velocity") ? "velocity" : s.node("position") ? "position" : nullptr;
        if (clash)
            s.fail(s.node("keys"), fmt::format("{} and {} are both given", s.key_name("keys"), s.key_name(clash)),
                   "keep one: keys for a path, or position and velocity for constant motion");
        k.pose.position = k.keys.front().position;  // the pose at t = 0 (held before the first key)
    }
    s.finish();
}

void read_projectile(TomlSection& s, ProjectileSettings& p, const std::string& shot_path) {
    read_entry(projectile_settings(), s, p);
    check_shape(s, p.shape, shot_path, true);
    s.finish();
}

// [[object.driven]]: a piece the scene moves (kinematic) or holds (fixed = true).
void read_drive(TomlSection& s, PieceDriveSettings& d, const std::string&) {
    read_entry(driven_settings(), s, d);
    const bool moving = s.node("velocity");
    if (!d.keys.empty() && moving)
        s.fail(s.node("keys"), fmt::format("{} and {} are both given", s.key_name("keys"), s.key_name("velocity")),
               "keep one: keys (offsets from the start at times) or a constant velocity");
    if (d.fixed && (moving || !d.keys.empty()))
        s.fail(s.node("fixed"), s.key_name("fixed") + " = true with a motion", "a fixed piece does not move: drop the motion");
    s.finish();
}

// An array of tables ([[scene.colliders]]), each entry read as its own section.
template <class T, class Read>
void read_table_array(TomlSection& s, const char* key, const std::string& shot_path, std::vector<T>& out, Read read) {
    const toml::node* n = s.node(key);
    if (!n) return;
    const toml::array* a = n->as_array();
    const std::string name = s.key_name(key);
    if (!a || (!a->empty() && !a->is_array_of_tables()))
        s.fail(n, fmt::format("{} must be an array of tables, each written [[{}]]", name, name), "see docs/shot.md");
    out.clear();
    for (size_t i = 0; i < a->size(); ++i) {
        TomlSection entry(*a->get(i)->as_table(), shot_path, fmt::format("{}[{}]", name, i));
        out.emplace_back();
        read(entry, out.back(), shot_path);
    }
}

}  // namespace

bool read_numbers(TomlSection& s, const char* key, double* out, size_t n, const Limits& limits, const char* example) {
    return numbers(s, key, out, n, limits, example);
}

void read_scene_arrays(TomlSection& s, SceneSettings& scene, const std::string& shot_path) {
    read_table_array(s, "colliders", shot_path, scene.colliders, read_collider);
    read_table_array(s, "kinematic", shot_path, scene.kinematic, read_kinematic);
    read_table_array(s, "projectile", shot_path, scene.projectiles, read_projectile);
}

void read_object_driven(TomlSection& s, ObjectSettings& object) {
    read_table_array(s, "driven", "", object.driven, read_drive);
}

}  // namespace shatter
