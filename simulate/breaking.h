// What happens to one constraint that the break policy picked, after it left the world:
// its stored energy goes back to its two pieces as impulses at the pivot (energized_fracture.h),
// and the break is recorded with the kinetic energy the impulses actually added.
#pragma once

#include <array>
#include <optional>

#include "simulate/break_policy.h"
#include "simulate/bullet_world.h"
#include "simulate/simulate.h"

namespace shatter {

// `load` holds the two bodies' force and torque from the step in which the constraint broke
// (bodies_at_pivot before any rollback); positions and inertia are taken from the world as it
// is now. `key` seeds the random direction of a pure-tension break. `frame`: the velocity of the
// frame the break's energy is counted in (docs/physics.md section 4): the pair's centre of mass
// in the state the kicks act on, before any of the step's kicks; by default the one in `load`.
// `joined` (BulletWorld::joined_pieces after the step's removals), when given: the kicks act on
// the pieces with everything still joined to them, as the joints allow (KickBodies::Joined,
// joined_response.h); their directions are the pieces' own, their common magnitude adds
// alpha E + `release` in `frame` (`release`: energy held by earlier breaks that this one parts).
// When the joints hold the two pieces so that the kicks can move them by less than
// kHeldResponse of what they would move two free pieces (a crack inside a welded body), the
// break gives nothing back: its alpha E is held (BreakRecord::held_energy) and `release` is not
// used.
BreakRecord energize_broken(BulletWorld& world, size_t constraint, const std::array<BodyAtPivot, 2>& load,
                            const EnergizeSettings& settings, uint64_t key, std::optional<Vec3> frame = std::nullopt,
                            const BulletWorld::JoinedPieces* joined = nullptr, double release = 0);
inline constexpr double kHeldResponse = 0.01;
// The most pieces whose joints a break's kicks are solved through (joined_response: a sparse
// solve of six unknowns per piece). A larger fragment that the break parts from the other moves
// as one rigid body (rigid_response); a break inside a larger body is held, as a welded body
// holds it. Measured on the 1,000-piece bunny (28,900 breaks): energizing takes 2.0% of the
// run at 16, 2.9% at 64 and 15% at 256.
inline constexpr size_t kJoinedPiecesLimit = 16;

// The constraints overloaded in the last step, ascending, with |f| / strength. With
// BreakCriterion::Force: those whose force norm exceeds their strength. With BulletImpulse: those
// Bullet disabled (a row's impulse reached strength x h); they are enabled again here, and the
// ones the break policy picks are then removed as usual.
std::vector<Overload> find_overloads(BulletWorld& world, BreakCriterion criterion);

// The seed of constraint c's random kick direction.
uint64_t break_key(uint64_t seed, size_t constraint);

}  // namespace shatter
