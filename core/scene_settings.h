// Settings of the simulated scene, the fracturable object, its material and the simulation:
// the shot's [scene], [[scene.colliders]], [[scene.kinematic]], [object], [material] and
// [simulate] sections (docs/shot.md). Physical units throughout; nothing here changes meaning
// with the time step. The trajectory file carries these settings as JSON (to_json/from_json),
// so that render draws exactly the scene that was simulated.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/geometry.h"
#include "core/settings.h"

namespace shatter {

enum class ShapeKind { Box, Sphere, Plane, Mesh };

struct ShapeSettings {
    ShapeKind kind = ShapeKind::Box;
    Vec3 size = Vec3(1, 1, 1);  // box: full extents (unit: m)
    double radius = 0.5;        // sphere (unit: m)
    std::string mesh;           // mesh (static colliders only): file, relative to the shot's folder
    double mesh_scale = 1;      // mesh: metres per mesh unit (unit: m)
    // plane: the plane through the pose's position whose normal is the pose's rotation of +Y
};

struct Pose {
    Vec3 position = Vec3::Zero();      // (unit: m)
    Vec3 rotation_deg = Vec3::Zero();  // Euler angles applied X, then Y, then Z (unit: degrees)
};
Mat3 rotation_matrix(const Vec3& rotation_deg);

struct SurfaceSettings {
    double friction = 0.5;     // Coulomb friction coefficient (unit: 1)
    double restitution = 0.0;  // (unit: 1, 0 to 1)
};

struct ColliderSettings {  // static
    std::string name;
    ShapeSettings shape;
    Pose pose;
    SurfaceSettings surface;
    std::array<float, 3> colour = {0.6f, 0.6f, 0.6f};  // linear RGB for render
};

struct KeyFrame {
    double time = 0;               // (unit: s)
    Vec3 position = Vec3::Zero();  // (unit: m)
};

struct KinematicSettings {  // moved by script, pushes dynamic bodies, is not pushed
    std::string name;
    ShapeSettings shape;  // box or sphere
    Pose pose;            // at t = 0 (the rotation is kept)
    Vec3 velocity = Vec3::Zero();  // constant velocity when `keys` is empty (unit: m/s)
    std::vector<KeyFrame> keys;    // else positions at times, linear between, held after the last
    SurfaceSettings surface;
    std::array<float, 3> colour = {0.15f, 0.3f, 0.8f};
};
// The kinematic body's position at time t (unit: m).
Vec3 kinematic_position(const KinematicSettings& k, double t);

struct ProjectileSettings {  // thrown at the object: moved by gravity and contacts, not by script
    std::string name;
    ShapeSettings shape;           // box or sphere
    Pose pose;                     // at t = 0
    Vec3 velocity = Vec3::Zero();  // at t = 0 (unit: m/s)
    double density = 7800;         // (unit: kg/m^3) steel
    SurfaceSettings surface;
    std::array<float, 3> colour = {0.55f, 0.56f, 0.58f};
};
// A projectile's mass (unit: kg).
double projectile_mass(const ProjectileSettings& p);

struct SceneSettings {
    Vec3 gravity = Vec3(0, -9.81, 0);  // (unit: m/s^2)
    bool ground = true;                // an infinite ground plane y = ground_height
    double ground_height = 0;          // (unit: m)
    SurfaceSettings ground_surface{0.5, 0.1};
    std::vector<ColliderSettings> colliders;
    std::vector<KinematicSettings> kinematic;
    std::vector<ProjectileSettings> projectiles;
};
// The bodies a trajectory records after the pieces ("props"), in its order: the kinematic bodies,
// then the projectiles, each as its shape, name, colour and pose at t = 0 (what render and the
// .glb draw; a projectile's script is empty).
std::vector<KinematicSettings> scene_props(const SceneSettings& scene);

// A piece of the object that the scene moves instead of the solver (the chain's end cubes, an
// anchor): it is not pushed, takes no energizing impulse, and its constraints still break.
struct PieceDriveSettings {
    uint32_t piece = 0;
    bool fixed = false;            // true: never moves (static)
    Vec3 velocity = Vec3::Zero();  // constant velocity when `keys` is empty (unit: m/s)
    std::vector<KeyFrame> keys;    // else offsets from its start position at times (unit: s, m)
};

// Where the fracturable object starts: model coordinates x go to R x + position.
// What the object's `position` places: the model frame's origin, or the centre of the bottom of
// the object's bounding box (after its rotation): a mesh from elsewhere has its own origin.
enum class Placement { Origin, Base };

struct ObjectSettings {
    Pose pose;
    Placement place = Placement::Origin;
    Vec3 velocity = Vec3::Zero();          // initial linear velocity of every piece (unit: m/s)
    Vec3 angular_velocity = Vec3::Zero();  // initial angular velocity about the object's centre of mass (unit: rad/s)
    std::vector<PieceDriveSettings> driven;  // [[object.driven]]
};

struct Model;
// Where the model frame's origin goes: the object's position, or (place = "base") the position
// less the centre of the bottom of the rotated model's bounding box (its pieces' surfaces).
Vec3 object_translation(const Model& model, const ObjectSettings& object);
// The offset of a driven piece from its start position at time t (unit: m).
Vec3 drive_offset(const PieceDriveSettings& d, double t);

// Constraint properties per unit of the area a constraint stands for (prescore's area share):
// a constraint with area A has stiffness k = stiffness * A, damping c = damping * A and breaks
// when its force exceeds strength * A. With youngs_modulus E set (by the key or a preset), the
// stiffness is k = E A / l instead, l the distance between the centres of mass of the two pieces
// it joins (core/material_presets.h has the rule, docs/physics.md section 2 derives it).
//
// A preset (core/material_presets.h) is applied when the shot is read: it sets youngs_modulus,
// strength, density and the surface; the same table's other keys then override it, and so does a
// later layer (`--set` over the shot file; a flag). A key of the file under a preset given by
// `--set` is replaced by the preset (core/setting_table_scene.cpp).
struct MaterialSettings {
    std::string preset = "none";    // the preset the numbers came from ("none": no preset)
    std::optional<double> density;  // (unit: kg/m^3) default: the model's density
    std::optional<double> youngs_modulus;  // (unit: Pa) set: k = E A / l, and stiffness is unused
    double stiffness = 1e10;        // (unit: N/m per m^2 = N/m^3)
    double damping = 0;             // (unit: N s/m per m^2)
    double strength = 1e6;          // tensile strength (unit: Pa = N/m^2)
    double alpha = 1.0;             // fraction of stored energy given back at a break (unit: 1, >= 0)
    SurfaceSettings surface{0.5, 0.1};
    bool stiffen = false;           // raise a stiffness too soft for the step to the least that converges (false: refuse)
};
inline constexpr Limits kStiffnessLimits{1e-3, 1e18, "N/m^3"};
inline constexpr Limits kYoungsModulusLimits{1, 1e13, "Pa"};
inline constexpr Limits kDampingLimits{0, 1e15, "N s/m^3"};
inline constexpr Limits kStrengthLimits{0, 1e12, "Pa"};
inline constexpr Limits kAlphaLimits{0, 100, "(fraction of stored energy)"};
inline constexpr Limits kFrictionLimits{0, 10, ""};
inline constexpr Limits kRestitutionLimits{0, 1, ""};

enum class EnergySplitMode { Total, PerBody };
enum class KickDirectionMode { Paper, Opposed, Force };
// What a break's kicks move: "pieces": the constraint's two pieces, as free bodies; "joined": the
// two pieces with everything still joined to them, as the joints allow
// (simulate/joined_response.h).
enum class KickBodiesMode { Pieces, Joined };
// The energizing method: a name for the four keys energy_split, directions, exact_energy and
// kick_bodies (docs/physics.md section 4). "exact" (the default): the pair gains exactly alpha E
// in its own frame, equal and opposite kicks, body a's along the paper's direction (momentum
// conserved; directions = "opposed"), passed through the joints (kick_bodies = "joined");
// "paper": the paper as written, alpha E per body with its magnitudes and its directions
// -(t x f), on the two pieces.
enum class EnergizeMethod { Exact, Paper };
// When a constraint is overloaded: "force": the norm of its force exceeds strength x area
// (docs/physics.md section 3); "bullet_impulse": Bullet's own per-row test, any world-axis row's
// impulse in a step reaches strength x area x h (btTypedConstraint::setBreakingImpulseThreshold),
// for comparison (docs/accuracy.md).
enum class BreakCriterion { Force, BulletImpulse };
// How the solver treats the joints (simulate/bullet_solver.h): "iterative": one row at a time, as
// Bullet's sequential impulses; "direct": all joint rows of a step solved at once (a sparse
// LDL^T) in every iteration, the contacts iterated around them; "auto": direct, at any piece count
// (simulate/simulate.h).
enum class JointSolve { Auto, Iterative, Direct };
// When the simulation goes unstable (a NaN or Inf, or kinetic energy beyond the energy budget,
// simulate/instability.h): "stop": end the run there, keep the frames before, mark the trajectory
// incomplete (exit code 5); "clamp": scale the pieces' velocities down to the budget and go on,
// counting each clamp (a NaN still stops: there is nothing to clamp).
enum class InstabilityMode { Stop, Clamp };

struct SimulateSettings {
    double duration = 4.0;      // (unit: s)
    // duration = "auto": simulate until every piece has been at rest for a short hold
    // (simulate/simulate.h: kRestSpeed, kRestHold), at most max_duration; `duration` is then unused.
    bool auto_duration = false;
    double max_duration = 10;   // the cap of duration = "auto" (unit: s)
    double fps = 30;            // frames recorded per second (unit: 1/s)
    uint32_t substeps = 8;      // solver steps per frame: h = 1 / (fps * substeps)
    // substeps = "auto": the step chosen as the run goes (simulate/simulate.h, "The automatic
    // step"); `substeps` is then unused. Every shot's default (Shot, core/shot.h); a
    // SimulationInput built in code keeps the fixed step it names.
    bool auto_substeps = false;
    uint32_t iterations = 20;   // sequential-impulse iterations per step
    JointSolve joints = JointSolve::Auto;  // "auto", "iterative" or "direct" (simulate/bullet_solver.h)
    EnergizeMethod method = EnergizeMethod::Exact;  // sets the next three and kick_bodies (apply_energize_method)
    EnergySplitMode energy_split = EnergySplitMode::Total;  // "total": two bodies at rest gain alpha E; "per_body": each alpha E
    // "paper": -(t x f) per body; "opposed": momentum-conserving; "force": along the load, never
    // into the partner (momentum-conserving)
    KickDirectionMode directions = KickDirectionMode::Opposed;
    KickBodiesMode kick_bodies = KickBodiesMode::Joined;  // "pieces" or "joined"
    double rate_limit = 0;      // least time between two breaks of the object; 0: off (unit: s)
    bool rollback = false;      // re-run a step whose breaks were found, without the broken constraints
    bool exact_energy = true;   // impulse magnitudes solved for the bodies' motion: the gained kinetic energy is exactly alpha E
    uint64_t seed = 1;          // seed of the random kick directions
    double max_cfm = 0.5;       // refuse settings whose constraints would need a larger CFM (unit: 1)
    BreakCriterion break_criterion = BreakCriterion::Force;  // "force" (norm) or "bullet_impulse" (per row)
    InstabilityMode on_instability = InstabilityMode::Stop;  // "stop" or "clamp" (simulate/instability.h)
    // An object that starts without spin and touching nothing falls as one rigid body, its joints
    // unsolved, until something comes within contact reach (simulate/bullet_world.h, rigid flight).
    bool rigid_flight = true;
    // Pieces at rest sleep (neither solved nor moved) until something touches them
    // (simulate/simulate.h, kSleepSpeed; simulate/bullet_world.h, kSleepTime).
    bool sleep = true;
};
// Sets `method` and the four keys it names.
void apply_energize_method(EnergizeMethod m, SimulateSettings& s);
inline constexpr Limits kDurationLimits{1e-3, 3600, "s"};
inline constexpr Limits kFpsLimits{1, 1000, "frames/s"};
inline constexpr Limits kSubstepsLimits{1, 10000, "steps per frame"};
inline constexpr Limits kIterationsLimits{1, 10000, "iterations"};
inline constexpr Limits kRateLimitLimits{0, 3600, "s"};
inline constexpr Limits kMaxCfmLimits{1e-6, 0.99, ""};

nlohmann::ordered_json to_json(const SceneSettings& s);
nlohmann::ordered_json to_json(const ObjectSettings& s);
nlohmann::ordered_json to_json(const MaterialSettings& s);
nlohmann::ordered_json to_json(const SimulateSettings& s);
// Inverse of to_json(SceneSettings); throws Error(BadInput) naming `source` on a malformed value.
SceneSettings scene_from_json(const nlohmann::json& j, const std::string& source);

const char* to_string(ShapeKind k);
const char* to_string(EnergySplitMode m);
const char* to_string(KickDirectionMode m);
const char* to_string(EnergizeMethod m);
const char* to_string(BreakCriterion c);
const char* to_string(InstabilityMode m);

}  // namespace shatter
