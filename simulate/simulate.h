// simulate: pieces become rigid bodies joined by compliant point constraints; overloaded
// constraints break, and the energy they stored comes back as kinetic energy (energized
// fracture). The public entry point of the stage.
//
// A run is a fixed list of stages (simulate.cpp, simulate()): choose the joint solve and the
// stiffness; record frame 0; then per frame its steps, each followed by the stepper's stages
// (stepper.h: save, step, measure, pick breaks, roll back or remove, energize) and the guard
// (instability.h); record the frame's poses and books; check for rest (rest_check.h).
// With substeps = "auto" the steps of a frame are blocks of at most 1/480 s, each run as one
// probe step or, when the probe's joints carry kAutoRefineLoad of their strength or more, as the
// fine steps the stiffest joint needs (auto_step.h; below, "The automatic step").
#pragma once

#include <string>
#include <vector>

#include "core/model.h"
#include "core/scene_settings.h"
#include "core/trajectory.h"
#include "simulate/deep_contact.h"
#include "simulate/energized_fracture.h"

namespace shatter {

struct SimulationInput {
    SceneSettings scene;
    ObjectSettings object;
    MaterialSettings material;
    SimulateSettings simulate;
    // Threads the step runs on (WorldSetup::threads; 0: default_threads(), core/workers.h):
    // never changes the result.
    unsigned threads = 0;
};

struct BreakRecord {
    double time = 0;  // (unit: s) end of the step in which it broke
    double step = 0;  // the length of that step (unit: s)
    uint32_t constraint = 0, piece_a = 0, piece_b = 0;
    Vec3 pivot = Vec3::Zero();  // (unit: m, world)
    Vec3 force = Vec3::Zero();  // on piece a (unit: N)
    double strength = 0;        // (unit: N)
    double stiffness = 0;       // (unit: N/m)
    double alpha = 0;
    BreakKicks kicks;           // stored energy E, directions, effective masses, impulses
    // Kinetic energy the impulses actually added, measured in the pair's frame (the velocity of the
    // two pieces' common centre of mass before the break; docs/physics.md section 4): alpha E with
    // exact_energy (unit: J).
    double injected_energy = 0;
    // What the impulses' net momentum dP added on top in the world's frame, dP . V: zero for
    // opposed directions or a pair at rest (unit: J).
    double momentum_work = 0;
    // With kick_bodies = "joined": alpha E that this break could not give back because the joints
    // around it hold its two pieces together (a crack that has not opened), kept until a later
    // break parts them; and the held energy of earlier breaks that this one gave back with its
    // own, having parted their pieces (unit: J).
    double held_energy = 0;
    double released_energy = 0;
    // Broken because its two pieces had turned into each other (kOverlapBreak): how deep the
    // deepest of the pair's broken joints had passed beyond the joints left (unit: m); 0 for a
    // break by its load.
    double overlap = 0;
};

// Joined pieces do not collide with each other (they share faces). A pair whose joints that are
// left hold it on one line (a ball joint or a hinge) can then turn one piece through the other's
// material with nothing but the joints' damping to stop it, where real pieces would meet and lever
// those joints off. So when the two pivots of one of a pair's broken joints, each carried by its
// piece, have passed into each other along the line between the pieces' centres by more than
// kOverlapBreak of the smaller piece's radius beyond what the joints left are pressed together
// along it, the pair's joints still holding break, through the usual break and its books
// (BreakRecord::overlap; docs/physics.md section 3).
inline constexpr double kOverlapBreak = 0.1;  // of the smaller piece's radius (unit: 1)

// What a break gives back: alpha E, plus the held energy it releases, less what it holds (unit: J).
inline double given_back(const BreakRecord& b) {
    return b.alpha * b.kicks.stored_energy + b.released_energy - b.held_energy;
}

// The energy books at one recorded frame (unit: J).
struct EnergySample {
    double time = 0;       // (unit: s)
    double kinetic = 0;    // of the dynamic pieces
    double potential = 0;  // gravitational, -sum m g.x
    double stored = 0;     // in the active constraints, |f|^2 / 2k
    double injected = 0;   // by energizing so far, in the world's frame (injected + momentum work)
    double removed = 0;    // elastic energy (k |d|^2 / 2 by the stretch) of the constraints broken so far
    double elastic = 0;    // in the active constraints by their stretch, k |d|^2 / 2
    // The largest joint residual (BulletWorld::joint_residual: the solver's force against the
    // stretch's, over the strength) in the steps since the previous sample (unit: 1)
    double residual = 0;
    // So far: taken from the pieces' motion by the joints' damping and the implicit step,
    // taken by contacts, given by driven pieces and props, and taken by the step's integration
    // (BulletWorld::StepWork). With them the books close: kinetic + potential + elastic +
    // removed + joints_damped + contacts + integration - injected - driven stays constant
    // (docs/physics.md, "The books").
    double joints_damped = 0;
    double contacts = 0;
    double driven = 0;
    double integration = 0;
};

// The largest joint residual of a run: where the joints' forces matched their stretch least.
struct ResidualPeak {
    double residual = 0;      // (unit: 1, of the joint's strength)
    double time = -1;         // (unit: s)
    int64_t constraint = -1;  // -1: no active joint
};

// A residual above this fraction of a joint's strength means the solve did not converge: the
// joints' forces are not what their stretch says, and the books miss the difference.
inline constexpr double kResidualTolerance = 0.05;

// Where the instability guard found a run unstable (simulate/instability.h); -1: none named.
struct InstabilityWhere {
    double time = -1;          // (unit: s)
    int64_t piece = -1;        // the first piece whose state is not finite, else the fastest
    int64_t constraint = -1;   // the active constraint with the largest load for its strength
    int64_t last_broken = -1;  // the constraint broken last
};

struct SimulationResult {
    Trajectory trajectory;
    std::vector<BreakRecord> breaks;
    std::vector<EnergySample> energy;
    uint64_t steps = 0;           // solver steps kept
    uint64_t rejected_steps = 0;  // substeps = "auto": probe steps undone to be re-run finer
    // The solver's iterations, summed over the kept steps (each step's most over its batches):
    // over `steps`, the iterations a step took (20 as shipped with iterative joints; with direct
    // ones until the joints converge, docs/physics.md section 5b).
    uint64_t solver_iterations = 0;
    uint32_t asleep = 0;          // dynamic pieces asleep at the end ([simulate] sleep)
    // duration = "auto": when the last piece came to rest (the movie ends kRestHold later);
    // negative when the simulation reached max_duration first, or without "auto" (unit: s).
    double rest_time = -1;
    double energize_seconds = 0;  // wall time spent energizing breaks (for the benchmark)
    uint64_t parallel_contact_tests = 0;  // BulletWorld::parallel_contact_tests at the end
    ResidualPeak residual;        // over every step (before each step's breaks)
    ResidualPeak residual_before_break;  // over the steps before the first break's
    // The deepest contact for its piece's size over the kept steps (BulletWorld::
    // last_step_deepest_contact), when, and the step it came from (unit: s).
    DeepContact deepest;
    double deepest_time = 0, deepest_step = 0;
    bool complete = true;
    std::string stop_reason;  // why it stopped early (complete == false)
    InstabilityWhere stopped_at;
    // on_instability = clamp: how many steps had their velocities scaled down to the energy
    // limit, the first one's description and where it was (its time: first_clamp_at.time;
    // simulate/instability.h).
    uint64_t clamps = 0;
    std::string first_clamp;
    InstabilityWhere first_clamp_at;
    // What simulate warned of, in order, each once, whatever the log level (the trajectory's
    // settings keep them under "warnings").
    std::vector<std::string> warnings;
};

// Runs the simulation. `model_id` (e.g. the model file's hash) goes into the trajectory's
// settings. Throws Error(BadInput) for settings it refuses (e.g. CFM beyond max_cfm). An
// instability (NaN, or runaway kinetic energy: simulate/instability.h) stops the run and returns
// what was recorded, complete = false, stop_reason naming the time, piece and constraints; with
// on_instability = clamp, runaway energy is clamped instead (SimulationResult::clamps).
SimulationResult simulate(const Model& model, const SimulationInput& input, const std::string& model_id);

// The fragments left after `breaks` (core/model.h count_fragments).
inline size_t count_fragments(const Model& model, const std::vector<BreakRecord>& breaks) {
    std::vector<bool> broken(model.constraints.size(), false);
    for (const BreakRecord& b : breaks) broken[b.constraint] = true;
    return count_fragments(model, broken);
}

// The largest mass ratio between two pieces that share a constraint (heavier over lighter; 1 with
// no constraints), and which two: the ratio at which sequential impulses stop converging on the
// joints between them (docs/accuracy.md, "The stability map").
double largest_joined_mass_ratio(const Model& model, uint32_t* heavier = nullptr, uint32_t* lighter = nullptr);
// The largest mass ratio between two pieces of one island (pieces joined through constraints,
// directly or through others), and which two.
double largest_island_mass_ratio(const Model& model, uint32_t* heavier = nullptr, uint32_t* lighter = nullptr);
// joints = "auto" (the default) solves every model's joints directly: only direct joints keep every
// joint's force to its stretch through an impact, at any piece count, and so the energy a break
// gives back to what its joint held (docs/physics.md section 5b). Iterative joints, by name, are
// warned before the run where they may fail:
// ... when the largest joined mass ratio is above this: the rig of the stability map (20
// iterations) is stable with iterative joints up to a ratio of 10 and cascades from 12 on; direct
// joints hold it up to 1,000 (docs/accuracy.md, "The stability map").
inline constexpr double kIterativeMassRatio = 10;   // (unit: 1)
// ... or when the largest island mass ratio is above this: a load passed down a chain of moderate
// ratios onto a light piece that a contact holds (the stability scenes' stack, heavier by the same
// factor at each of its three joints) cascades with iterative joints at 100 from top to bottom and
// stands at 10, where direct joints, which solve such contacts through the joints, hold it at
// 1,000.
inline constexpr double kIterativeIslandRatio = 30;  // (unit: 1)
// ... and after the run when the joints that broke held more than this share above what their
// forces stored (the books count the stored energy; the stretch's excess left with the pieces).
inline constexpr double kIterativeStretchExcess = 0.1;  // (unit: 1)
// Whether a run with these settings solves its joints directly ("auto" resolved: it does).
bool solves_joints_directly(const Model& model, const SimulateSettings& s);

// Where the frames go: frame count for duration and fps (frame 0 at t = 0 included). With
// duration = "auto", the most frames: those of max_duration.
uint32_t frame_count(const SimulateSettings& s);

// The automatic step (substeps = "auto"; docs/physics.md, "The automatic step"). Each frame is
// cut into blocks of at most kAutoBlock. A block starts as one probe step of its whole length.
// The probe is undone (the bodies' state restored, the contacts' remembered impulses forgotten)
// when a joint's load reaches kAutoRefineLoad of its strength, the load being the largest of
//   - the force the solver applied;
//   - the spring's own force k |d| from the stretch (a joint between two dynamic pieces): an
//     unconverged solve applies less than the stretch holds;
//   - omega h |df|, df the change of its force in the probe from its mean over the block before:
//     a load that comes within a step that treats the joint as rigid (omega h > 1) stands for a
//     velocity jump whose real peak force is omega h times larger (docs/physics.md section 7);
//     only the change beyond twice the solve's tolerance (BulletWorld::joint_tolerance; direct
//     joints: kDirectTolerance of the strength), within which two converged solves of a joint at
//     rest can differ; after fine steps, only as much of it as the probe's force has;
//   - for a piece that the probe leaves in contact, v sqrt(k / w), v the speed at which it
//     approaches what it touches (BulletWorld::approach_load): an impact that begins at the end
//     of the probe, where Bullet finds the contact only in the next step.
// An undone block is re-run in n equal steps, n the least power of two with omega h <= kAutoOmegaH
// for the stiffest joint row (omega = sqrt(k w)), at most kAutoMaxSplit, and with iterative
// joints no more than keeps every row's CFM within max_cfm. Blocks stay fine until one ends with
// no break and every joint's force under kAutoCalmLoad of its strength.
// Except where the probe was undone for the spring's k |d| alone: joined pieces that turn part
// their pivots within a step by about (omega h)^2 |r| with no force behind it, which falls as h^2.
// Such a block is first run in m < n steps (m the power of two that brings the stretch under
// kAutoRefineLoad), each of them a probe; one undone for its stretch alone again splits the rest
// of the block further, any other sends it to the fine steps. The next block starts at m steps,
// or m / 2 when the kept steps' stretch allows it.
// Calm steps span blocks: once the object has touched the scene (or broken), a kept one-step probe
// lets the next probe cover two aligned blocks (at most kAutoMaxSpan) when its loads scaled to the
// longer step (the stretch as h^2, everything else as h) stay under kAutoRefineLoad and every
// awake piece moves under kAutoSpanTravel of its size (|v| / r + |w|) within it.
// A probe undone for its stretch alone whose split would need the fine steps' count or more sends
// the next 1, 2, 4, ... (at most kAutoMaxWait) blocks to the fine steps unprobed; a kept probe
// starts the wait at 1 again.
inline constexpr double kAutoBlock = 1.0 / 480;   // (unit: s)
// A run at a fixed step that breaks nothing while its stiffest joint has omega h above this is
// warned about: an impact's peak force is then resolved to about 1 / (omega h) of itself
// (docs/physics.md section 7), so a stiff material may not break where it should.
inline constexpr double kStiffStepWarning = 10;   // (unit: 1)
// A piece found deeper inside what it touches than this many times its radius after a kept step
// (SimulationResult::deepest) is warned about, with the finer step to take: glmark2's cat in 1,000
// pieces dropped 1.5 m at h = 1/480 s reaches 1.47 and ends with a 3 mm piece stuck below the
// ground; in 300 pieces 0.79, and none does.
inline constexpr double kDeepContactWarning = 1.0;  // (unit: 1)
inline constexpr double kAutoRefineLoad = 0.5;    // of a joint's strength
inline constexpr double kAutoCalmLoad = 0.25;     // of a joint's strength
inline constexpr double kAutoOmegaH = 2.5;        // (unit: 1)
inline constexpr uint32_t kAutoMaxSplit = 4096;   // fine steps per block, at most
inline constexpr uint32_t kAutoMaxSpan = 2;       // blocks one calm step spans, at most
inline constexpr double kAutoSpanTravel = 0.1;    // of a piece's size, at most, in a spanned step
inline constexpr uint32_t kAutoMaxWait = 8;       // blocks run fine unprobed after a stretch only they resolve
// The fine steps per block of length `block` for joints whose rows' frequencies span
// [lowest, highest] (rad/s; BulletWorld::joint_frequencies): 1 with no joints.
uint32_t auto_split(double block, double highest, double lowest, bool direct_joints, double max_cfm);

// duration = "auto": the pieces are at rest over a hold of kRestHold when no dynamic piece's
// centre moved faster than the rest speed between two of its frames and no point of any got
// farther than the rest speed times kRestHold from where it was at the hold's first frame
// (|dx| + angle r, r its radius about its centre of mass; from the poses the trajectory keeps):
// a piece trembling in place rests, one falling, creeping or turning further does not.
// The simulation ends at the end of the first such hold, checked at frame boundaries
// (deterministic), or at max_duration. A hold begins no earlier than the end of the frame in which
// the object first touched the scene or broke (when it does), so that a fall does not count; no
// piece may gather more than kRestSpeed of speed over it (a slow collapse is no rest); and a piece
// far from the others rests below kRestSpeedPerSize times its distance from their centre of mass
// when that is more than the rest speed (a 40 degree camera that keeps it in view sees it move
// under half a pixel a frame; one that lets it go does not see it).
// The rest speed is kRestSpeed, or kRestSpeedPerSize times the object's size (the diagonal of its
// bounding box) when that is more: a 5 m object creeping at 5 cm/s moves less than half a pixel
// a frame in a movie that frames it, and is still to the eye. But, until the object first touches
// the scene or breaks, never more than a quarter of the speed gravity gives in the hold (kRestFall
// x |g| x kRestHold, 1.23 m/s on Earth): a 100 m object dropped from rest falls slower than 0.04
// sizes per second for its whole first hold, and would end its movie before it lands.
// Once it has landed, the rest speed of each frame is also at least kRestSpeedPerSize times the
// spread of its pieces (twice the distance from their centre of mass within which the nearest
// kRestSpreadMass of the mass lies): the follow camera frames the bulk of the pieces, not the
// object's first size, and a fragment creeping at 3 cm/s in a heap of pieces strewn over 0.8 m
// moves under half a pixel a frame (glmark2's cat in 1,000 pieces: one 3 mm piece wedged under the
// heap creeps at 2 cm/s for seconds; by the object's size alone its movie runs to max_duration, by
// the spread it ends at 6.4 s).
inline constexpr double kRestSpeed = 0.02;          // (unit: m/s)
inline constexpr double kRestSpeedPerSize = 0.04;   // (unit: 1/s: object sizes per second)
inline constexpr double kRestHold = 0.5;            // (unit: s)
inline constexpr double kRestFall = 0.25;           // (unit: 1)
inline constexpr double kRestSpreadMass = 0.9;      // the share of the mass whose spread counts (unit: 1)
double rest_speed(const Model& model, double gravity);  // gravity: |g| (unit: m/s^2); returns m/s
// Sleeping ([simulate] sleep; simulate/bullet_world.h): an island of pieces sleeps once all of
// them have moved slower than kSleepSpeed (centre, and turning: at their radius) for kSleepTime:
// half the least rest speed. Not in proportion to the object's size, as the rest speed may be: a
// sleeping piece stops, and a piece drifting in free space or creeping down a slope would stop
// where it should go on (the movie's end at rest only stops watching it). At 0.01 m/s a piece thrown
// up is that slow for 2 ms around the top of its flight, far below kSleepTime.
inline constexpr double kSleepSpeed = 0.5 * kRestSpeed;  // (unit: m/s)
// Once the object has touched the scene (a piece in contact with the ground, a collider, a
// kinematic body or a projectile) or broken, the cap no longer applies: it kept a falling object
// from resting, and a 600 m object's last piece sliding at 6 m/s (0.01 sizes per second) is still
// to the eye (unit: m/s).
double rest_speed_landed(const Model& model);

}  // namespace shatter
