// Scene, object, material and simulate settings: the rotation and kinematic-motion helpers, the
// canonical JSON written into the trajectory's settings, and its exact inverse for the scene.
// The JSON uses the shot file's key names (docs/shot.md), so a reader can compare the two.
#include "core/scene_settings.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "core/error.h"
#include "core/setting_table.h"
#include "core/shot_sections.h"

namespace shatter {

using ojson = nlohmann::ordered_json;

Mat3 rotation_matrix(const Vec3& rotation_deg) {
    const Vec3 r = rotation_deg * (M_PI / 180.0);
    const Mat3 rx = Eigen::AngleAxisd(r.x(), Vec3::UnitX()).toRotationMatrix();
    const Mat3 ry = Eigen::AngleAxisd(r.y(), Vec3::UnitY()).toRotationMatrix();
    const Mat3 rz = Eigen::AngleAxisd(r.z(), Vec3::UnitZ()).toRotationMatrix();
    return rz * ry * rx;  // X first, then Y, then Z
}

namespace {

Vec3 interpolate_keys(const std::vector<KeyFrame>& keys, double t) {
    if (t <= keys.front().time) return keys.front().position;
    if (t >= keys.back().time) return keys.back().position;
    auto after = std::upper_bound(keys.begin(), keys.end(), t,
                                  [](double time, const KeyFrame& k) { return time < k.time; });
    auto before = after - 1;
    const double span = after->time - before->time;
    const double u = span > 0 ? (t - before->time) / span : 1.0;
    return before->position + u * (after->position - before->position);
}

}  // namespace

Vec3 drive_offset(const PieceDriveSettings& d, double t) {
    if (d.fixed) return Vec3::Zero();
    if (d.keys.empty()) return d.velocity * t;
    return interpolate_keys(d.keys, t);  // the shot reader demands increasing times
}

Vec3 kinematic_position(const KinematicSettings& k, double t) {
    if (k.keys.empty()) return k.pose.position + k.velocity * t;
    auto by_time = [](const KeyFrame& a, const KeyFrame& b) { return a.time < b.time; };
    if (std::is_sorted(k.keys.begin(), k.keys.end(), by_time)) return interpolate_keys(k.keys, t);
    std::vector<KeyFrame> sorted = k.keys;
    std::stable_sort(sorted.begin(), sorted.end(), by_time);
    return interpolate_keys(sorted, t);
}

const char* to_string(ShapeKind k) {
    switch (k) {
        case ShapeKind::Box: return "box";
        case ShapeKind::Sphere: return "sphere";
        case ShapeKind::Plane: return "plane";
        case ShapeKind::Mesh: return "mesh";
    }
    return "?";
}

const char* to_string(EnergySplitMode m) {
    switch (m) {
        case EnergySplitMode::Total: return "total";
        case EnergySplitMode::PerBody: return "per_body";
    }
    return "?";
}

const char* to_string(KickDirectionMode m) {
    switch (m) {
        case KickDirectionMode::Paper: return "paper";
        case KickDirectionMode::Opposed: return "opposed";
        case KickDirectionMode::Force: return "force";
    }
    return "?";
}

const char* to_string(EnergizeMethod m) {
    switch (m) {
        case EnergizeMethod::Exact: return "exact";
        case EnergizeMethod::Paper: return "paper";
    }
    return "?";
}

void apply_energize_method(EnergizeMethod m, SimulateSettings& s) {
    s.method = m;
    const bool paper = m == EnergizeMethod::Paper;
    s.energy_split = paper ? EnergySplitMode::PerBody : EnergySplitMode::Total;
    s.directions = paper ? KickDirectionMode::Paper : KickDirectionMode::Opposed;
    s.exact_energy = !paper;
}

const char* to_string(BreakCriterion c) {
    switch (c) {
        case BreakCriterion::Force: return "force";
        case BreakCriterion::BulletImpulse: return "bullet_impulse";
    }
    return "?";
}

const char* to_string(InstabilityMode m) {
    switch (m) {
        case InstabilityMode::Stop: return "stop";
        case InstabilityMode::Clamp: return "clamp";
    }
    return "?";
}

// ---- to_json ---------------------------------------------------------------------------------

namespace {

ojson vec_json(const Vec3& v) { return ojson::array({v.x(), v.y(), v.z()}); }

// A float as the shortest decimal that reads back as the same float (0.6f is written 0.6).
double short_float(float f) {
    const std::string text = fmt::format("{}", f);
    double d = f;
    std::from_chars(text.data(), text.data() + text.size(), d);
    return d;
}

ojson keys_json(const std::vector<KeyFrame>& keys) {
    ojson out = ojson::array();
    for (const KeyFrame& f : keys) out.push_back({f.time, f.position.x(), f.position.y(), f.position.z()});
    return out;
}

ojson colour_json(const std::array<float, 3>& c) {
    return ojson::array({short_float(c[0]), short_float(c[1]), short_float(c[2])});
}

void put_shape(ojson& j, const ShapeSettings& s) {
    j["shape"] = to_string(s.kind);
    j["size"] = vec_json(s.size);
    j["radius"] = s.radius;
    j["mesh"] = s.mesh;
    j["mesh_scale"] = s.mesh_scale;
}

void put_pose(ojson& j, const Pose& p) {
    j["position"] = vec_json(p.position);
    j["rotation"] = vec_json(p.rotation_deg);
}

void put_surface(ojson& j, const SurfaceSettings& s) {
    j["friction"] = s.friction;
    j["restitution"] = s.restitution;
}

ojson collider_json(const ColliderSettings& c) {
    ojson j = ojson::object();
    j["name"] = c.name;
    put_shape(j, c.shape);
    put_pose(j, c.pose);
    put_surface(j, c.surface);
    j["colour"] = colour_json(c.colour);
    return j;
}

ojson kinematic_json(const KinematicSettings& k) {
    ojson j = ojson::object();
    j["name"] = k.name;
    put_shape(j, k.shape);
    put_pose(j, k.pose);
    j["velocity"] = vec_json(k.velocity);
    j["keys"] = keys_json(k.keys);
    put_surface(j, k.surface);
    j["colour"] = colour_json(k.colour);
    return j;
}

}  // namespace

void put_scene_arrays(const SceneSettings& s, ojson& j) {
    j["colliders"] = ojson::array();
    for (const ColliderSettings& c : s.colliders) j["colliders"].push_back(collider_json(c));
    j["kinematic"] = ojson::array();
    for (const KinematicSettings& k : s.kinematic) j["kinematic"].push_back(kinematic_json(k));
}

void put_object_driven(const ObjectSettings& s, ojson& j) {
    ojson driven = ojson::array();
    for (const PieceDriveSettings& d : s.driven)
        driven.push_back({{"piece", d.piece}, {"fixed", d.fixed}, {"velocity", vec_json(d.velocity)}, {"keys", keys_json(d.keys)}});
    j["driven"] = std::move(driven);
}

// The sections' keys come from their tables (core/setting_table_scene.cpp), in the order files
// already written have them.
ojson to_json(const SceneSettings& s) {
    Shot shot;
    shot.scene = s;
    return settings_json("scene", shot);
}

ojson to_json(const ObjectSettings& s) {
    Shot shot;
    shot.object = s;
    return settings_json("object", shot);
}

ojson to_json(const MaterialSettings& s) {
    Shot shot;
    shot.material = s;
    return settings_json("material", shot);
}

ojson to_json(const SimulateSettings& s) {
    Shot shot;
    shot.simulate = s;
    return settings_json("simulate", shot);
}

// ---- scene_from_json ---------------------------------------------------------------------------

namespace {

// One JSON object read strictly: every key must be present and of its type, and no other key
// may be there. `path` names the object in messages ("scene.colliders[1]").
class JsonObject {
public:
    JsonObject(const nlohmann::json& j, const std::string& source, std::string path)
        : j_(j), source_(source), path_(std::move(path)) {
        if (!j_.is_object()) fail(path_, "is not a JSON object");
    }

