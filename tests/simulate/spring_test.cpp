// The spring a compliant constraint stands for, measured in Bullet against what was asked for:
// static stiffness, and the stored energy from displacement against that from force.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "scenes/box_model.h"
#include "simulate/bullet_world.h"
#include "simulate/spring.h"

namespace shatter {
namespace {

// A box of mass m hangs from a fixed anchor box by one constraint at its top face's centre,
// directly above its centre of mass. At rest the constraint carries m g and is stretched
// phi = m g / k: the measured stiffness is m g / phi.
struct Hanging {
    BoxModelBuilder b;
    WorldSetup setup;
    Hanging(double mass, double k, double h) {
        const double side = std::cbrt(mass / 1000.0);
        const uint32_t anchor = b.box(Vec3(0, 1 + side, 0), Vec3::Constant(side));
        const uint32_t body = b.box(Vec3(0, 1, 0), Vec3::Constant(side));
        b.join(anchor, body, Vec3(0, 1 + side / 2, 0), 1.0);
        setup.scene.ground = false;
        setup.object.driven.push_back({anchor, true, Vec3::Zero(), {}});
        setup.material.stiffness = k;  // area 1 m^2: k N/m
        setup.material.damping = 0;
        setup.material.strength = 1e30;
        setup.h = h;
        setup.iterations = 50;
    }
};

// (mass kg, stiffness N/m, step s): chosen with CFM = m / (h^2 k) <= 0.1, where the solver converges.
struct Case {
    double mass, k, h;
};

TEST(Spring, StaticStiffnessOfOneBodyOnAnAnchorIsTheRequestedStiffnessWithinOnePercent) {
    for (const Case& c : {Case{0.2, 1e5, 1.0 / 240}, Case{5, 3e6, 1.0 / 240}, Case{100, 1e8, 1.0 / 480},
                          Case{1, 2e7, 1.0 / 960}, Case{20, 1e10, 1.0 / 960}}) {
        Hanging s(c.mass, c.k, c.h);
        BulletWorld world(s.b.model(), s.setup);
        const Vec3 start = world.piece_position(1);
        for (int i = 0; i < int(0.5 / c.h); ++i) world.step();
        const double sag = start.y() - world.piece_position(1).y();
        const double measured = c.mass * 9.81 / sag;
        EXPECT_NEAR(measured / c.k, 1.0, 0.01) << fmt::format("m {} k {} h {}", c.mass, c.k, c.h);
        RecordProperty(fmt::format("stiffness_ratio_m{}_k{}_h{}", c.mass, c.k, 1 / c.h), fmt::format("{:.6f}", measured / c.k));
        EXPECT_NEAR(world.force_on_a(0).norm(), c.mass * 9.81, 1e-6 * c.mass * 9.81);
    }
}

TEST(Spring, StaticStiffnessBetweenTwoDynamicBodiesIsTheRequestedStiffness) {
    // anchor - upper (2 kg) - lower (3 kg): the lower constraint carries only the lower body's
    // weight, and stretches by m_lower g / k although both its ends move.
    BoxModelBuilder b;
    const double side = std::cbrt(2.0 / 1000), side3 = std::cbrt(3.0 / 1000);
    const uint32_t anchor = b.box(Vec3(0, 2, 0), Vec3::Constant(side));
    const uint32_t upper = b.box(Vec3(0, 2 - side, 0), Vec3::Constant(side));
    const uint32_t lower = b.box(Vec3(0, 2 - 1.5 * side - side3 / 2, 0), Vec3::Constant(side3));
    b.join(anchor, upper, Vec3(0, 2 - side / 2, 0), 1.0);
    b.join(upper, lower, Vec3(0, 2 - 1.5 * side, 0), 1.0);
    WorldSetup setup;
    setup.scene.ground = false;
    setup.object.driven.push_back({anchor, true, Vec3::Zero(), {}});
    setup.material.stiffness = 1e7;
    setup.material.strength = 1e30;
    setup.h = 1.0 / 480;
    setup.iterations = 100;
    BulletWorld world(b.model(), setup);
    const double gap0 = world.piece_position(1).y() - world.piece_position(2).y();
    for (int i = 0; i < 480; ++i) world.step();
    const double stretch = world.piece_position(1).y() - world.piece_position(2).y() - gap0;
    EXPECT_NEAR(3.0 * 9.81 / stretch / 1e7, 1.0, 0.01);
}

TEST(Spring, StoredEnergyFromDisplacementEqualsEnergyFromForceWithinTwoPercent) {
    for (const Case& c : {Case{1, 1e6, 1.0 / 240}, Case{10, 1e8, 1.0 / 480}}) {
        Hanging s(c.mass, c.k, c.h);
        BulletWorld world(s.b.model(), s.setup);
        const Vec3 start = world.piece_position(1);
        for (int i = 0; i < int(0.5 / c.h); ++i) world.step();
        const double phi = (start - world.piece_position(1)).norm();
        const double from_displacement = 0.5 * c.k * phi * phi;
        const double from_force = world.stored_energy();
        EXPECT_NEAR(from_displacement / from_force, 1.0, 0.02);
    }
}

// A 1 kg box joined to a driven anchor that moves at 1 cm/s, without gravity: once the velocity
// jump of the start has rung out (omega h = 21, backward Euler damps it within a few steps) the box
// moves with the anchor and the spring holds nothing. Bullet has the anchor at its step-end pose
// when it solves the step and gives it that motion's velocity too; counted twice (measured), the
// box settles a step's motion further ahead (v h = 21 um), where the spring's law puts it at no
// stretch at all.
TEST(Spring, ABodyPulledByADrivenAnchorFollowsItWithoutStretch) {
    const double v = 0.01, h = 1.0 / 480, k = 1e8;
    for (const bool direct : {false, true}) {
        BoxModelBuilder b;
        const uint32_t anchor = b.box(Vec3(0, 0, 0), Vec3::Constant(0.1));
        const uint32_t body = b.box(Vec3(0.1, 0, 0), Vec3::Constant(0.1));
        b.join(anchor, body, Vec3(0.05, 0, 0), 1.0);
        WorldSetup setup;
        setup.scene.ground = false;
        setup.scene.gravity = Vec3::Zero();
        setup.object.driven.push_back({anchor, false, Vec3(v, 0, 0), {}});
        setup.material.stiffness = k;  // area 1 m^2: k N/m
        setup.material.damping = 0;
        setup.material.strength = 1e30;
        setup.h = h;
        setup.direct_joints = direct;
        BulletWorld world(b.model(), setup);
        for (int i = 0; i < 48; ++i) world.step();
        const Vec3 d = world.joint_stretch(0).stretch;
        EXPECT_LT(d.norm(), 1e-3 * v * h) << (direct ? "direct: " : "iterative: ") << d.transpose();
        EXPECT_NEAR(world.piece_position(body).x(), 0.1 + v * 48 * h, 1e-3 * v * h);
    }
}

TEST(Spring, ErpAndCfmFollowBulletsRelation) {
    const double k = 2e5, c = 300, h = 1.0 / 240, w = 1.5;
    EXPECT_DOUBLE_EQ(spring_erp(k, c, h), h * k / (h * k + c));
    EXPECT_DOUBLE_EQ(spring_cfm(k, c, h, w), 1 / (w * h * (h * k + c)));
    // min_stiffness_for_cfm inverts spring_cfm.
    EXPECT_NEAR(spring_cfm(min_stiffness_for_cfm(c, h, w, 0.5), c, h, w), 0.5, 1e-12);
}

}  // namespace
}  // namespace shatter
