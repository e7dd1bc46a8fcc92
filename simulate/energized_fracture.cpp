#include "simulate/energized_fracture.h"

#include <cassert>
#include <cmath>

#include "core/rng.h"

namespace shatter {

namespace {

// A uniformly random unit vector orthogonal to n (|n| > 0), from the key.
Vec3 random_orthogonal(const Vec3& n, uint64_t key) {
    const Vec3 u = n.normalized();
    const Vec3 helper = std::abs(u.x()) < 0.6 ? Vec3::UnitX() : (std::abs(u.y()) < 0.6 ? Vec3::UnitY() : Vec3::UnitZ());
    const Vec3 e1 = u.cross(helper).normalized();
    const Vec3 e2 = u.cross(e1);
    const double angle = 2.0 * M_PI * Rng(key).uniform();
    return std::cos(angle) * e1 + std::sin(angle) * e2;
}

// Directions::Force, body a's direction: along the force the constraint applied to a, signed to
// point away from b's centre of mass (a force exactly across the line of centres keeps its own
// sign: the joint's release). Body b takes the negative, so the pair's momentum is unchanged.
// A constraint that broke with no force at all gets a seeded random direction.
Vec3 separating_force_direction(const BodyAtPivot& a, const BodyAtPivot& b, uint64_t random_key, bool* random) {
    const double f = a.force.norm();
    *random = !(f > 0);
    const Vec3 along = *random ? random_orthogonal(Vec3::UnitZ(), random_key) : Vec3(a.force / f);
    const Vec3 apart = b.r - a.r;  // c_a - c_b: the pivot is common
    return along.dot(apart) >= 0 ? along : Vec3(-along);
}

}  // namespace

double kick_magnitude(double a, double b, double e) {
    if (e <= 0) return 0;
    const double disc = std::sqrt(b * b + 4 * a * e);
    // Both forms are the same root; pick the one without cancellation.
    return b >= 0 ? 2 * e / (b + disc) : (disc - b) / (2 * a);
}

double stored_energy(const Vec3& force, double stiffness) {
    assert(stiffness > 0);
    return 0.5 * force.squaredNorm() / stiffness;
}

double effective_mass(double inv_mass, const Mat3& inv_inertia, const Vec3& r, const Vec3& direction) {
    const Vec3 ri = r.cross(direction);
    const double inv = inv_mass + ri.dot(inv_inertia * ri);
    return inv > 0 ? 1.0 / inv : 0.0;
}

Vec3 kick_direction(const Vec3& force, const Vec3& torque, const Vec3& r, uint64_t random_key, double tiny_ratio,
                    bool* random) {
    const Vec3 txf = torque.cross(force);
    const double scale = force.squaredNorm() * r.norm();
    const double n = txf.norm();
    *random = !(n > tiny_ratio * scale) || !(n > 0);
    if (!*random) return -txf / n;
    if (force.squaredNorm() > 0) return random_orthogonal(force, random_key);
    return random_orthogonal(Vec3::UnitZ(), random_key);  // no force at all: any direction
}

Vec3 pair_frame_velocity(const BodyAtPivot& a, const BodyAtPivot& b) {
    if (!a.dynamic || !b.dynamic || !(a.inv_mass > 0) || !(b.inv_mass > 0)) return Vec3::Zero();
    const double ma = 1.0 / a.inv_mass, mb = 1.0 / b.inv_mass;
    return (ma * a.centre_velocity + mb * b.centre_velocity) / (ma + mb);
}

BreakKicks energize(const BodyAtPivot& a, const BodyAtPivot& b, double stiffness, const EnergizeSettings& s,
                    uint64_t random_key) {
    return energize(a, b, stiffness, s, random_key, pair_frame_velocity(a, b));
}

BreakKicks kick_directions(const BodyAtPivot& a, const BodyAtPivot& b, double stiffness, const EnergizeSettings& s,
                           uint64_t random_key) {
    BreakKicks out;
    out.stored_energy = stored_energy(a.force, stiffness);
    const std::array<const BodyAtPivot*, 2> body = {&a, &b};
    for (int k = 0; k < 2; ++k) {
        Kick& kick = out.kick[k];
        if (!body[k]->dynamic) continue;
        if (s.directions == KickDirections::Force) {
            bool random = false;
            const Vec3 along_a = separating_force_direction(a, b, random_key, &random);
            kick.direction = k == 0 ? along_a : Vec3(-along_a);
            kick.random_direction = random;
        } else if (k == 1 && s.directions == KickDirections::Opposed && a.dynamic) {
            kick.direction = -out.kick[0].direction;
            kick.random_direction = out.kick[0].random_direction;
        } else {
            kick.direction = kick_direction(body[k]->force, body[k]->torque, body[k]->r, random_key + 0x51ed27u * k,
                                            s.tiny_ratio, &kick.random_direction);
        }
    }
    return out;
}

BreakKicks energize(const BodyAtPivot& a, const BodyAtPivot& b, double stiffness, const EnergizeSettings& s,
                    uint64_t random_key, const Vec3& frame) {
    BreakKicks out = kick_directions(a, b, stiffness, s, random_key);
    const std::array<const BodyAtPivot*, 2> body = {&a, &b};
    for (int k = 0; k < 2; ++k) {
        Kick& kick = out.kick[k];
        if (body[k]->dynamic)
            kick.effective_mass = effective_mass(body[k]->inv_mass, body[k]->inv_inertia, body[k]->r, kick.direction);
    }
    const double released = s.alpha * out.stored_energy;
    const bool both = a.dynamic && b.dynamic;
    // The kinetic energy body k gains from mu along its kick: mu b_k + mu^2 a_k.
    auto a_of = [&](int k) { return 0.5 / out.kick[k].effective_mass; };
    auto b_of = [&](int k) { return s.exact_energy ? out.kick[k].direction.dot(body[k]->velocity - frame) : 0.0; };
    if (both && (s.split == EnergySplit::Total || s.directions != KickDirections::Paper)) {
        // Equal magnitudes, alpha E in all: mu^2 (a_a + a_b) + mu (b_a + b_b) = alpha E.
        const double mu = kick_magnitude(a_of(0) + a_of(1), b_of(0) + b_of(1), released);
        for (int k = 0; k < 2; ++k) {
            out.kick[k].magnitude = mu;
            out.kick[k].energy = mu * b_of(k) + mu * mu * a_of(k);
        }
    } else {
        // Each dynamic body takes alpha E (PerBody; or the only dynamic body takes it all).
        for (int k = 0; k < 2; ++k) {
            if (!body[k]->dynamic) continue;
            out.kick[k].magnitude = kick_magnitude(a_of(k), b_of(k), released);
            out.kick[k].energy = released;
        }
    }
    for (Kick& kick : out.kick) kick.impulse = kick.magnitude * kick.direction;
    return out;
}

}  // namespace shatter
