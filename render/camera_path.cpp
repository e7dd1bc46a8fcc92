#include "render/camera_path.h"

#include <algorithm>
#include <cmath>

#include "render/scene_bounds.h"

namespace shatter {

namespace {

constexpr double kOutlierShare = 0.1;   // at most this share of the pieces may be left out
constexpr double kOutlierGrowth = 2.0;  // ... and only when they make the box this much larger

Eigen::AlignedBox3d box_of(const std::vector<Ball>& balls, const std::vector<bool>& keep) {
    Eigen::AlignedBox3d box;
    for (size_t i = 0; i < balls.size(); ++i)
        if (keep[i]) {
            box.extend(balls[i].centre - Vec3::Constant(balls[i].radius));
            box.extend(balls[i].centre + Vec3::Constant(balls[i].radius));
        }
    return box;
}

// Which balls of a frame are framed: all, or all but up to a tenth of the pieces, the farthest
// from the pieces' median centre, when those would more than double the box's diagonal.
std::vector<bool> kept_balls(const std::vector<Ball>& balls, uint32_t pieces) {
    std::vector<bool> keep(balls.size(), true);
    const size_t drop = size_t(std::floor(kOutlierShare * pieces));
    if (drop == 0) return keep;
    Vec3 median;
    for (int axis = 0; axis < 3; ++axis) {
        std::vector<double> v;
        for (uint32_t i = 0; i < pieces; ++i) v.push_back(balls[i].centre[axis]);
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        median[axis] = v[v.size() / 2];
    }
    std::vector<uint32_t> order(pieces);
    for (uint32_t i = 0; i < pieces; ++i) order[i] = i;
    auto reach = [&](uint32_t i) { return (balls[i].centre - median).norm() + balls[i].radius; };
    // Farthest first; ties by index, so the choice is the same on every machine.
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        const double ra = reach(a), rb = reach(b);
        return ra != rb ? ra > rb : a < b;
    });
    std::vector<bool> trimmed = keep;
    for (size_t k = 0; k < drop; ++k) trimmed[order[k]] = false;
    const double all = box_of(balls, keep).sizes().norm(), rest = box_of(balls, trimmed).sizes().norm();
    return all > kOutlierGrowth * rest ? trimmed : keep;
}

// Symmetric Hann window of half-width `w` frames (weights sum to 1), applied with the ends held.
template <typename T>
std::vector<T> smooth(const std::vector<T>& x, int w) {
    if (w < 1 || x.empty()) return x;
    std::vector<double> weight(size_t(2 * w + 1));
    double sum = 0;
    for (int k = -w; k <= w; ++k) sum += weight[size_t(k + w)] = 0.5 * (1 + std::cos(M_PI * k / (w + 1)));
    const int n = int(x.size());
    std::vector<T> out(x.size());
    for (int f = 0; f < n; ++f) {
        T acc = x[0] * 0.0;
        for (int k = -w; k <= w; ++k) acc = acc + x[size_t(std::clamp(f + k, 0, n - 1))] * (weight[size_t(k + w)] / sum);
        out[size_t(f)] = acc;
    }
    return out;
}

}  // namespace

FollowInput follow_input(const RenderScene& scene) {
    FollowInput in;
    const Trajectory& t = *scene.trajectory;
    in.pieces = t.pieces;
    in.ground = scene.scene.ground;
    in.ground_height = scene.scene.ground_height;
    in.fps = t.fps;
    std::vector<double> radius(t.bodies(), 0.0);
    for (uint32_t i = 0; i < t.pieces; ++i) radius[i] = piece_radius(scene.model->pieces[i]);
    for (uint32_t k = 0; k < t.props; ++k) radius[t.pieces + k] = shape_radius(scene.scene.kinematic[k].shape);
    std::vector<Ball> statics;
    for (const ColliderSettings& c : scene.scene.colliders)
        if (c.shape.kind == ShapeKind::Box || c.shape.kind == ShapeKind::Sphere)
            statics.push_back({c.pose.position, shape_radius(c.shape)});
    in.frames.resize(t.frames());
    for (uint32_t f = 0; f < t.frames(); ++f) {
        std::vector<Ball>& balls = in.frames[f];
        for (uint32_t b = 0; b < t.bodies(); ++b) balls.push_back({t.pose(f, b).position.cast<double>(), radius[b]});
        balls.insert(balls.end(), statics.begin(), statics.end());
    }
    return in;
}

