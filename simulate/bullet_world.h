// The Bullet adapter: builds a btDiscreteDynamicsWorld (double precision) from a model and the
// scene, steps it one solver step at a time, and exposes what breaking, energizing and recording
// need. The physics decisions live in the engine-free files (spring.h, energized_fracture.h,
// break_policy.h); this file only translates.
//
// Bodies: each piece is a rigid body whose frame is its principal frame at its centre of mass,
// shaped as a compound of its convex collision parts (shrunk by the collision margin, so that
// hull + margin is the part itself). Driven pieces ([[object.driven]]) are kinematic (or
// static); props are the kinematic boxes and spheres ([[scene.kinematic]]) and then the
// projectiles ([[scene.projectile]], dynamic boxes and spheres of their own mass, in the energy
// books beside the pieces); colliders and the ground are static.
// Joined pieces never collide with each other: every constraint is added with Bullet's
// "disable collisions between linked bodies", so two pieces that touch along a fracture face do
// not push each other apart at rest (the classic frame-one explosion); when the last constraint
// between them breaks it is removed from the world and they collide again from the next step.
// Pieces that overlap at the start without being joined (touching along an edge; convex parts
// reaching into a neighbour) ignore each other until their bounding boxes part.
// Sleeping (WorldSetup::sleep_speed): Bullet's islands (pieces joined to each other or touching
// each other, with what moves them) fall asleep together once every body in them has moved slower
// than its thresholds for kSleepTime: they are then neither solved nor moved, their contacts are
// not looked for, and their joints keep the force of their last solve, under which they did not
// break; the joints of a sleeping island are left out of every load, frequency and residual the
// world reports. A body that comes to touch a sleeping island wakes all of it, and so does a
// break's kick on any of its pieces. A piece joined to
// a driven piece never sleeps (its joint is loaded by a script, not by contact), and neither does
// anything joined to it.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "core/model.h"
#include "core/scene_settings.h"
#include "core/trajectory.h"
#include "simulate/deep_contact.h"
#include "simulate/energized_fracture.h"
#include "simulate/joined_response.h"

namespace shatter {

struct WorldSetup {
    SceneSettings scene;
    ObjectSettings object;
    MaterialSettings material;
    double h = 1.0 / 240;   // solver step (unit: s)
    uint32_t iterations = 20;
    // Bullet's own breaking: each constraint gets the impulse threshold strength x h, which the
    // solver checks per world-axis row and then disables the constraint (bullet_disabled).
    bool bullet_breaking = false;
    // Joint convergence (simulate/bullet_solver.h): more iterations, up to max_iterations, until
    // every joint's force is within converge_tolerance of its strength from its spring law;
    // 0: off (exactly `iterations`).
    double converge_tolerance = 0;
    uint32_t max_iterations = 0;
    // Direct joints (simulate/bullet_solver.h): every iteration solves all joint rows at once;
    // contacts' pushes move joined pieces together (PieceSolver::push_joints), and unless
    // converge_tolerance says otherwise the step iterates until the joints' forces are within
    // kDirectTolerance of their strength, at most kDirectIterationCap x iterations.
    bool direct_joints = false;
    // Rigid flight: an object whose dynamic pieces all move alike (no spin, none driven) and that
    // touches nothing moves as one body, its joints unsolved, until anything comes within
    // contact reach (BulletWorld::flying). In free fall every piece accelerates alike and no joint
    // is loaded, so the solve would give each piece the same motion; its cost (a 1,000-piece
    // bunny's 31,000 joints, every step of its fall) is skipped.
    bool rigid_flight = true;
    // Sleeping (above): a body sleeps below this speed of its centre, and this speed over its
    // radius of turn (its piece's radius; a projectile's shape's). 0: nothing sleeps (unit: m/s).
    double sleep_speed = 0;
    // Threads for the contact tests of pairs already in contact or near it (PieceDispatcher::
    // workers); 0: default_threads() (core/workers.h). The result is the same for any number.
    unsigned threads = 0;
};

// How long every body of an island must stay below its sleeping thresholds before the island
// sleeps (unit: s). Bullet's own is 2 s, longer than most shots' rest; Box2D and Jolt use 0.5 s.
inline constexpr double kSleepTime = 0.25;

// The iterations of a step stop once no row changes a relative velocity by more than this: a
// pass that changes nothing (unit: m/s; at 1e-6 the stiffness identity's 2,000 iterations stopped
// 7.5e-5 short of k, at 1e-10 1.8e-8).
inline constexpr double kSettledSpeed = 1e-10;
// Direct joints' convergence: 1% of the strength, a fifth of what the residual check allows
// (simulate/simulate.h kResidualTolerance); ten times the step's iterations at most (measured:
// docs/physics.md section 5b).
inline constexpr double kDirectTolerance = 0.01;
inline constexpr double kDirectIterationCap = 10;

class BulletWorld {
public:
    BulletWorld(const Model& model, const WorldSetup& setup);
    ~BulletWorld();
    BulletWorld(const BulletWorld&) = delete;
    BulletWorld& operator=(const BulletWorld&) = delete;

