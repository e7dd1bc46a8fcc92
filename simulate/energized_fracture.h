// Energized fracture: the contribution of Xiaokai Li, Sheldon Andrews, Ben Jones and Adam W.
// Bargteil, "Energized Rigid Body Fracture", Proc. ACM Comput. Graph. Interact. Tech. (PACMCGIT)
// 1(1), article 9, 2018, doi:10.1145/3203207. Free of any physics engine (Eigen only);
// simulate/bullet_world.cpp is the adapter that feeds it.
//
// A breaking constraint stored elastic energy in its compliance; plain deletion throws that
// energy away. The paper gives it back as kinetic energy:
//
//   stored energy      E   = 1/2 |f|^2 / k              (k: the constraint's stiffness, N/m;
//                                                        f: its force, N; = 1/2 h^-2 l^T C l)
//   direction, body b  i_b = -(t_b x f_b) / |t_b x f_b| (t_b: the constraint's torque about b's
//                                                        centre of mass, f_b: its force on b)
//                      when |t_b x f_b| is tiny (a pull through the centre of mass, a chain):
//                      a seeded random direction orthogonal to f_b
//   effective mass     m_G = 1 / (1/m + (r x i)^T I^-1 (r x i))   (r: pivot - centre of mass)
//   impulse            mu_b = sqrt(2 alpha m_G E_b), applied at the pivot along i_b
//
// A body at rest that takes the impulse mu along i at r gains kinetic energy mu^2 / (2 m_G).
// A moving body gains mu (i . v_p) + mu^2 / (2 m_G), v_p the velocity of its point at the
// pivot: the paper's magnitudes then add more or less than alpha E, by a cross term that depends
// on the frame of reference and can dominate on impact (docs/physics.md section 4 has the
// measurements). With exact_energy the magnitudes solve the quadratic instead,
//
//   a mu^2 + b mu = alpha E,   a = 1/2 sum 1/m_G,   b = sum i . (v_p - V)   (sums over the bodies)
//
// so that the kinetic energy gained is alpha E (or the split's share) whatever the bodies'
// motion; directions are unchanged. The quadratic is solved in the pair's frame: v_p is taken
// relative to the velocity V of the two bodies' common centre of mass (pair_frame_velocity).
// Released energy is internal: it should not depend on how fast the pair as a whole moves.
// Solved in the lab frame instead (V = 0), a pair falling at speed u whose kicks point up (the
// paper's directions in a bending break) has b ~ -2u and needs mu ~ 2 m_G u: the kicks reflect
// the fall and can stop a falling object in mid-air. In the lab frame the impulses add
// alpha E + dP . V, dP their net momentum: zero for Directions::Opposed, the "momentum work" of
// the paper's directions otherwise.
//
// How E is shared (the paper says "the process is similar for the second body"):
//   Split::Total (default): the two bodies take impulses of EQUAL magnitude mu with
//     mu^2/2 (1/m_Ga + 1/m_Gb) = alpha E, so that two bodies at rest gain exactly alpha E in
//     total, body b the share E_b = alpha E (1/m_Gb) / (1/m_Ga + 1/m_Gb): the lighter body
//     moves more, as with an internal force pair.
//   Split::PerBody (the paper read literally): each dynamic body takes alpha E, 2 alpha E in all.
//   A static or kinematic body takes nothing; a dynamic body joined to one takes the whole
//   alpha E (both splits).
// Directions:
//   Directions::Paper: each body its own i_b as above. In a bending break both bodies
//     can be kicked the same way, so linear momentum is not conserved in general.
//   Directions::Opposed (momentum-conserving; the shots' default method, "exact"): body a takes
//     i_a, body b takes -i_a, with the equal magnitudes of Split::Total. Equal and opposite impulses at one point change
//     neither linear nor angular momentum.
//   Directions::Force (momentum-conserving): along the line of the force the constraint carried,
//     each body away from the other: body b along +-f_b/|f_b|, the sign making it point away from
//     a's centre of mass ((c_b - c_a) . i_b >= 0), body a opposite, equal magnitudes. A joint
//     loaded in compression or tension is pushed open along its load; one loaded in shear (an
//     impact's) releases across the interface, where packed neighbours do not stop the pieces.
#pragma once

#include <array>
#include <cstdint>

#include "core/geometry.h"

