// The follow camera (render/camera_path.h) on made-up trajectories whose framing geometry
// predicts: a ball dropped from 1.5 m that lands and splits into ten pieces rolling apart, one of
// them flying far off. Every kept piece is in view in every frame, the first frame shows the
// whole object and the ground under it, the path never moves faster than what it follows (no
// cuts), and a shot's own camera is kept as it was.
#include <gtest/gtest.h>

#include <cmath>

#include "render/camera_path.h"

namespace shatter {
namespace {

constexpr double kFps = 30, kG = 9.81, kDrop = 1.5;
constexpr uint32_t kPieces = 10, kFrames = 90;

// Ten 3 cm balls that fall together from 1.5 m (landing at sqrt(2 x 1.5 / g) = 0.553 s), then
// spread along the ground at 0.3 m/s each in its own direction; piece 9 instead flies off at
// `fly` m/s (0: like the others).
FollowInput drop(double fly = 0) {
    FollowInput in;
    in.pieces = kPieces;
    in.fps = kFps;
    const double land = std::sqrt(2 * kDrop / kG);
    for (uint32_t f = 0; f < kFrames; ++f) {
        const double t = f / kFps;
        std::vector<Ball> balls;
        for (uint32_t i = 0; i < kPieces; ++i) {
            const double a = 2 * M_PI * i / kPieces;
            const Vec3 home(0.05 * std::cos(a), 0.03, 0.05 * std::sin(a));
            const double after = std::max(0.0, t - land);
            const double speed = (i == 9 && fly > 0) ? fly : 0.3;
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

TEST(FollowCamera, EveryPieceIsInViewInEveryFrameAndTheGroundAtTheStart) {
    const FollowInput in = drop();
    const std::vector<Camera> cams = follow_cameras(in, whole(in), hd());
    ASSERT_EQ(cams.size(), kFrames);
    for (uint32_t f = 0; f < kFrames; ++f)
        for (const Ball& b : in.frames[f]) EXPECT_TRUE(ball_in_view(cams[f], b)) << "frame " << f;
    // The ground point under the falling object is in view in the first frame.
    EXPECT_TRUE(ball_in_view(cams[0], {Vec3(0, 0, 0), 0.0}));
    // The fixed camera frames the whole fall from ~4.1 m; the follow camera is closer once the
    // pieces are down (1.7 m at the end, the pieces spread over 1.5 m): within half of it.
    const double end = (cams.back().position - cams.back().target).norm();
    const double fixed = (make_camera(whole(in), {}, hd()).position - whole(in).center().cast<float>()).norm();
    EXPECT_LT(end, 0.5 * fixed) << end << " vs " << fixed;
    std::printf("[ follow   ] distance: first frame %.3f m, last %.3f m; the fixed camera %.3f m\n",
                double((cams[0].position - cams[0].target).norm()), end, fixed);
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
    // No jitter: the target's acceleration stays within gravity's (the fastest change it follows)
    // scaled by the window (the landing's velocity jump of 5.4 m/s spread over +-0.5 s).
    double jerkiest = 0;
    for (uint32_t f = 1; f + 1 < kFrames; ++f)
        jerkiest = std::max(jerkiest, double((cams[f + 1].target - 2 * cams[f].target + cams[f - 1].target).norm()) *
                                          kFps * kFps);
    EXPECT_LT(jerkiest, 2 * kG);
    std::printf("[ follow   ] fastest target %.3f m/frame (pieces %.3f), largest acceleration %.2f m/s^2\n",
                fastest_target, fastest_piece, jerkiest);
}

TEST(FollowCamera, APieceFlyingOffIsLetGoRatherThanShrinkingTheRest) {
    const FollowInput calm = drop(), wild = drop(3.0);  // piece 9 at 3 m/s: 3 m off by the end
    const auto a = follow_cameras(calm, whole(wild), hd()), b = follow_cameras(wild, whole(wild), hd());
    const double da = (a.back().position - a.back().target).norm(), db = (b.back().position - b.back().target).norm();
    EXPECT_LT(db, 1.5 * da) << da << " vs " << db;
    for (uint32_t f = 0; f < kFrames; ++f)
        for (uint32_t i = 0; i < 9; ++i) EXPECT_TRUE(ball_in_view(b[f], wild.frames[f][i])) << f << " " << i;
    EXPECT_FALSE(ball_in_view(b.back(), wild.frames.back()[9], true));  // 3 m away: out of view
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