    const nlohmann::json& at(const char* key) {
        used_.insert(key);
        auto it = j_.find(key);
        if (it == j_.end()) fail(name(key), "is missing");
        return *it;
    }
    double number(const char* key) { return number_value(at(key), name(key)); }
    bool boolean(const char* key) {
        const auto& v = at(key);
        if (!v.is_boolean()) fail(name(key), "must be true or false");
        return v.get<bool>();
    }
    std::string text(const char* key) {
        const auto& v = at(key);
        if (!v.is_string()) fail(name(key), "must be a string");
        return v.get<std::string>();
    }
    Vec3 vec3(const char* key) {
        const auto& v = at(key);
        if (!v.is_array() || v.size() != 3) fail(name(key), "must be an array of 3 numbers");
        return Vec3(number_value(v[0], name(key)), number_value(v[1], name(key)), number_value(v[2], name(key)));
    }
    std::array<float, 3> colour(const char* key) {
        Vec3 c = vec3(key);
        return {static_cast<float>(c.x()), static_cast<float>(c.y()), static_cast<float>(c.z())};
    }
    const nlohmann::json& array(const char* key) {
        const auto& v = at(key);
        if (!v.is_array()) fail(name(key), "must be an array");
        return v;
    }
    void finish() const {
        for (auto it = j_.begin(); it != j_.end(); ++it)
            if (!used_.count(it.key())) fail(name(it.key().c_str()), "is not a known setting");
    }

