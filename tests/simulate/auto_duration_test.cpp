// duration = "auto" (simulate/simulate.h): the simulation ends kRestHold after the last piece
// comes to rest, at most max_duration, deterministically.
#include <gtest/gtest.h>

#include <cmath>

#include "core/trajectory.h"
#include "scenes/box_model.h"
#include "simulate/simulate.h"

namespace shatter {
namespace {

// A 4 x 1 x 4 plate of 5 cm boxes dropped tilted from 0.3 m on the ground: it lands after
// sqrt(2 x 0.3 / 9.81) = 0.25 s, breaks, and its pieces settle.
SimulationInput dropped_plate() {
    SimulationInput in;
    in.object.pose.position = Vec3(0, 0.3, 0);
    in.object.pose.rotation_deg = Vec3(20, 0, 10);
    in.material.stiffness = 1e9;
    in.material.strength = 2e4;
    in.material.alpha = 1;
    in.simulate.auto_duration = true;
    in.simulate.max_duration = 6;
    return in;
}

Model plate() { return box_grid(4, 1, 4, 0.05, Vec3(-0.1, 0, -0.1), 2400, 2); }

// How far the farthest point of any piece got between frames `from` and f, from the recorded
// poses (unit: m).
double reach(const Model& m, const Trajectory& t, uint32_t from, uint32_t f) {
    double farthest = 0;
    for (uint32_t i = 0; i < t.pieces; ++i) {
        double r = 0;
        for (const Vec3& v : m.pieces[i].surface.vertices) r = std::max(r, (v - m.pieces[i].mass.center).norm());
        const BodyPose &a = t.pose(from, i), &b = t.pose(f, i);
        const double angle = 2 * std::acos(std::min(1.0, double(std::abs(a.rotation.dot(b.rotation)))));
        farthest = std::max(farthest, (b.position - a.position).norm() + angle * r);
    }
    return farthest;
}

TEST(AutoDuration, EndsAHoldAfterThePiecesRest) {
    const Model m = plate();
    const SimulationResult r = simulate(m, dropped_plate(), "test");
    ASSERT_TRUE(r.complete) << r.stop_reason;
    const Trajectory& t = r.trajectory;
    // It lands at 0.25 s and needs time to settle; it rests well before the 6 s cap.
    ASSERT_GT(r.rest_time, 0.25);
    EXPECT_LT(t.frames(), frame_count(dropped_plate().simulate));
    // The last frame is kRestHold (15 frames at 30 fps) after the hold's first.
    const uint32_t hold = uint32_t(std::lround(kRestHold * t.fps));
    EXPECT_NEAR((t.frames() - 1) / t.fps, r.rest_time + kRestHold, 1e-9);
    // Over the hold, no point of any piece gets farther than the rest speed times the hold (1 cm:
    // kRestSpeed for this 0.28 m plate) from where it was at the hold's start; the hold a frame
    // earlier did not stay that close, or a centre moved faster than the rest speed in it.
    ASSERT_EQ(rest_speed(m, 9.81), kRestSpeed);
    const uint32_t start = t.frames() - 1 - hold;
    for (uint32_t f = start + 1; f < t.frames(); ++f) EXPECT_LT(reach(m, t, start, f), kRestSpeed * kRestHold) << f;
    double earlier = 0, fastest = 0;
    for (uint32_t f = start; f < t.frames() - 1; ++f) {
        earlier = std::max(earlier, reach(m, t, start - 1, f));
        for (uint32_t i = 0; i < t.pieces; ++i)
            fastest = std::max(fastest, double((t.pose(f, i).position - t.pose(f - 1, i).position).norm()) * t.fps);
    }
    EXPECT_TRUE(earlier >= kRestSpeed * kRestHold || fastest >= kRestSpeed) << earlier << " m, " << fastest << " m/s";
    // The settings remember "auto" and the cap; the same inputs give the same bytes.
    EXPECT_NE(t.settings_json.find("\"duration\":\"auto\""), std::string::npos) << t.settings_json;
    EXPECT_EQ(encode_trajectory(simulate(m, dropped_plate(), "test").trajectory), encode_trajectory(t));
    std::printf("[ auto     ] rests at %.3f s, ends at %.3f s (%u frames)\n", r.rest_time, (t.frames() - 1) / t.fps,
                t.frames());
}

// A large object rests at a speed in proportion to its size: the 4 x 1 x 4 m plate of 1 m boxes
// has a diagonal of sqrt(4^2 + 1^2 + 4^2) = sqrt(33) = 5.745 m, so kRestSpeedPerSize x 5.745 m =
// 0.2298 m/s; a 0.28 m plate keeps kRestSpeed (0.04 x 0.28 = 0.011 m/s is less).
TEST(AutoDuration, TheRestSpeedGrowsWithTheObject) {
    EXPECT_NEAR(rest_speed(box_grid(4, 1, 4, 1.0, Vec3::Zero(), 2400, 2), 9.81), 0.04 * std::sqrt(33.0), 1e-12);
    EXPECT_EQ(rest_speed(plate(), 9.81), kRestSpeed);
    // Up to a quarter of what gravity gives in the hold: 0.25 x 9.81 x 0.5 = 1.22625 m/s for a
    // 100 m cube (0.04 x 173.2 m = 6.93 m/s uncapped); without gravity, kRestSpeed.
    const Model cube = box_grid(1, 1, 1, 100.0, Vec3::Zero(), 2400, 2);
    EXPECT_NEAR(rest_speed(cube, 9.81), 1.22625, 1e-12);
    EXPECT_EQ(rest_speed(cube, 0.0), kRestSpeed);
}

// A 100 m cube dropped from 1.5 m lands after sqrt(2 x 1.5 / 9.81) = 0.553 s: its movie runs
// past the landing (it used to end at 0.5 s, the fall taken for rest).
TEST(AutoDuration, ALargeObjectFallingIsNotAtRest) {
    SimulationInput in = dropped_plate();
    in.object.pose.position = Vec3(0, 1.5, 0);
    in.object.pose.rotation_deg = Vec3::Zero();
    const SimulationResult r = simulate(box_grid(1, 1, 1, 100.0, Vec3(-50, 0, -50), 2400, 2), in, "test");
    ASSERT_TRUE(r.complete) << r.stop_reason;
    EXPECT_GT(r.rest_time, std::sqrt(2 * 1.5 / 9.81));
    EXPECT_GT((r.trajectory.frames() - 1) / r.trajectory.fps, std::sqrt(2 * 1.5 / 9.81) + kRestHold);
}

// Once it has landed, the cap is off: the 100 m cube slides on without friction at 3 m/s, over
// the capped 1.23 m/s but under its own 0.04 x 173.2 = 6.93 m/s (a few pixels a second in a movie
// that frames it), so it rests one hold after the landing instead of running to max_duration.
TEST(AutoDuration, ALargeObjectThatHasLandedRestsAtItsOwnSpeed) {
    const Model cube = box_grid(1, 1, 1, 100.0, Vec3(-50, 0, -50), 2400, 2);
    EXPECT_NEAR(rest_speed_landed(cube), 0.04 * std::sqrt(3.0) * 100, 1e-9);
    SimulationInput in = dropped_plate();
    in.object.pose.position = Vec3(0, 1.5, 0);
    in.object.pose.rotation_deg = Vec3::Zero();
    in.object.velocity = Vec3(3, 0, 0);
    in.material.surface = SurfaceSettings{0, 0};
    in.scene.ground_surface = SurfaceSettings{0, 0};
    const SimulationResult r = simulate(cube, in, "test");
    ASSERT_TRUE(r.complete) << r.stop_reason;
    const double landing = std::sqrt(2 * 1.5 / 9.81);
    EXPECT_GT(r.rest_time, landing - 1.0 / 30);  // the hold begins at a frame up to one before it lands
    EXPECT_LT(r.rest_time, landing + 1.0 / 30);
    const Trajectory& t = r.trajectory;
    const double speed = double(t.pose(t.frames() - 1, 0).position.x() - t.pose(t.frames() - 2, 0).position.x()) * t.fps;
    EXPECT_NEAR(speed, 3.0, 0.01);  // still sliding: at rest by its size, not stopped
}

// A piece far from the others rests below kRestSpeedPerSize times its distance from their centre:
// a 1 m box (1,000 kg) turning at 0.02 rad/s in place and a 10 cm box (1 kg) 10 m away that the
// turn sends off at 0.2 m/s (over kRestSpeed, under 0.04 x 10 m = 0.4 m/s; under half a pixel a
// frame for any 40 degree camera that keeps it in view): at rest over the first hold, where the
// far box alone used to run the movie to max_duration.
TEST(AutoDuration, APieceFarFromTheOthersRestsAtASpeedInProportionToItsDistance) {
    BoxModelBuilder b(1000);
    b.box(Vec3::Zero(), Vec3::Constant(1.0));
    b.box(Vec3(10, 0, 0), Vec3::Constant(0.1));
    const Model m = b.take();
    SimulationInput in = dropped_plate();
    in.scene.ground = false;
    in.scene.gravity = Vec3::Zero();
    in.object.pose = Pose{};
    in.object.angular_velocity = Vec3(0, 0.02, 0);
    const SimulationResult r = simulate(m, in, "test");
    ASSERT_TRUE(r.complete) << r.stop_reason;
    const Trajectory& t = r.trajectory;
    const double far_speed = double((t.pose(t.frames() - 1, 1).position - t.pose(t.frames() - 2, 1).position).norm()) * t.fps;
    EXPECT_NEAR(far_speed, 0.02 * 10, 0.002);
    EXPECT_NEAR(r.rest_time, 0.0, 1e-9);
    EXPECT_EQ(t.frames(), uint32_t(std::ceil(kRestHold * in.simulate.fps - 1e-9)) + 1);
}

// Once landed, the rest speed grows with the pieces' spread: eight 10 cm boxes (1 kg) in a ring of
// radius r = 1 m on a frictionless ground, the object turning at w = 2 rad/s about its centre, each
// box sliding off along its tangent at v = w r = 2 m/s and spinning at w. At time t a box is
// sqrt(r^2 + (v t)^2) from the centre, the eight spread over twice that, and the rest speed is
// 0.04 x the spread; over a hold ending at t a box's farthest point gets (v + w r_p) x 0.5 s from
// where it was (r_p = 0.0866 m, half the cube's diagonal). So the hold rests once
// 0.08 sqrt(r^2 + (v t)^2) > v + w r_p, t = 13.57 s: its first frame at 13.1 s (30 fps). With the
// far pieces' rule alone (0.04 x each box's distance) it would take twice as long.
TEST(AutoDuration, PiecesStrewnWideRestAtASpeedInProportionToTheirSpread) {
    BoxModelBuilder b(1000);
    const double r = 1.0, w = 2.0, half_diagonal = 0.05 * std::sqrt(3.0);
    for (int k = 0; k < 8; ++k) {
        const double a = k * M_PI / 4;
        b.box(Vec3(r * std::cos(a), 0.05, r * std::sin(a)), Vec3::Constant(0.1));
    }
    const Model m = b.take();
    SimulationInput in = dropped_plate();
    in.object.pose = Pose{};
    in.object.angular_velocity = Vec3(0, w, 0);
    in.material.surface = SurfaceSettings{0, 0};
    in.scene.ground_surface = SurfaceSettings{0, 0};
    in.simulate.max_duration = 30;
    const SimulationResult result = simulate(m, in, "test");
    ASSERT_TRUE(result.complete) << result.stop_reason;
    const Trajectory& t = result.trajectory;
    const double v = w * r;
    const double speed = double((t.pose(t.frames() - 1, 0).position - t.pose(t.frames() - 2, 0).position).norm()) * t.fps;
    EXPECT_NEAR(speed, v, 0.01);  // still sliding at the end: at rest by the spread, not stopped
    const double end = std::sqrt(std::pow((v + w * half_diagonal) / (2 * kRestSpeedPerSize), 2) - r * r) / v;
    EXPECT_NEAR(end, 13.573, 1e-3);
    const double first = std::ceil(end * in.simulate.fps) / in.simulate.fps - kRestHold;  // the hold's first frame
    EXPECT_NEAR(result.rest_time, first, 1.5 / in.simulate.fps);
}

TEST(AutoDuration, StopsAtTheCapWhenThePiecesDoNotRest) {
    SimulationInput in = dropped_plate();
    in.simulate.max_duration = 0.2;  // still falling at 0.2 s (lands at 0.25 s)
    const SimulationResult r = simulate(plate(), in, "test");
    EXPECT_EQ(r.trajectory.frames(), 7u);  // 0.2 s at 30 fps, frame 0 included
    EXPECT_LT(r.rest_time, 0);
}

TEST(AutoDuration, WithoutAutoTheDurationIsKept) {
    SimulationInput in = dropped_plate();
    in.simulate.auto_duration = false;
    in.simulate.duration = 0.5;
    const SimulationResult r = simulate(plate(), in, "test");
    EXPECT_EQ(r.trajectory.frames(), 16u);
    EXPECT_EQ(r.trajectory.settings_json.find("\"duration\":\"auto\""), std::string::npos) << r.trajectory.settings_json;
    EXPECT_EQ(r.trajectory.settings_json.find("max_duration"), std::string::npos) << r.trajectory.settings_json;
    EXPECT_NE(r.trajectory.settings_json.find("\"duration\":0.5"), std::string::npos) << r.trajectory.settings_json;
}

}  // namespace
}  // namespace shatter
