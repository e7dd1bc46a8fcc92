// The camera of every frame. A shot that places the camera (camera_position), or asks for
// camera = "whole", gets one fixed camera (render/camera.h make_camera). Otherwise the camera
// follows the event ("follow"): same view direction as the fixed camera (30 degrees right of +z,
// 22 degrees above the horizon; no cuts, the lights do not move), target and distance taken
// from the pieces of each frame and smoothed over the whole trajectory, computed once before
// any frame is drawn:
//
//   1. per frame, what to frame: each piece's ball (centre of mass plus radius) or the corners
//      of its box (piece_box, turning with it), whichever fits nearer (either one in the image
//      has the piece in it); the props' balls; the finite static colliders; and the ground below
//      the pieces, at most kGroundReach object sizes below them (so the ground comes into view
//      before the landing, without framing the whole drop). Pieces may be let go: a piece
//      outside the main mass (main_mass: the pieces nearest the mass-weighted median holding 90%
//      of the mass) whose ball lies more than kLetGo of the main mass's box diagonal outside
//      that box, at most a tenth of the pieces, the farthest first; never in the first frame;
//   2. the target: the centres of the boxes around what is framed, smoothed with a Hann window
//      of +-kFollowWindow (symmetric: looks ahead as far as back, so the camera starts to slow
//      before the landing);
//   3. the distance each frame needs so that what it frames falls inside the inner 90% of the
//      image from the smoothed target; then the largest need within +-kFollowWindow, smoothed
//      with the same window. Every weight of the window lies within the span of the maximum, so
//      the smoothed distance is never less than the frame's need: the kept pieces of every frame
//      are in view (every piece in the first frame, at least 90% of them in every frame), and
//      the path has no jitter (a frame's camera depends on the whole trajectory, not on the
//      range rendered).
//
// Why: framing the ground point directly under the pieces in every frame (as this camera first
// did) framed a 0.2 m object dropped from 1.5 m with the whole drop below it, at about a tenth
// of the image; seen 22 degrees from above, the ground shows behind a falling object anyway, so
// only the ground near the pieces is framed, and the falling object fills about a third of the
// image. The ground at the bottom of the image is measured (camera_coverage), not enforced: at
// 35 to 40 degrees every frame measured has it; at 5 degrees, on a fall that stays in place, it
// lies a fifth of the way into the fade, and backing off until it did not took the camera from
// 3 m to 12 m. The window is 0.2 s (it was 0.5 s): smoothing the landing's kink puts the target
// about 0.15 x window x landing speed off the object, which the camera has to back off to hold;
// a shorter window stops harder (docs/render.md, "The follow camera").
#pragma once

#include <vector>

#include "render/camera.h"
#include "render/render.h"

namespace shatter {

inline constexpr double kFollowWindow = 0.2;  // half-width of the smoothing window (unit: s)
// The ground is framed at most this far below the pieces (unit: the object's size, the largest
// side of its pieces' box in the first frame).
inline constexpr double kGroundReach = 0.5;
// A piece this far outside the main mass's box may leave the frame (unit: that box's diagonal),
// at most kLetGoShare of the pieces in a frame.
inline constexpr double kLetGo = 0.5, kLetGoShare = 0.1;

// What the follow camera is computed from: per frame, the balls to frame (pieces first, then
// props and static colliders), and the pieces' masses (which pieces make the main mass).
struct FollowInput {
    std::vector<std::vector<Ball>> frames;  // per frame: the pieces' balls, then the others
    uint32_t pieces = 0;                    // the first `pieces` balls of a frame are pieces
    std::vector<double> mass;               // per piece (unit: kg); absent: all alike
    // Optional: per piece its box about its centre of mass (model axes), and per frame each
    // piece's rotation; with them a kept piece is framed by its box's corners, not by its ball.
    std::vector<Eigen::AlignedBox3d> boxes;
    std::vector<std::vector<Eigen::Quaterniond>> turns;  // [frame][piece]
    bool ground = true;
    double ground_height = 0;  // (unit: m)
    double fps = 30;           // (unit: frames/s)
};
FollowInput follow_input(const RenderScene& scene);

// A piece's box about its centre of mass (model axes): around its tet surface and its render
// surface, what is drawn of it; a point at the centre when it has neither.
Eigen::AlignedBox3d piece_box(const Piece& piece);
// The radius of the ball about its centre of mass that holds both surfaces (unit: m).
double piece_ball_radius(const Piece& piece);

// One camera per frame, from `bounds` (the whole animation: near and far planes).
std::vector<Camera> follow_cameras(const FollowInput& in, const Eigen::AlignedBox3d& bounds, const RenderSettings& s);

// The cameras of a render: one per frame when following, else a single fixed camera.
std::vector<Camera> make_camera_path(const RenderScene& scene, const RenderSettings& s);

// Whether a ball lies inside the view of `c` (its whole ball in the image, or `partly`: any of
// it).
bool ball_in_view(const Camera& c, const Ball& b, bool partly = false);

// The main mass of a frame: the pieces nearest the mass-weighted median of their centres (per
// axis; ties by index), taken until they hold kMainMass of the mass (of the count when the masses
// do not add up to a positive total). Indices ascending.
inline constexpr double kMainMass = 0.9;
std::vector<uint32_t> main_mass(const std::vector<Ball>& pieces, const std::vector<double>& mass);

// How large `balls` are on screen: the rectangle around their projections, its width as a
// fraction of the image's width or its height of the image's height, whichever is larger
// (1: the balls span the image from edge to edge; more when they reach beyond). A ball is taken
// as its centre's projection plus its radius at its centre's depth.
double screen_fill(const Camera& c, const std::vector<Ball>& balls);

// Where the ray through the midpoint of the image's bottom edge meets the ground at height
// `ground_height`, or false when it does not go down.
bool ground_at_bottom(const Camera& c, double ground_height, Vec3* at);

// What a render's cameras show, measured on the pieces' boxes (piece_box, turning with the piece)
// and balls (piece_ball_radius), each an over-estimate of the piece, projected through the camera
// of each frame.
struct CameraCoverage {
    std::vector<double> in_view;  // per frame: the share of the pieces whose whole box or ball is in view
    double first = 0;             // in_view of frame 0
    double least = 0;             // the smallest in_view
    uint32_t least_frame = 0;
    // The time at the end during which no corner of any piece's box (about its centre of mass,
    // turning with it) moves on screen by more than kStillPixels from one frame to the next
    // (camera motion included) (unit: s).
    double still_at_end = 0;
    // How large the main mass is on screen (screen_fill of the corners of its pieces' boxes about
    // their centres of mass, turning with them): per frame, its least and its median over the
    // frames (unit: fraction of the image's width or height, whichever the mass fills more).
    std::vector<double> fill;
    double fill_least = 0, fill_median = 0;
    uint32_t fill_least_frame = 0;
    // Frames in which the ground is not seen at the bottom of the image: the ray through the
    // bottom edge's midpoint meets no ground, or meets it where it has begun to fade (0 without
    // a ground).
    uint32_t frames_without_ground = 0;
};
inline constexpr double kStillPixels = 0.5;
CameraCoverage camera_coverage(const RenderScene& scene, const RenderSettings& s);

}  // namespace shatter
