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
BreakRecord energize_broken(BulletWorld& world, size_t constraint, const std::array<BodyAtPivot, 2>& load,
                            const EnergizeSettings& settings, uint64_t key, std::optional<Vec3> frame = std::nullopt);

// The constraints overloaded in the last step, ascending, with |f| / strength. With
// BreakCriterion::Force: those whose force norm exceeds their strength. With BulletImpulse: those
// Bullet disabled (a row's impulse reached strength x h); they are enabled again here, and the
// ones the break policy picks are then removed as usual.
std::vector<Overload> find_overloads(BulletWorld& world, BreakCriterion criterion);

// The seed of constraint c's random kick direction.
uint64_t break_key(uint64_t seed, size_t constraint);

}  // namespace shatter
