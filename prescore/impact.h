// The impact pre-pass: where the shot's object first hits something, before it is split.
//
// The object flies as one rigid body from the shot's pose with its initial velocity under
// gravity, without spin (an initial angular velocity is ignored, and noted), until its surface
// first touches another body of the scene: the ground, a static collider (plane, sphere, box), a
// kinematic body on its script or a projectile (which falls under the same gravity, so relative
// to the object it moves in a straight line), or a static mesh collider (its triangles).
//
// Every point of a body that does not spin moves by the same displacement, so the gap between
// the object and another body is the gap between the object at rest and the other body moved by
// their relative displacement e(t). The search is conservative advancement (Mirtich 1996): from
// t, step to the first time the relative displacement can have closed the current gap, until
// the gap is below a tolerance; exact for the plane and the sphere (their gaps are exact), and
// for a box whose gap is only a bound (its vertices against the object's surface) an overshoot
// is bisected back. A mesh collider's first contact is found in closed form instead: the first time
// a vertex of one surface, moving along the parabola, crosses a triangle of the other (both ways:
// the object's vertices against the mesh's triangles and the mesh's vertices against the object's),
// each a quadratic's root; edge-against-edge first contacts are found when a vertex follows, a
// bound like the box's. Each body's first contact is reported; the earliest that closes at some
// speed is the impact that grades the seeds (prescore/partition.h).
//
// Why here and not in simulate: stages meet only through files (docs/architecture.md), and
// prescore may not depend on simulate's Bullet adapter. A body that does not spin needs no
// solver: its flight is the analytic x0 + v t + g t^2 / 2.
#pragma once

#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/scene_settings.h"

namespace shatter {

struct Contact {
    std::string with;        // "ground", or the collider's, kinematic body's or projectile's name
    double time = 0;         // when it touches (unit: s)
    Vec3 point;              // where, in the world (unit: m)
    Vec3 model_point;        // the same point in the model's frame (unit: m)
    Vec3 normal;             // the other body's surface normal there, pointing at the object
    double speed = 0;        // relative speed of the object against the other body (unit: m/s)
    double normal_speed = 0; // its part along the normal, closing (unit: m/s)
};

struct Impact {
    std::vector<Contact> contacts;  // each body's first contact within the horizon, earliest first
    bool spin_ignored = false;      // the object had an angular velocity, which the flight leaves out
    size_t mesh_colliders_skipped = 0;
    // The contacts that grade the seeds: the first that closes at kMinImpactSpeed or more, and
    // those within kSimultaneous of it.
    std::vector<Contact> grading() const;
};

inline constexpr double kImpactHorizon = 10;      // (unit: s) contacts later than this are not looked for
inline constexpr double kMinImpactSpeed = 0.05;   // (unit: m/s) slower contacts (a resting object) do not grade
inline constexpr double kSimultaneous = 1e-3;     // (unit: s)
inline constexpr double kContactTolerance = 1e-4; // (unit: of the diagonal) a gap this small touches

// The first contacts of the object whose outer surface is `surface` (model frame, unit: m),
// placed and launched by `object` in `scene`. `tolerance` (unit: m) is the gap taken as contact.
// `collider_meshes` holds each of scene.colliders' triangles (its own frame, in metres; empty for
// other shapes); without it mesh colliders are skipped and counted.
Impact find_impact(const TriangleMesh& surface, const SceneSettings& scene, const ObjectSettings& object,
                   double tolerance, const std::vector<TriangleMesh>* collider_meshes = nullptr);

// Where the model frame's origin goes (object_translation on the surface's vertices).
Vec3 object_origin(const std::vector<Vec3>& vertices, const ObjectSettings& object);

}  // namespace shatter