    // One solver step of h; scripted bodies move to their place at the step's end.
    void step();
    double time() const { return time_; }
    // The most solver iterations a batch of islands took in the last step.
    int last_step_iterations() const;
    double h() const { return setup_.h; }
    // Rigid flight (WorldSetup::rigid_flight): the dynamic pieces still move as one body, Bullet
    // leaving them out, their joints unsolved and their feedback zero. It ends, for good, at the
    // start of the first step in which any piece's contact box (its bounding box grown by its
    // contact breaking threshold, as the broadphase has it), swept over the step's motion, reaches
    // another body's (a plane: its half-space), and whenever velocities are changed from outside.
    // flight_end(): when it ended (unit: s; 0 if it never began, the time still flying otherwise).
    bool flying() const;
    double flight_end() const;
    // The tolerance the joints' solve iterates to, of each joint's strength: converge_tolerance,
    // or kDirectTolerance for direct joints without it; 0: the step's own iterations only. Two
    // solves of a joint at rest can differ by twice this.
    double joint_tolerance() const;
    // Changes the solver step for the steps that follow (`[simulate] substeps = "auto"`): the
    // joints' ERP and CFM and Bullet's breaking thresholds follow it.
    void set_step(double h);
    // The largest load of an active joint that is awake: |force| / strength from the last step's
    // feedback (0 when none is).
    double max_load() const;
    // Whether the joint's pieces are awake (not in a sleeping island; see Sleeping above); and how
    // many dynamic pieces sleep.
    bool awake(size_t c) const;
    uint32_t sleeping_pieces() const;
    // Contact tests run so far on the worker threads beside the step (WorldSetup::threads); 0
    // with one thread.
    uint64_t parallel_contact_tests() const;
    // The load an impact that has begun would bring on the joints: contacts are found for the
    // bodies as they are now (Bullet finds them at the start of a step), and every penetrating
    // contact point of a piece with active joints awake whose bodies approach at v along the normal
    // counts v sqrt(k / w) / strength for the stiffest of that piece's joints, the peak force a
    // sudden stop of one side of a joint brings (docs/physics.md section 7). 0 without such.
    double approach_load();
    // Whether a dynamic piece touches something that is not a piece (the ground, a collider, a
    // kinematic body or a projectile) in the last step's contacts.
    bool touches_scene() const;
    // A joint's natural frequency along its stiffest row, omega = sqrt(k w), w the row's inverse
    // effective mass with the bodies as they are now (0 when it is not active; unit: rad/s).
    double joint_frequency(size_t c) const;
    // Over the active joints awake, the largest natural frequency omega = sqrt(k w) (w the largest row
    // inverse effective mass: the stiffest row) and the smallest (the softest row, which sets the
    // largest CFM); both 0 when none is active (unit: rad/s).
    void joint_frequencies(double* highest, double* lowest) const;

    // State of every body (its sleep too), for rollback.
    struct Snapshot;
    // How suddenly the last step moved what a joint holds: the largest change, from `before` to
    // now, of either of its bodies' velocity at its pivot (unit: m/s), times sqrt(k / w) for its
    // softest row (w that row's inverse effective mass): the peak force a jump of that size
    // brings on the joint's spring (docs/physics.md section 7; unit: N). A load that a step moves
    // between balanced joints (a chain pulled slowly) changes their forces, not their bodies'
    // velocities.
    double velocity_jump_force(size_t c, const Snapshot& before) const;
    std::shared_ptr<Snapshot> save() const;
    void restore(const Snapshot& s);
    // Sets every contact point's remembered impulses to zero: after a restore, the solver would
    // otherwise start (warm start) from impulses of a step that was undone.
    void forget_contact_impulses();

