// Scene, object, material and simulate settings: the rotation, placement and kinematic-motion helpers, the
// canonical JSON written into the trajectory's settings, and its exact inverse for the scene,
// both by the setting tables (core/setting_table_scene.cpp, with the tables of the arrays'
// entries). The JSON uses the shot file's key names (docs/shot.md), so a reader can compare the two.
#include "core/scene_settings.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/model.h"
#include "core/setting_table.h"

namespace shatter {

using ojson = nlohmann::ordered_json;

Mat3 rotation_matrix(const Vec3& rotation_deg) {
    const Vec3 r = rotation_deg * (M_PI / 180.0);
    const Mat3 rx = Eigen::AngleAxisd(r.x(), Vec3::UnitX()).toRotationMatrix();
    const Mat3 ry = Eigen::AngleAxisd(r.y(), Vec3::UnitY()).toRotationMatrix();
    const Mat3 rz = Eigen::AngleAxisd(r.z(), Vec3::UnitZ()).toRotationMatrix();
    return rz * ry * rx;  // X first, then Y, then Z
}

Vec3 object_translation(const Model& model, const ObjectSettings& object) {
    if (object.place == Placement::Origin) return object.pose.position;
    const Mat3 r = rotation_matrix(object.pose.rotation_deg);
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
    for (const Piece& p : model.pieces)
        for (const Vec3& v : p.surface.vertices) {
            const Vec3 x = r * v;
            lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
        }
    if (!(lo.x() <= hi.x())) return object.pose.position;
    return object.pose.position - Vec3(0.5 * (lo.x() + hi.x()), lo.y(), 0.5 * (lo.z() + hi.z()));
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

double projectile_mass(const ProjectileSettings& p) {
    const double volume = p.shape.kind == ShapeKind::Sphere ? 4.0 / 3.0 * M_PI * std::pow(p.shape.radius, 3)
                                                            : p.shape.size.prod();
    return p.density * volume;
}

std::vector<KinematicSettings> scene_props(const SceneSettings& scene) {
    std::vector<KinematicSettings> props = scene.kinematic;
    for (const ProjectileSettings& p : scene.projectiles) {
        KinematicSettings k;
        k.name = p.name;
        k.shape = p.shape;
        k.pose = p.pose;
        k.surface = p.surface;
        k.colour = p.colour;
        props.push_back(k);
    }
    return props;
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
    s.kick_bodies = paper ? KickBodiesMode::Pieces : KickBodiesMode::Joined;
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

// The inverse, by the same tables: every key present with its type, and no other.
SceneSettings scene_from_json(const nlohmann::json& j, const std::string& source) {
    JsonObject o(j, source, "scene");
    Shot shot;
    read_settings_json("scene", o, shot);
    return shot.scene;
}

}  // namespace shatter