    std::string name(const char* key) const { return path_ + "." + key; }
    [[noreturn]] void fail(const std::string& what, const std::string& problem) const {
        throw_input_error(source_, "settings JSON: " + what + " " + problem,
                          "make the file again with this version of shatter");
    }
    double number_value(const nlohmann::json& v, const std::string& what) const {
        if (!v.is_number()) fail(what, "must be a number");
        const double d = v.get<double>();
        if (!std::isfinite(d)) fail(what, "is not a finite number");
        return d;
    }

private:
    const nlohmann::json& j_;
    const std::string& source_;
    std::string path_;
    std::set<std::string> used_;
};

ShapeKind shape_kind(JsonObject& o) {
    const std::string s = o.text("shape");
    for (ShapeKind k : {ShapeKind::Box, ShapeKind::Sphere, ShapeKind::Plane, ShapeKind::Mesh})
        if (s == to_string(k)) return k;
    o.fail(o.name("shape"), "= \"" + s + "\" is not box, sphere, plane or mesh");
}

void get_common(JsonObject& o, ShapeSettings& shape, Pose& pose, SurfaceSettings& surface) {
    shape.kind = shape_kind(o);
    shape.size = o.vec3("size");
    shape.radius = o.number("radius");
    shape.mesh = o.text("mesh");
    shape.mesh_scale = o.number("mesh_scale");
    pose.position = o.vec3("position");
    pose.rotation_deg = o.vec3("rotation");
    surface.friction = o.number("friction");
    surface.restitution = o.number("restitution");
}

ColliderSettings collider_from_json(const nlohmann::json& j, const std::string& source, const std::string& path) {
    JsonObject o(j, source, path);
    ColliderSettings c;
    c.name = o.text("name");
    get_common(o, c.shape, c.pose, c.surface);
    c.colour = o.colour("colour");
    o.finish();
    return c;
}

KeyFrame key_from_json(const JsonObject& o, const nlohmann::json& k, const std::string& what) {
    if (!k.is_array() || k.size() != 4) o.fail(what, "must be an array [t, x, y, z]");
    KeyFrame f;
    f.time = o.number_value(k[0], what);
    for (int i = 0; i < 3; ++i) f.position[i] = o.number_value(k[i + 1], what);
    return f;
}

KinematicSettings kinematic_from_json(const nlohmann::json& j, const std::string& source, const std::string& path) {
    JsonObject o(j, source, path);
    KinematicSettings k;
    k.name = o.text("name");
    get_common(o, k.shape, k.pose, k.surface);
    if (k.shape.kind != ShapeKind::Box && k.shape.kind != ShapeKind::Sphere)
        o.fail(o.name("shape"), "must be box or sphere for a kinematic body");
    k.velocity = o.vec3("velocity");
    const nlohmann::json& keys = o.array("keys");
    for (size_t i = 0; i < keys.size(); ++i) {
        const std::string what = fmt::format("{}[{}]", o.name("keys"), i);
        k.keys.push_back(key_from_json(o, keys[i], what));
        if (i > 0 && !(k.keys[i].time > k.keys[i - 1].time)) o.fail(what, "has a time not after the key before it");
    }
    k.colour = o.colour("colour");
    o.finish();
    return k;
}

}  // namespace

SceneSettings scene_from_json(const nlohmann::json& j, const std::string& source) {
    JsonObject o(j, source, "scene");
    SceneSettings s;
    s.gravity = o.vec3("gravity");
    s.ground = o.boolean("ground");
    s.ground_height = o.number("ground_height");
    s.ground_surface.friction = o.number("ground_friction");
    s.ground_surface.restitution = o.number("ground_restitution");
    const nlohmann::json& colliders = o.array("colliders");
    for (size_t i = 0; i < colliders.size(); ++i)
        s.colliders.push_back(collider_from_json(colliders[i], source, fmt::format("scene.colliders[{}]", i)));
    const nlohmann::json& kinematic = o.array("kinematic");
    for (size_t i = 0; i < kinematic.size(); ++i)
        s.kinematic.push_back(kinematic_from_json(kinematic[i], source, fmt::format("scene.kinematic[{}]", i)));
    o.finish();
    return s;
}

}  // namespace shatter
