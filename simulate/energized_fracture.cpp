#include "simulate/energized_fracture.h"

#include <cassert>
#include <cmath>

namespace shatter {

namespace {

uint64_t splitmix64(uint64_t& state) {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

double unit_double(uint64_t& state) { return static_cast<double>(splitmix64(state) >> 11) * 0x1.0p-53; }

// A uniformly random unit vector orthogonal to n (|n| > 0), from the key.
Vec3 random_orthogonal(const Vec3& n, uint64_t key) {
    const Vec3 u = n.normalized();
    const Vec3 helper = std::abs(u.x()) < 0.6 ? Vec3::UnitX() : (std::abs(u.y()) < 0.6 ? Vec3::UnitY() : Vec3::UnitZ());
    const Vec3 e1 = u.cross(helper).normalized();
    const Vec3 e2 = u.cross(e1);
    uint64_t state = key;
    const double angle = 2.0 * M_PI * unit_double(state);
    return std::cos(angle) * e1 + std::sin(angle) * e2;
}

}  // namespace

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

BreakKicks energize(const BodyAtPivot& a, const BodyAtPivot& b, double stiffness, const EnergizeSettings& s,
                    uint64_t random_key) {
    BreakKicks out;
    out.stored_energy = stored_energy(a.force, stiffness);
    const std::array<const BodyAtPivot*, 2> body = {&a, &b};
    for (int k = 0; k < 2; ++k) {
        Kick& kick = out.kick[k];
        if (!body[k]->dynamic) continue;
        if (k == 1 && s.directions == KickDirections::Opposed && a.dynamic) {
            kick.direction = -out.kick[0].direction;
            kick.random_direction = out.kick[0].random_direction;
        } else {
            kick.direction = kick_direction(body[k]->force, body[k]->torque, body[k]->r, random_key + 0x51ed27u * k,
                                            s.tiny_ratio, &kick.random_direction);
        }
        kick.effective_mass = effective_mass(body[k]->inv_mass, body[k]->inv_inertia, body[k]->r, kick.direction);
    }
    const double released = s.alpha * out.stored_energy;
    const bool both = a.dynamic && b.dynamic;
    if (both && (s.split == EnergySplit::Total || s.directions == KickDirections::Opposed)) {
        // Equal magnitudes: mu^2 / 2 (1/m_Ga + 1/m_Gb) = alpha E.
        const double inv_sum = 1.0 / out.kick[0].effective_mass + 1.0 / out.kick[1].effective_mass;
        const double mu = std::sqrt(2.0 * released / inv_sum);
        for (Kick& kick : out.kick) {
            kick.magnitude = mu;
            kick.energy = mu * mu / (2.0 * kick.effective_mass);
        }
    } else {
        // Each dynamic body takes alpha E (PerBody; or the only dynamic body takes it all).
        for (int k = 0; k < 2; ++k) {
            if (!body[k]->dynamic) continue;
            out.kick[k].energy = released;
            out.kick[k].magnitude = std::sqrt(2.0 * out.kick[k].effective_mass * released);
        }
    }
    for (Kick& kick : out.kick) kick.impulse = kick.magnitude * kick.direction;
    return out;
}

}  // namespace shatter
