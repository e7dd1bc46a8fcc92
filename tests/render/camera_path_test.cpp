// The follow camera (render/camera_path.h) on made-up trajectories whose framing geometry
// predicts: a ball dropped from 1.5 m that lands and splits into ten pieces rolling apart, one of
// them flying far off. Every kept piece is in view in every frame, the first frame shows the
// whole object, the ground is seen at the bottom of every frame, the falling object fills a third
// of the image, the path never moves faster than what it follows (no cuts) and smooths out what
// shakes (no jitter), a small piece flying off leaves the frame rather than shrinking the rest,
// and a shot's own camera is kept as it was.
#include <gtest/gtest.h>

#include <cmath>

#include "render/camera_path.h"
#include "scenes/render_test_scene.h"

namespace shatter {
namespace {

constexpr double kFps = 30, kG = 9.81, kDrop = 1.5;
constexpr uint32_t kPieces = 10, kFrames = 90;

// Ten 3 cm balls of 1 kg that fall together from 1.5 m (landing at sqrt(2 x 1.5 / g) = 0.553 s),
// then spread along the ground at 0.3 m/s each in its own direction; piece 9 (of `fly_mass` kg)
// instead flies off at `fly` m/s (0: like the others). `pieces` below 10 leaves out the last.
FollowInput drop(double fly = 0, double fly_mass = 1, uint32_t pieces = kPieces) {
    FollowInput in;
    in.pieces = pieces;
    in.fps = kFps;
    in.mass.assign(pieces, 1.0);
    in.mass[9 % pieces] = fly_mass;
    const double land = std::sqrt(2 * kDrop / kG);
    for (uint32_t f = 0; f < kFrames; ++f) {
        const double t = f / kFps;
        std::vector<Ball> balls;
        for (uint32_t i = 0; i < pieces; ++i) {
            const double a = 2 * M_PI * i / kPieces;
            const Vec3 home(0.05 * std::cos(a), 0.03, 0.05 * std::sin(a));
            const double after = std::max(0.0, t - land);
            const double speed = (i == 9 % pieces && fly > 0) ? fly : 0.3;
            Vec3 c = home + Vec3(std::cos(a), 0, std::sin(a)) * speed * after;
            if (t < land) c.y() += kDrop - 0.5 * kG * t * t;
            balls.push_back({c, 0.03});
        }
        in.frames.push_back(balls);
    }
    return in;
}

Eigen::AlignedBox3d whole(const FollowInput& in) {
    std::vector<Ball> all;
    for (const auto& f : in.frames) all.insert(all.end(), f.begin(), f.end());
    return animation_bounds(all);
}

RenderSettings hd() {
    RenderSettings s;
    s.fov = 40;
    return s;
}

// The ground is seen at the bottom of a frame when the ray through the bottom edge's middle meets
// it before it begins to fade (kFadeStart half-diagonals of the animation's box from its centre).
bool ground_seen(const Camera& c, const Eigen::AlignedBox3d& bounds) {
    Vec3 at;
    if (!ground_at_bottom(c, 0, &at)) return false;
    return Eigen::Vector2d(at.x() - bounds.center().x(), at.z() - bounds.center().z()).norm() <=
           kFadeStart * bounds.sizes().norm() / 2;
}

TEST(FollowCamera, EveryPieceInViewTheGroundAtTheBottomAndTheFallingObjectLarge) {
    const FollowInput in = drop();
    const std::vector<Camera> cams = follow_cameras(in, whole(in), hd());
    ASSERT_EQ(cams.size(), kFrames);
    const uint32_t landing = uint32_t(std::sqrt(2 * kDrop / kG) * kFps);  // frame 16
    double least_falling = 1, least_after = 1;
    for (uint32_t f = 0; f < kFrames; ++f) {
        for (const Ball& b : in.frames[f]) EXPECT_TRUE(ball_in_view(cams[f], b)) << "frame " << f;
        EXPECT_TRUE(ground_seen(cams[f], whole(in))) << "frame " << f;
        const double fill = screen_fill(cams[f], in.frames[f]);
        (f <= landing ? least_falling : least_after) = std::min(f <= landing ? least_falling : least_after, fill);
    }
    // The object is 0.16 m across (a 5 cm ring of 3 cm balls). In the first frame the camera
    // frames it and half its size of air below (kGroundReach): it fills over 30% of the image.
    // Nearer the landing the target lags: the landing's kink in the path (5.4 m/s to rest)
    // smoothed over +-kFollowWindow puts the target 0.149 x 0.2 s x 5.4 m/s = 0.16 m above the
    // object as it lands, and the camera backs off to hold it: still over a quarter of the image.
    // The fixed camera, which holds the whole 1.6 m fall, shows it at an eighth of that.
    const Camera fixed = make_camera(whole(in), {}, hd());
    const double first = screen_fill(cams[0], in.frames[0]);
    EXPECT_GT(first, 0.3);
    EXPECT_GT(least_falling, 0.25);
    EXPECT_LT(screen_fill(fixed, in.frames[0]), least_falling / 7);
    // The fixed camera frames the whole fall from ~4.1 m; the follow camera is closer once the
    // pieces are down (1.7 m at the end, the pieces spread over 1.5 m): within half of it.
    const double end = (cams.back().position - cams.back().target).norm();
    const double far = (fixed.position - whole(in).center().cast<float>()).norm();
    EXPECT_LT(end, 0.5 * far) << end << " vs " << far;
    std::printf("[ follow   ] distance: first frame %.3f m, last %.3f m; the fixed camera %.3f m; the object fills "
                "%.3f of the image in the first frame, at least %.3f while it falls (the fixed camera %.3f), %.3f "
                "after\n",
                double((cams[0].position - cams[0].target).norm()), end, far, first, least_falling,
                screen_fill(fixed, in.frames[0]), least_after);
}

TEST(FollowCamera, TheDirectionNeverChangesAndThePathIsSmooth) {
    const FollowInput in = drop();
    const std::vector<Camera> cams = follow_cameras(in, whole(in), hd());
    const Eigen::Vector3f dir = auto_view_direction().cast<float>();
    double fastest_piece = 0, fastest_target = 0;
    for (uint32_t f = 0; f < kFrames; ++f) {
        const Eigen::Vector3f back = (cams[f].position - cams[f].target).normalized();
        EXPECT_NEAR((back - dir).norm(), 0, 1e-5) << f;  // no cuts, no turning
        if (f == 0) continue;
        // Smoothing with positive weights never moves the target farther in a frame than the
        // pieces' box centre moved in some frame; it also spreads the landing's kink.
        fastest_target = std::max(fastest_target, double((cams[f].target - cams[f - 1].target).norm()));
        for (uint32_t i = 0; i < kPieces; ++i)
            fastest_piece = std::max(fastest_piece, (in.frames[f][i].centre - in.frames[f - 1][i].centre).norm());
    }
    EXPECT_LE(fastest_target, fastest_piece);
    // No jolt: the target's acceleration stays within the landing's kink (sqrt(2 g h) = 5.4 m/s
    // to rest) spread over the window: 5.4 m/s / kFollowWindow = 27 m/s^2.
    double jerkiest = 0;
    for (uint32_t f = 1; f + 1 < kFrames; ++f)
        jerkiest = std::max(jerkiest, double((cams[f + 1].target - 2 * cams[f].target + cams[f - 1].target).norm()) *
                                          kFps * kFps);
    EXPECT_LT(jerkiest, std::sqrt(2 * kG * kDrop) / kFollowWindow);
    std::printf("[ follow   ] fastest target %.3f m/frame (pieces %.3f), largest acceleration %.2f m/s^2\n",
                fastest_target, fastest_piece, jerkiest);
}

// A piece of 1% of the mass flying off at 3 m/s (3 m away by the end) leaves the frame once it
// is half the main mass's box diagonal outside that box: the main mass then fills the image as
// if the piece had stayed with the others, and 9 of 10 pieces stay in view.
TEST(FollowCamera, ASmallPieceFlyingOffIsLetGoRatherThanShrinkingTheRest) {
    const FollowInput calm = drop(), wild = drop(3.0, 0.1);
    const auto a = follow_cameras(calm, whole(wild), hd()), b = follow_cameras(wild, whole(wild), hd());
    const std::vector<Ball> rest_a(calm.frames.back().begin(), calm.frames.back().begin() + 9),
        rest_b(wild.frames.back().begin(), wild.frames.back().begin() + 9);
    const double fill_a = screen_fill(a.back(), rest_a), fill_b = screen_fill(b.back(), rest_b);
    EXPECT_GT(fill_b, 0.9 * fill_a) << fill_a << " vs " << fill_b;
    for (const Ball& ball : wild.frames[0]) EXPECT_TRUE(ball_in_view(b[0], ball));
    for (uint32_t f = 0; f < kFrames; ++f)
        for (uint32_t i = 0; i < 9; ++i) EXPECT_TRUE(ball_in_view(b[f], wild.frames[f][i])) << f << " " << i;
    EXPECT_FALSE(ball_in_view(b.back(), wild.frames.back()[9], true));  // 3 m away: out of view
    std::printf("[ follow   ] the nine others fill %.3f of the image at the end (%.3f when the tenth stays with "
                "them)\n", fill_b, fill_a);
}

// What may not be let go: a heavy piece (it is part of the main mass), and any piece when fewer
// than ten make up the object (one piece would be more than a tenth of them).
TEST(FollowCamera, AHeavyPieceOrOneOfFewerThanTenStaysInView) {
    for (const FollowInput& in : {drop(3.0, 3.0), drop(3.0, 0.1, 9)}) {
        const auto cams = follow_cameras(in, whole(in), hd());
        for (uint32_t f = 0; f < kFrames; ++f)
            for (const Ball& ball : in.frames[f]) EXPECT_TRUE(ball_in_view(cams[f], ball)) << in.pieces << " " << f;
    }
}

// Pieces at rest that shake by up to 2 mm from frame to frame (a simulation's contact noise):
// the target and the distance move less than a tenth of that from frame to frame.
TEST(FollowCamera, ShakingPiecesDoNotShakeTheCamera) {
    FollowInput in = drop();
    uint32_t state = 1;
    auto noise = [&] {  // deterministic, uniform in [-1, 1]
        state = state * 1664525u + 1013904223u;
        return double(state >> 8) / double(1u << 23) - 1;
    };
    for (auto& frame : in.frames)
        for (uint32_t i = 0; i < kPieces; ++i) {
            const double a = 2 * M_PI * i / kPieces;
            const Vec3 shake(noise(), noise(), noise());
            frame[i].centre = Vec3(0.1 * std::cos(a), 0.03, 0.1 * std::sin(a)) + shake * 0.002;
        }
    const auto cams = follow_cameras(in, whole(in), hd());
    double target = 0, distance = 0, centre = 0;
    for (uint32_t f = 1; f + 1 < kFrames; ++f) {
        target = std::max(target, double((cams[f + 1].target - 2 * cams[f].target + cams[f - 1].target).norm()));
        auto d = [&](uint32_t g) { return double((cams[g].position - cams[g].target).norm()); };
        distance = std::max(distance, std::abs(d(f + 1) - 2 * d(f) + d(f - 1)));
        const Vec3 second = in.frames[f + 1][0].centre - 2 * in.frames[f][0].centre + in.frames[f - 1][0].centre;
        centre = std::max(centre, second.norm());
    }
    EXPECT_LT(target, 0.1 * centre);
    EXPECT_LT(distance, 0.1 * centre);
    std::printf("[ follow   ] shaking pieces: second differences %.2g m (a piece), %.2g m (target), %.2g m "
                "(distance)\n", centre, target, distance);
}

TEST(FollowCamera, ScreenFillAndMainMassMatchTheirGeometry) {
    RenderSettings s = hd();
    s.camera_position = Vec3(0, 0, 2);
    s.camera_target = Vec3(0, 0, 0);
    const Camera c = make_camera(Eigen::AlignedBox3d(Vec3(-1, -1, -1), Vec3(1, 1, 1)), {}, s);
    // A 0.1 m ball 2 m off: 0.1 / (2 tan 20 deg) = 0.137 of the height, 0.077 of the width.
    EXPECT_NEAR(screen_fill(c, {{Vec3(0, 0, 0), 0.1}}), 0.1 / (2 * std::tan(20 * M_PI / 180)), 1e-6);
    // Two points 1 m apart across: 1 / (2 x 2 tan 20 deg x 16 / 9) = 0.386 of the width.
    EXPECT_NEAR(screen_fill(c, {{Vec3(-0.5, 0, 0), 0}, {Vec3(0.5, 0, 0), 0}}),
                1 / (4 * std::tan(20 * M_PI / 180) * 1280 / 720), 1e-6);
    // Ten 1 kg pieces and one of 0.5 kg far off: the ten hold 95%, the nearest nine 86% < 90%.
    std::vector<Ball> pieces;
    std::vector<double> mass;
    for (int i = 0; i < 10; ++i) pieces.push_back({Vec3(0.01 * i, 0, 0), 0.01}), mass.push_back(1);
    pieces.push_back({Vec3(5, 0, 0), 0.01});
    mass.push_back(0.5);
    EXPECT_EQ(main_mass(pieces, mass).size(), 10u);
    mass.back() = 5;  // now a third of the mass: the main mass must reach it
    EXPECT_EQ(main_mass(pieces, mass).size(), 11u);
    // No masses to go by: by count, 10 of 11 reach 90%.
    EXPECT_EQ(main_mass(pieces, std::vector<double>(11, 0.0)).size(), 10u);
}

// camera_coverage on the golden test scene (two pieces of a 10 cm cube flying apart beside a
// sphere and a post): both pieces in view in every frame (none may be let go with two), the
// ground at the bottom of every frame, and the fill as screen_fill of the pieces' box corners.
TEST(FollowCamera, CoverageOfTheTestScene) {
    testing_support::TestScene t;
    const RenderScene scene = t.scene();
    const RenderSettings s = testing_support::small_render_settings();
    const CameraCoverage c = camera_coverage(scene, s);
    ASSERT_EQ(c.in_view.size(), t.trajectory.frames());
    EXPECT_EQ(c.first, 1.0);
    EXPECT_EQ(c.least, 1.0);
    EXPECT_EQ(c.frames_without_ground, 0u);
    ASSERT_EQ(c.fill.size(), t.trajectory.frames());
    EXPECT_LE(c.fill_least, c.fill_median);
    // Frame 0: the two pieces at rest, their boxes about their centres of mass, unturned.
    const std::vector<Camera> cams = make_camera_path(scene, s);
    std::vector<Ball> corners;
    for (uint32_t i = 0; i < t.trajectory.pieces; ++i) {
        const Piece& piece = t.model.pieces[i];
        Eigen::AlignedBox3d box;
        for (const Vec3& v : piece.surface.vertices) box.extend(v - piece.mass.center);
        const BodyPose& pose = t.trajectory.pose(0, i);
        const Eigen::Quaterniond r = pose.rotation.cast<double>().normalized();
        for (int k = 0; k < 8; ++k)
            corners.push_back({r * box.corner(Eigen::AlignedBox3d::CornerType(k)) + pose.position.cast<double>(), 0.0});
    }
    EXPECT_NEAR(c.fill[0], screen_fill(cams[0], corners), 1e-9);
    std::printf("[ follow   ] test scene: fill %.3f at the least (frame %u), %.3f in the median frame\n", c.fill_least,
                c.fill_least_frame, c.fill_median);
}

// A 1 m rod, 2 cm thick, lying still along x: its ball (radius 0.5 m) needs the camera 1.5 m
// off for the image's height (0.5 / (0.9 tan 20 deg)); its box's corners fit the image's width
// (16:9) much nearer. With its box the camera takes the nearer fit, and the box is in view.
TEST(FollowCamera, APieceIsFramedByItsBoxWhenThatFitsNearer) {
    FollowInput in;
    in.pieces = 1;
    in.fps = kFps;
    in.ground = false;
    in.frames.assign(10, {{Vec3(0, 1, 0), 0.5}});
    const Eigen::AlignedBox3d whole_box(Vec3(-0.5, 0.5, -0.5), Vec3(0.5, 1.5, 0.5));
    const auto by_ball = follow_cameras(in, whole_box, hd());
    in.boxes = {Eigen::AlignedBox3d(Vec3(-0.5, -0.01, -0.01), Vec3(0.5, 0.01, 0.01))};
    in.turns.assign(10, {Eigen::Quaterniond::Identity()});
    const auto by_box = follow_cameras(in, whole_box, hd());
    const double ball = (by_ball[0].position - by_ball[0].target).norm();
    const double box = (by_box[0].position - by_box[0].target).norm();
    EXPECT_NEAR(ball, 0.5 / (0.9 * std::tan(20 * M_PI / 180)), 1e-4);
    EXPECT_LT(box, 0.7 * ball);
    for (int k = 0; k < 8; ++k) {
        const Vec3 corner = in.boxes[0].corner(Eigen::AlignedBox3d::CornerType(k)) + Vec3(0, 1, 0);
        EXPECT_TRUE(ball_in_view(by_box[0], {corner, 0}));
    }
    std::printf("[ follow   ] a 1 m rod: the camera %.3f m off by its ball, %.3f m by its box\n", ball, box);
}

TEST(FollowCamera, BallInViewMatchesTheFrustum) {
    RenderSettings s = hd();
    s.camera_position = Vec3(0, 0, 2);
    s.camera_target = Vec3(0, 0, 0);
    const Camera c = make_camera(Eigen::AlignedBox3d(Vec3(-1, -1, -1), Vec3(1, 1, 1)), {}, s);
    // At 2 m, the vertical half-height is 2 tan(20 deg) = 0.728 m; a 0.1 m ball's centre may go to
    // 0.728 - 0.1 / cos(20 deg) = 0.621 m and stay wholly inside.
    EXPECT_TRUE(ball_in_view(c, {Vec3(0, 0.62, 0), 0.1}));
    EXPECT_FALSE(ball_in_view(c, {Vec3(0, 0.63, 0), 0.1}));
    EXPECT_TRUE(ball_in_view(c, {Vec3(0, 0.82, 0), 0.1}, true));   // partly: to 0.728 + 0.106
    EXPECT_FALSE(ball_in_view(c, {Vec3(0, 0.84, 0), 0.1}, true));
    EXPECT_FALSE(ball_in_view(c, {Vec3(0, 0, 3), 0.1}, true));     // behind the eye
}

}  // namespace
}  // namespace shatter
