// The camera of every frame. A shot that places the camera (camera_position), or asks for
// camera = "whole", gets one fixed camera (render/camera.h make_camera). Otherwise the camera
// follows the event ("follow"): same view direction as the fixed camera (30 degrees right of +z,
// 22 degrees above the horizon; no cuts, the lights do not move), target and distance taken
// from the pieces of each frame and smoothed over the whole trajectory, computed once before
// any frame is drawn:
//
//   1. per frame, the box of the pieces' balls (centre of mass plus radius), the props' balls,
//      the finite static colliders and the ground point under the pieces (so the ground stays in
//      view); when at most a tenth of the pieces, the farthest from the median, more than double
//      the box's diagonal (a piece flying off), the box is taken without them;
//   2. the target: the box centres smoothed with a Hann window of +-kFollowWindow (symmetric:
//      looks ahead as far as back, so the camera starts to move before the landing);
//   3. the distance each frame needs so that those balls fall inside the inner 90% of the image
//      from the smoothed target; then the largest need within +-kFollowWindow, smoothed with the
//      same window. Every weight of the window lies within the span of the maximum, so the
//      smoothed distance is never less than the frame's need: the kept balls of every frame are
//      in view, and the path has no jitter (a frame's camera depends on the whole trajectory, not
//      on the range rendered).
#pragma once

#include <vector>

#include "render/camera.h"
#include "render/render.h"

namespace shatter {

inline constexpr double kFollowWindow = 0.5;  // half-width of the smoothing window (unit: s)

// What the follow camera is computed from: per frame, the balls to frame (pieces first, then
// props and static colliders) and whether a piece is one of them may be dropped as an outlier.
struct FollowInput {
    std::vector<std::vector<Ball>> frames;  // per frame: the pieces' balls, then the others
    uint32_t pieces = 0;                    // the first `pieces` balls of a frame are pieces
    bool ground = true;
    double ground_height = 0;  // (unit: m)
    double fps = 30;           // (unit: frames/s)
};
FollowInput follow_input(const RenderScene& scene);

// One camera per frame, from `bounds` (the whole animation: near and far planes).
std::vector<Camera> follow_cameras(const FollowInput& in, const Eigen::AlignedBox3d& bounds, const RenderSettings& s);

// The cameras of a render: one per frame when following, else a single fixed camera.
std::vector<Camera> make_camera_path(const RenderScene& scene, const RenderSettings& s);

// Whether a ball lies inside the view of `c` (its whole ball in the image, or `partly`: any of
// it).
bool ball_in_view(const Camera& c, const Ball& b, bool partly = false);

// What a render's cameras show, measured on the pieces' balls (centre of mass plus radius, so a
// slight over-estimate of each piece) projected through the camera of each frame.
struct CameraCoverage {
    std::vector<double> in_view;  // per frame: the fraction of the pieces wholly in view
    double first = 0;             // in_view of frame 0
    double least = 0;             // the smallest in_view
    uint32_t least_frame = 0;
    // The time at the end during which no corner of any piece's box (about its centre of mass,
    // turning with it) moves on screen by more than kStillPixels from one frame to the next
    // (camera motion included) (unit: s).
    double still_at_end = 0;
};
inline constexpr double kStillPixels = 0.5;
CameraCoverage camera_coverage(const RenderScene& scene, const RenderSettings& s);

}  // namespace shatter