    // Constraints, in model order.
    size_t constraint_count() const;
    bool active(size_t c) const;
    double stiffness(size_t c) const;   // (unit: N/m)
    double strength(size_t c) const;    // break force (unit: N)
    Vec3 force_on_a(size_t c) const;    // the last step's solve's (unit: N)
    Vec3 load_on_a(size_t c) const;     // and with its push's load, what its stretch holds (unit: N)
    double max_cfm(size_t c) const;     // largest row CFM of the last step
    double current_max_cfm(size_t c, double* min_row_inverse_mass) const;  // the same from the bodies as they are now
    uint32_t piece_a(size_t c) const;
    uint32_t piece_b(size_t c) const;
    // Bullet disabled it in the last step (its own per-row threshold, WorldSetup::bullet_breaking).
    bool bullet_disabled(size_t c) const;
    // Enables it again (a Bullet break the break policy did not pick).
    void enable(size_t c);
    // A joint's spring as the bodies show it after a step: the stretch d = (pivot on B) - (pivot
    // on A), its rate d' (the pivots' relative velocity), and the force on A the solver applied in
    // that step (world frame).
    struct JointStretch {
        Vec3 stretch = Vec3::Zero();     // (unit: m)
        Vec3 rate = Vec3::Zero();        // (unit: m/s)
        Vec3 force_on_a = Vec3::Zero();  // (unit: N)
    };
    JointStretch joint_stretch(size_t c) const;
    // How far the last solve is from the joint's spring law: |f_A - (k d + c d')| / strength, the
    // force the solver applied against the force the stretch asks for, relative to the joint's
    // strength (docs/physics.md, "Joint convergence"). 0 for a joint that is not active.
    double joint_residual(size_t c) const;
    // The largest joint_residual over the active joints awake, and which (-1 when there is none).
    double max_joint_residual(int64_t* worst) const;
    // The last step's deepest contact for the size of the piece in it: how far a dynamic piece was
    // inside what it touches (the depth of the deepest point of its contacts, as the step's
    // collision detection found them) over its radius (piece_radius). A piece that moves further
    // in a step than its own size (a small piece at an impact's speed) may end inside the ground
    // or another piece, where the contacts no longer push it out.
    DeepContact last_step_deepest_contact() const;
    // Removes it from the world (its pieces may collide again when no other constraint joins them).
    void remove_constraint(size_t c);
    // The two bodies at the constraint's pivot (its mid-point), for energize().
    std::array<BodyAtPivot, 2> bodies_at_pivot(size_t c, Vec3* pivot) const;
    // Applies the impulses (N s) of a break at the world point to the constraint's two pieces.
    void apply_kicks(size_t c, const Vec3& pivot, const BreakKicks& kicks);

    // The fragments the active joints make now: the pieces joined to each other through them
    // (driven pieces included), each fragment's pieces ascending. Found once for all the breaks of
    // a step, after its removals: a break's side past the search's limit is taken from here.
    struct Fragments {
        std::vector<uint32_t> of;      // per piece: its fragment
        std::vector<uint32_t> first;   // per fragment, and one past the last: where its pieces start
        std::vector<uint32_t> pieces;  // fragment by fragment, ascending within each
        size_t size(uint32_t f) const { return first[f + 1] - first[f]; }
    };
    void fragments(Fragments* out) const;
    // What a break's kicks act through (simulate/joined_response.h): the pieces joined, through
    // the active joints, to either piece of a constraint that has left the world, and the active
    // joints among them. `parted`: the two pieces are no longer joined (side 1 holds piece_b's).
    struct JoinedPieces {
        // piece_a's side first; a side within the limit in the order the search reached it, a
        // larger one ascending (its fragment's list).
        std::vector<uint32_t> pieces;
        // Ascending: the joints among a side within the limit (a larger side moves as one rigid
        // body, breaking.h).
        std::vector<uint32_t> joints;
        size_t side_b = 0;             // pieces[side_b..] are piece_b's side (none when not parted)
        bool parted = false;
        // Not parted, and more than `limit` pieces joined (pieces and joints left empty).
        bool held = false;
    };
    // `fragments`: as fragments() gives them after the step's removals.
    void joined_pieces(size_t c, size_t limit, const Fragments& fragments, JoinedPieces* out) const;
    // The bodies (in the order of `joined.pieces`) and joints as joined_response() takes them,
    // and the bodies' velocities.
    void joined_bodies(const JoinedPieces& joined, std::vector<JoinedBody>* bodies, std::vector<JoinedJoint>* joints,
                       std::vector<VelocityChange>* velocities) const;
    // Adds dv[i] to the velocities of piece pieces[i].
    void add_velocities(const std::vector<uint32_t>& pieces, const std::vector<VelocityChange>& dv);
    // The frame a break's kicks on these pieces are counted in (unit: m/s): the velocity of their
    // centre of mass, or zero when one of them is static or kinematic (or none is given): a body of
    // infinite mass is at rest in the frame where momentum is counted, as pair_frame_velocity takes
    // it (docs/physics.md section 4).
    Vec3 frame_velocity(const std::vector<uint32_t>& pieces) const;
    // The kinetic energy of the given pieces' dynamic ones in a frame moving at velocity `frame`
    // and in the world's (unit: J). `inertia` holds each dynamic piece's inertia tensor in the
    // world frame, in order: worked out when empty, else taken from there (for the same poses: a
    // kick changes velocities only).
    void kinetic_energies_of(const std::vector<uint32_t>& pieces, const Vec3& frame, double* in_frame,
                             double* in_world, std::vector<Mat3>* inertia) const;