std::vector<Camera> follow_cameras(const FollowInput& in, const Eigen::AlignedBox3d& bounds, const RenderSettings& s) {
    const size_t n = in.frames.size();
    const double tan_v = std::tan(s.fov * M_PI / 360), tan_h = tan_v * double(s.width) / s.height;
    const Vec3 dir = auto_view_direction();
    const Vec3 right = Vec3(0, 1, 0).cross(dir).normalized(), up = dir.cross(right);
    const int window = std::max(1, int(std::lround(kFollowWindow * in.fps)));

    // 1. Per frame: the balls framed (the kept ones and the ground point under them), their box.
    std::vector<std::vector<Ball>> framed(n);
    std::vector<Vec3> centres(n);
    for (size_t f = 0; f < n; ++f) {
        const std::vector<Ball>& balls = in.frames[f];
        const std::vector<bool> keep = kept_balls(balls, in.pieces);
        for (size_t i = 0; i < balls.size(); ++i)
            if (keep[i]) framed[f].push_back(balls[i]);
        Eigen::AlignedBox3d box = box_of(balls, keep);
        if (box.isEmpty()) box.extend(Vec3::Zero());
        if (in.ground) {
            const Vec3 contact(box.center().x(), in.ground_height, box.center().z());
            framed[f].push_back({contact, 0.0});
            box.extend(contact);
        }
        centres[f] = box.center();
    }
    // 2. The target: the centres smoothed.
    const std::vector<Vec3> targets = smooth(centres, window);
    // 3. The distance each frame needs from its target; the window's largest need, smoothed.
    std::vector<double> need(n, 0.0);
    for (size_t f = 0; f < n; ++f) {
        // At least 10 cm across is framed, as animation_bounds does.
        double d = 0.05 / (kAutoFill * tan_v);
        for (const Ball& b : framed[f]) {
            const Vec3 q = b.centre - targets[f];
            const double depth = q.dot(dir);
            d = std::max(d, depth + (std::abs(q.dot(right)) + b.radius) / (kAutoFill * tan_h));
            d = std::max(d, depth + (std::abs(q.dot(up)) + b.radius) / (kAutoFill * tan_v));
        }
        need[f] = d;
    }
    std::vector<double> widest(n, 0.0);
    for (size_t f = 0; f < n; ++f)
        for (int k = -window; k <= window; ++k) {
            const long g = long(f) + k;
            if (g >= 0 && g < long(n)) widest[f] = std::max(widest[f], need[size_t(g)]);
        }
    const std::vector<double> distance = smooth(widest, window);
    std::vector<Camera> cameras;
    cameras.reserve(n);
    for (size_t f = 0; f < n; ++f)
        cameras.push_back(camera_looking(targets[f] + dir * distance[f], targets[f], bounds, s));
    return cameras;
}

std::vector<Camera> make_camera_path(const RenderScene& scene, const RenderSettings& s) {
    const std::vector<Ball> balls = animation_balls(scene);
    const Eigen::AlignedBox3d bounds = animation_bounds(balls);
    if (s.camera_position || s.camera == CameraMode::Whole || scene.trajectory->frames() == 0)
        return {make_camera(bounds, balls, s)};
    return follow_cameras(follow_input(scene), bounds, s);
}

bool ball_in_view(const Camera& c, const Ball& b, bool partly) {
    const Eigen::Vector3d p = (c.view.cast<double>() * b.centre.homogeneous()).head<3>();
    const double depth = -p.z();
    const double tan_h = 1 / double(c.projection(0, 0)), tan_v = 1 / double(c.projection(1, 1));
    const double r = partly ? -b.radius : b.radius;
    // Distance inside each side plane of the frustum, against the ball's radius.
    const double inside_h = (depth * tan_h - std::abs(p.x())) / std::sqrt(1 + tan_h * tan_h);
    const double inside_v = (depth * tan_v - std::abs(p.y())) / std::sqrt(1 + tan_v * tan_v);
    return depth > r && inside_h >= r && inside_v >= r;
}

CameraCoverage camera_coverage(const RenderScene& scene, const RenderSettings& s) {
    CameraCoverage out;
    const Trajectory& t = *scene.trajectory;
    const std::vector<Camera> cameras = make_camera_path(scene, s);
    auto camera = [&](uint32_t f) -> const Camera& { return cameras[cameras.size() > 1 ? f : 0]; };
    std::vector<double> radius(t.pieces);
    for (uint32_t i = 0; i < t.pieces; ++i) radius[i] = piece_radius(scene.model->pieces[i]);
    // Where a point of piece i (about its centre of mass, model axes) lands in frame f (unit: px).
    auto pixel = [&](uint32_t f, uint32_t i, const Vec3& local) {
        const BodyPose& pose = t.pose(f, i);
        const Vec3 world = pose.rotation.cast<double>().normalized() * local + pose.position.cast<double>();
        const Eigen::Vector4d p = (camera(f).projection * camera(f).view).cast<double>() * world.homogeneous();
        return Eigen::Vector2d((p.x() / p.w() * 0.5 + 0.5) * s.width, (p.y() / p.w() * 0.5 + 0.5) * s.height);
    };
    // Each piece's motion is watched at the corners of its box about its centre of mass, so that
    // a piece that turns in place (a slab rocking) counts as moving.
    std::vector<std::vector<Vec3>> corners(t.pieces);
    for (uint32_t i = 0; i < t.pieces && i < scene.model->pieces.size(); ++i) {
        const Piece& piece = scene.model->pieces[i];
        Eigen::AlignedBox3d box;
        for (const Vec3& v : piece.surface.vertices) box.extend(v - piece.mass.center);
        if (box.isEmpty()) box.extend(Vec3::Zero());
        for (int k = 0; k < 8; ++k) corners[i].push_back(box.corner(Eigen::AlignedBox3d::CornerType(k)));
    }
    out.least = 1;
    for (uint32_t f = 0; f < t.frames(); ++f) {
        uint32_t seen = 0;
        for (uint32_t i = 0; i < t.pieces; ++i)
            if (ball_in_view(camera(f), {t.pose(f, i).position.cast<double>(), radius[i]})) ++seen;
        const double share = t.pieces ? double(seen) / t.pieces : 1.0;
        out.in_view.push_back(share);
        if (share < out.least) out.least = share, out.least_frame = f;
    }
    out.first = out.in_view.empty() ? 1.0 : out.in_view.front();
    uint32_t still = 0;
    for (uint32_t f = t.frames(); f-- > 1;) {
        bool moved = false;
        for (uint32_t i = 0; i < t.pieces && !moved; ++i)
            for (const Vec3& q : corners[i]) moved = moved || (pixel(f, i, q) - pixel(f - 1, i, q)).norm() > kStillPixels;
        if (moved) break;
        ++still;
    }
    out.still_at_end = still / t.fps;
    return out;
}

}  // namespace shatter
