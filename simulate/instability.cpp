// The instability check. Design notes and the energy budget: instability.h.
#include "simulate/instability.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "simulate/bullet_world.h"
#include "simulate/simulate.h"

namespace shatter {

namespace {

constexpr double kRelativeMargin = 0.10;  // the solver's own energy error (instability.h)
constexpr double kJitterDrop = 0.01;      // (unit: m)
constexpr double kJitterSpeed = 0.1;      // (unit: m/s)

// The fastest a set of keys or a constant velocity moves (unit: m/s).
double top_speed(const Vec3& velocity, const std::vector<KeyFrame>& keys) {
    if (keys.empty()) return velocity.norm();
    double v = 0;
    for (size_t i = 1; i < keys.size(); ++i) {
        const double dt = keys[i].time - keys[i - 1].time;
        if (dt > 0) v = std::max(v, (keys[i].position - keys[i - 1].position).norm() / dt);
    }
    return v;
}

}  // namespace

InstabilityGuard::InstabilityGuard(const BulletWorld& world, const Model& model, const SceneSettings& scene,
                                   const ObjectSettings& object, const MaterialSettings& material) {
    const double density_scale = material.density ? *material.density / model.density : 1.0;
    for (uint32_t p = 0; p < world.pieces(); ++p)
        if (world.piece_dynamic(p)) mass_ += model.pieces[p].mass.mass * density_scale;
    for (const ProjectileSettings& p : scene.projectiles) mass_ += projectile_mass(p);
    for (const KinematicSettings& k : scene.kinematic)
        scripted_speed_ = std::max(scripted_speed_, top_speed(k.velocity, k.keys));
    std::vector<const PieceDriveSettings*> drive(world.pieces(), nullptr);
    for (const PieceDriveSettings& d : object.driven) {
        if (d.piece < drive.size()) drive[d.piece] = &d;
        if (!d.fixed) scripted_speed_ = std::max(scripted_speed_, top_speed(d.velocity, d.keys));
    }
    for (size_t c = 0; c < world.constraint_count(); ++c) {
        const uint32_t a = world.piece_a(c), b = world.piece_b(c);
        if (drive[a] && !drive[a]->fixed && world.piece_dynamic(b)) driven_joints_.push_back({c, true, drive[a]});
        if (drive[b] && !drive[b]->fixed && world.piece_dynamic(a)) driven_joints_.push_back({c, false, drive[b]});
    }
    initial_ = world.kinetic_energy() + world.potential_energy() + world.stored_energy();
    slack_ = mass_ * (scene.gravity.norm() * kJitterDrop + 0.5 * kJitterSpeed * kJitterSpeed);
}

void InstabilityGuard::after_step(const BulletWorld& world) {
    const double t = world.time(), h = world.h();
    for (const DrivenJoint& j : driven_joints_) {
        if (!world.active(j.constraint)) continue;
        const Vec3 on_driven = j.driven_is_a ? world.force_on_a(j.constraint) : Vec3(-world.force_on_a(j.constraint));
        const Vec3 move = drive_offset(*j.drive, t) - drive_offset(*j.drive, t - h);
        driven_work_ -= on_driven.dot(move);
    }
}

EnergyLimit InstabilityGuard::limit(const BulletWorld& world, double injected) const {
    EnergyLimit e;
    e.kinetic = world.kinetic_energy();
    e.budget = std::max(0.0, initial_ + injected + driven_work_ - world.potential_energy() - world.stored_energy());
    const double bound = std::sqrt(e.budget) + scripted_speed_ * std::sqrt(2 * mass_);
    e.limit = (1 + kRelativeMargin) * bound * bound + slack_;
    return e;
}

bool InstabilityGuard::non_finite(const BulletWorld& world) { return !world.finite(); }

std::string InstabilityGuard::where(const BulletWorld& world, const std::vector<BreakRecord>& breaks,
                                    InstabilityWhere* at) {
    std::string s;
    // The piece: the first non-finite one, else the fastest dynamic one.
    int64_t piece = -1;
    double speed = -1;
    for (uint32_t p = 0; p < world.pieces() && piece < 0; ++p)
        if (!world.piece_position(p).allFinite() || !world.piece_velocity(p).allFinite()) piece = p;
    if (piece >= 0) {
        s = fmt::format("piece {} is the first whose position or velocity is not finite", piece);
    } else {
        for (uint32_t p = 0; p < world.pieces(); ++p) {
            if (!world.piece_dynamic(p)) continue;
            const double v = world.piece_velocity(p).norm();
            if (v > speed) speed = v, piece = p;
        }
        if (piece >= 0) s = fmt::format("piece {} is the fastest ({:.4g} m/s)", piece, speed);
    }
    // The constraints: the one broken last, and the active one with the largest force for its strength.
    if (!breaks.empty()) {
        const BreakRecord& b = breaks.back();
        s += fmt::format("; constraint {} (pieces {} and {}) broke last, at t = {:.4f} s", b.constraint, b.piece_a,
                         b.piece_b, b.time);
    }
    int64_t worst = -1;
    double ratio = -1, force = 0;
    for (size_t c = 0; c < world.constraint_count(); ++c) {
        if (!world.active(c)) continue;
        const double f = world.force_on_a(c).norm();
        const double r = world.strength(c) > 0 ? f / world.strength(c) : f;
        if (!std::isfinite(f)) {
            worst = int64_t(c), force = f, ratio = INFINITY;
            break;
        }
        if (r > ratio) worst = int64_t(c), ratio = r, force = f;
    }
    if (worst >= 0)
        s += fmt::format("; constraint {} (pieces {} and {}) carries the largest load, {:.4g} N ({:.3g} of its strength)",
                         worst, world.piece_a(size_t(worst)), world.piece_b(size_t(worst)), force, ratio);
    if (at) {
        at->time = world.time();
        at->piece = piece;
        at->constraint = worst;
        at->last_broken = breaks.empty() ? -1 : int64_t(breaks.back().constraint);
    }
    return s;
}

std::string InstabilityGuard::describe_runaway(const EnergyLimit& e, const BulletWorld& world,
                                               const std::vector<BreakRecord>& breaks, InstabilityWhere* at) {
    return fmt::format("at t = {:.4f} s the kinetic energy {:.4g} J exceeds what the scene can supply, {:.4g} J (energy "
                       "budget {:.4g} J with the injected and scripted work, +10% and the margin of "
                       "docs/reliability.md): {}",
                       world.time(), e.kinetic, e.limit, e.budget, where(world, breaks, at));
}

std::string InstabilityGuard::describe_non_finite(const BulletWorld& world, const std::vector<BreakRecord>& breaks,
                                                  InstabilityWhere* at) {
    return fmt::format("at t = {:.4f} s a piece's position or velocity became NaN or infinite: {}", world.time(),
                       where(world, breaks, at));
}

}  // namespace shatter