    // Energy books over the dynamic pieces and the projectiles (driven pieces and kinematic bodies
    // are scripted, not counted).
    double kinetic_energy() const;    // (unit: J)
    double potential_energy() const;  // -sum m g.x (unit: J)
    double stored_energy() const;     // sum over active constraints of |f|^2 / 2k (unit: J)
    // The same read from the poses: sum over active constraints of k |d|^2 / 2, d the stretch
    // (joint_stretch). Equal to stored_energy() when every joint's force matches its stretch.
    double elastic_energy() const;    // (unit: J)
    // Where the steps so far sent energy besides the pieces' motion, height and joints' stretch,
    // from each force's impulse on the mean of its bodies' velocities before and after the step
    // (the kinetic energy an impulse P adds to a body is exactly P . (v0 + v1) / 2):
    struct StepWork {
        // Taken from the pieces' motion by the joints and not stored in their stretch: their
        // damping and the implicit step's (a stiff joint at omega h >> 1 relaxes without ringing).
        double joints = 0;    // (unit: J)
        // Taken by contacts: friction and inelastic impacts, less the potential energy their
        // pushes out of penetration gave (unit: J).
        double contacts = 0;
        // Given to the dynamic pieces by driven pieces and kinematic bodies, through joints and
        // contacts (unit: J).
        double driven = 0;
        // What the time step's integration takes from kinetic + potential energy (unit: J). Of
        // gravity: a step moves a body by h v1 (symplectic Euler), so its potential energy changes
        // by -m g . h v1 while gravity's work on its motion is m g . h (v0 + v1) / 2 less the
        // impulses' share; the difference is m h g . (v1 - v0) / 2 (in free fall m |g|^2 h^2 / 2 a
        // step; at an impact, m h g . dv / 2 for the impact's change of velocity; nothing in rigid
        // flight, which moves the pieces by h (v0 + v1) / 2, on the parabola). Of the turn: a
        // body's kinetic energy is w . I w / 2 with its inertia I in the world frame, which turns
        // with it, and Bullet's implicit gyroscopic term changes w by dw_g within the step: the
        // energy changes by w1 . (I1 - I0) w1 / 2 + wm . I0 dw_g that no impulse accounts for
        // (wm the mean of w0 and w1).
        double integration = 0;
    };
    StepWork step_work() const;
    Vec3 linear_momentum() const;     // (unit: kg m/s)
    Vec3 angular_momentum() const;    // about the world origin (unit: kg m^2/s)
    bool finite() const;              // every body's position and velocity finite
    // Multiplies every dynamic piece's linear and angular velocity by `factor` (on_instability = clamp).
    void scale_piece_velocities(double factor);

    // Poses as the trajectory stores them.
    BodyPose piece_pose(uint32_t piece) const;
    BodyPose prop_pose(uint32_t prop) const;
    Vec3 piece_velocity(uint32_t piece) const;
    Vec3 piece_angular_velocity(uint32_t piece) const;  // (unit: rad/s)
    Vec3 piece_position(uint32_t piece) const;  // centre of mass, world (unit: m)
    uint32_t pieces() const;
    uint32_t props() const;
    bool piece_dynamic(uint32_t piece) const;

private:
    void build_pieces(const Model& model);
    void build_joints(const Model& model);
    void ignore_initial_overlaps();
    void allow_sleep(const Model& model);  // WorldSetup::sleep_speed
    void release_parted_pairs();
    bool near_anything() const;  // rigid flight ends here: see flying()
    void end_flight();
    void fly();                  // one step of rigid flight
    struct Impl;
    std::unique_ptr<Impl> impl_;
    WorldSetup setup_;
    double time_ = 0;
};

}  // namespace shatter
