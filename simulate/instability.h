// Detecting a simulation that has gone unstable, and naming where: the check simulate runs after
// every solver step ([simulate] on_instability, docs/reliability.md).
//
// Two symptoms:
//   1. a NaN or Inf in any piece's position or velocity;
//   2. runaway energy: kinetic energy that no source in the scene can pay for.
//
// The energy budget. With K, U, S the kinetic, gravitational and stored (spring) energy of the
// dynamic pieces, energy conservation with sources says
//     K(t) + U(t) + S(t) <= K0 + U0 + S0 + I(t) + W(t)
// where I is the kinetic energy injected at breaks (measured, simulate.cpp) and W the work of the
// scripted bodies. Friction, damping, restitution < 1 and breaking only remove energy. W has two
// parts:
//   - driven pieces ([[object.driven]]) do work through their constraints: per step,
//     W += -F_d . dx_d, F_d the constraint's force on the driven piece, dx_d its scripted move;
//   - kinematic bodies ([[scene.kinematic]], and driven pieces by contact) push by contact,
//     which we do not measure; instead a body hit by something moving at speed V leaves it at most
//     2V faster (an elastic bounce off a moving wall), so each piece's speed is bounded by its
//     speed under the budget plus 2V, and by Minkowski's inequality over the pieces
//         K <= (sqrt(B) + 2V sqrt(M/2))^2 = (sqrt(B) + V sqrt(2M))^2,
//     B = max(0, K0 + U0 + S0 + I + W - U - S), M the dynamic mass, V the fastest scripted speed.
// The limit adds a margin for the solver's own energy error: 10% (sequential impulses with
// position correction (ERP) push penetrating contacts and stretched constraints apart, which adds
// a few percent of the energy in play), plus an absolute M (|g| 1 cm + (0.1 m/s)^2 / 2): the
// energy of the whole object dropping 1 cm and moving at 10 cm/s, so that a scene at rest, whose
// budget is ~0, is not tripped by contact jitter.
//     unstable  <=>  K > 1.1 (sqrt(B) + V sqrt(2M))^2 + M (|g| 0.01 m + 0.005 m^2/s^2)
// A real blow-up exceeds that by orders of magnitude within a few steps.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/model.h"
#include "core/scene_settings.h"

namespace shatter {

class BulletWorld;
struct BreakRecord;
struct InstabilityWhere;

struct EnergyLimit {
    double kinetic = 0;  // K now (unit: J)
    double budget = 0;   // B (unit: J)
    double limit = 0;    // the kinetic energy beyond which the run is unstable (unit: J)
};

class InstabilityGuard {
public:
    InstabilityGuard(const BulletWorld& world, const Model& model, const SceneSettings& scene,
                     const ObjectSettings& object, const MaterialSettings& material);

    // After each solver step: adds the driven pieces' work of that step.
    void after_step(const BulletWorld& world);
    // The budget and limit now, given the kinetic energy injected at breaks so far.
    EnergyLimit limit(const BulletWorld& world, double injected) const;
    // True when a piece's position or velocity is NaN or infinite.
    static bool non_finite(const BulletWorld& world);

    // "at t = 1.2340 s ...: piece 3 is the fastest (85 m/s); constraint 12 (pieces 3 and 4) broke
    // last, at t = 1.2000 s; constraint 7 (pieces 1 and 2) carries the largest force, ..."
    // Also fills *at (when given) with the time, piece and constraints the text names.
    static std::string where(const BulletWorld& world, const std::vector<BreakRecord>& breaks,
                             InstabilityWhere* at = nullptr);
    static std::string describe_runaway(const EnergyLimit& e, const BulletWorld& world,
                                        const std::vector<BreakRecord>& breaks, InstabilityWhere* at = nullptr);
    static std::string describe_non_finite(const BulletWorld& world, const std::vector<BreakRecord>& breaks,
                                           InstabilityWhere* at = nullptr);

    double driven_work() const { return driven_work_; }  // W so far (unit: J)
    double scripted_speed() const { return scripted_speed_; }  // V (unit: m/s)

private:
    struct DrivenJoint {
        size_t constraint;
        bool driven_is_a;
        const PieceDriveSettings* drive;
    };
    std::vector<DrivenJoint> driven_joints_;
    double initial_ = 0;         // K0 + U0 + S0 (unit: J)
    double mass_ = 0;            // M (unit: kg)
    double scripted_speed_ = 0;  // V (unit: m/s)
    double slack_ = 0;           // the absolute margin (unit: J)
    double driven_work_ = 0;     // W of the driven pieces (unit: J)
};

}  // namespace shatter