namespace shatter {

enum class EnergySplit { Total, PerBody };
enum class KickDirections { Paper, Opposed, Force };
// What a break's kicks move: its two pieces as free bodies, or the pieces with everything still
// joined to them, as their joints allow (joined_response.h; simulate/breaking.h).
enum class KickBodies { Pieces, Joined };

// One body at the breaking constraint's pivot, in world coordinates.
struct BodyAtPivot {
    bool dynamic = true;          // false: static or kinematic, takes no impulse
    double inv_mass = 0;          // (unit: 1/kg)
    Mat3 inv_inertia = Mat3::Zero();  // world frame (unit: 1/(kg m^2))
    Vec3 r = Vec3::Zero();        // pivot - centre of mass (unit: m)
    Vec3 force = Vec3::Zero();    // force the constraint applied to this body (unit: N)
    Vec3 torque = Vec3::Zero();   // torque the constraint applied about the centre of mass (unit: N m)
    Vec3 velocity = Vec3::Zero(); // velocity of the body's point at the pivot, v + w x r (unit: m/s)
    Vec3 centre_velocity = Vec3::Zero();  // velocity v of the centre of mass (unit: m/s)
};

// The frame in which a break's energy is counted: the velocity of the two bodies' common centre
// of mass when both are dynamic; zero when one is static or kinematic (the world's frame).
// (Of the bodies as given: see energize() for which state the simulation passes.)
Vec3 pair_frame_velocity(const BodyAtPivot& a, const BodyAtPivot& b);

struct Kick {
    Vec3 direction = Vec3::Zero();  // unit vector i_b
    bool random_direction = false;  // |t x f| was tiny: a random direction orthogonal to f
    double effective_mass = 0;      // m_G along direction at the pivot (unit: kg)
    double energy = 0;              // the kinetic energy this body gains in the pair's frame (if at rest, or with exact_energy) (unit: J)
    double magnitude = 0;           // mu (unit: N s)
    Vec3 impulse = Vec3::Zero();    // magnitude * direction (unit: N s), applied at the pivot
};

struct BreakKicks {
    double stored_energy = 0;  // E (unit: J)
    std::array<Kick, 2> kick;  // bodies a and b
};

struct EnergizeSettings {
    double alpha = 1.0;  // fraction of E given back; >= 0, > 1 for artistic effect
    EnergySplit split = EnergySplit::Total;
    KickDirections directions = KickDirections::Paper;
    // |t x f| <= tiny_ratio |f|^2 |r| means t and f are (nearly) parallel or t vanishes.
    double tiny_ratio = 1e-6;
    // Solve the magnitudes for the bodies' motion so that the kinetic energy gained is exact.
    bool exact_energy = false;
    KickBodies bodies = KickBodies::Pieces;
};

// E = 1/2 |f|^2 / k (unit: J).
double stored_energy(const Vec3& force, double stiffness);

// m_G = 1 / (1/m + (r x i)^T I^-1 (r x i)) (unit: kg).
double effective_mass(double inv_mass, const Mat3& inv_inertia, const Vec3& r, const Vec3& direction);

// -(t x f)/|t x f|, or a random unit vector orthogonal to f drawn from `random_key` when
// |t x f| is tiny. Sets *random accordingly.
Vec3 kick_direction(const Vec3& force, const Vec3& torque, const Vec3& r, uint64_t random_key, double tiny_ratio,
                    bool* random);

// The kicks' directions (energize()'s rules) and the stored energy; magnitudes and energies zero.
BreakKicks kick_directions(const BodyAtPivot& a, const BodyAtPivot& b, double stiffness, const EnergizeSettings& settings,
                           uint64_t random_key);

// The impulse magnitude mu >= 0 that adds kinetic energy e >= 0 to bodies that gain
// mu b + mu^2 a from it (a > 0; b: the bodies' motion along the kicks; a: half the kicks' work per
// unit impulse squared, sum 1/(2 m_G) for free bodies) (unit: N s).
double kick_magnitude(double a, double b, double e);

// The impulses to apply at the pivot when a constraint with stiffness k (N/m) breaks.
// `random_key` makes the random directions reproducible (e.g. a hash of seed and constraint).
// With exact_energy the energy is counted in the frame moving at `frame` (by default
// pair_frame_velocity(a, b)). When several constraints break in one step, the simulation passes
// the pair's velocity from before any of that step's kicks: the paper's kicks do not conserve
// momentum, and each break's frame would otherwise move with the kicks before it (docs/physics.md
// section 4 measures what that loses on the beam).
BreakKicks energize(const BodyAtPivot& a, const BodyAtPivot& b, double stiffness, const EnergizeSettings& settings,
                    uint64_t random_key);
BreakKicks energize(const BodyAtPivot& a, const BodyAtPivot& b, double stiffness, const EnergizeSettings& settings,
                    uint64_t random_key, const Vec3& frame);

}  // namespace shatter
