#include "render/camera_path.h"

#include <algorithm>
#include <cmath>

#include "render/scene_bounds.h"

namespace shatter {

namespace {

Eigen::AlignedBox3d box_of(const std::vector<Ball>& balls, const std::vector<bool>& keep) {
    Eigen::AlignedBox3d box;
    for (size_t i = 0; i < balls.size(); ++i)
        if (keep[i]) {
            box.extend(balls[i].centre - Vec3::Constant(balls[i].radius));
            box.extend(balls[i].centre + Vec3::Constant(balls[i].radius));
        }
    return box;
}

// Which balls of a frame are framed: all but the pieces let go. A piece is let go when it lies
// outside the main mass (main_mass), its ball more than kLetGo diagonals of the main mass's box
// away from that box, and it is among the kLetGoShare of the pieces farthest from that box.
std::vector<bool> kept_balls(const std::vector<Ball>& balls, const std::vector<double>& mass, uint32_t pieces) {
    std::vector<bool> keep(balls.size(), true);
    const size_t most = size_t(std::floor(kLetGoShare * pieces + 1e-9));
    if (most == 0) return keep;
    const std::vector<Ball> piece_balls(balls.begin(), balls.begin() + pieces);
    std::vector<bool> in_main(pieces, false);
    for (uint32_t i : main_mass(piece_balls, mass)) in_main[i] = true;
    const Eigen::AlignedBox3d box = box_of(piece_balls, in_main);
    const double diagonal = box.sizes().norm();
    std::vector<std::pair<double, uint32_t>> far;  // (distance of the ball outside the box, piece)
    for (uint32_t i = 0; i < pieces; ++i) {
        const double gap = box.exteriorDistance(balls[i].centre) - balls[i].radius;
        if (!in_main[i] && gap > kLetGo * diagonal) far.push_back({gap, i});
    }
    // Farthest first; ties by index, so the choice is the same on every machine.
    std::sort(far.begin(), far.end(), [](const auto& a, const auto& b) {
        return a.first != b.first ? a.first > b.first : a.second < b.second;
    });
    for (size_t k = 0; k < far.size() && k < most; ++k) keep[far[k].second] = false;
    return keep;
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

Eigen::AlignedBox3d piece_box(const Piece& piece) {
    Eigen::AlignedBox3d box;
    for (const Vec3& v : piece.surface.vertices) box.extend(v - piece.mass.center);
    if (piece.render)
        for (const Vec3& v : piece.render->vertices) box.extend(v - piece.mass.center);
    if (box.isEmpty()) box.extend(Vec3::Zero());
    return box;
}

double piece_ball_radius(const Piece& piece) {
    double r = piece_radius(piece);
    if (piece.render)
        for (const Vec3& v : piece.render->vertices) r = std::max(r, (v - piece.mass.center).norm());
    return r;
}

FollowInput follow_input(const RenderScene& scene) {
    FollowInput in;
    const Trajectory& t = *scene.trajectory;
    in.pieces = t.pieces;
    in.ground = scene.scene.ground;
    in.ground_height = scene.scene.ground_height;
    in.fps = t.fps;
    for (uint32_t i = 0; i < t.pieces; ++i) {
        const Piece& piece = scene.model->pieces[i];
        in.mass.push_back(piece.mass.mass);
        in.boxes.push_back(piece_box(piece));
    }
    in.turns.resize(t.frames());
    for (uint32_t f = 0; f < t.frames(); ++f)
        for (uint32_t i = 0; i < t.pieces; ++i)
            in.turns[f].push_back(t.pose(f, i).rotation.cast<double>().normalized());
    std::vector<double> radius(t.bodies(), 0.0);
    for (uint32_t i = 0; i < t.pieces; ++i) radius[i] = piece_ball_radius(scene.model->pieces[i]);
    const std::vector<KinematicSettings> props = scene_props(scene.scene);
    for (uint32_t k = 0; k < t.props; ++k) radius[t.pieces + k] = shape_radius(props[k].shape);
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

    std::vector<double> mass = in.mass;
    mass.resize(in.pieces, 1.0);

    // 1. Per frame: the balls framed (the kept ones, and the ground below them down to
    // kGroundReach object sizes), their box. The first frame keeps every piece.
    double size = 0;  // the object's size: the largest side of its pieces' box in the first frame (unit: m)
    if (n > 0 && in.pieces > 0) {
        const std::vector<Ball> first(in.frames[0].begin(), in.frames[0].begin() + in.pieces);
        size = box_of(first, std::vector<bool>(in.pieces, true)).sizes().maxCoeff();
    }
    // What is framed of a body: its ball, and for a piece with a box, the box's eight corners
    // too; either one wholly in the image has the body in it, so the nearer fit counts.
    struct Framed {
        Ball ball;
        std::vector<Vec3> corners;  // empty: the ball alone
    };
    const bool with_boxes = in.boxes.size() == in.pieces && in.turns.size() == n;
    std::vector<std::vector<Framed>> framed(n);
    std::vector<Vec3> centres(n);
    for (size_t f = 0; f < n; ++f) {
        const std::vector<Ball>& balls = in.frames[f];
        const std::vector<bool> keep =
            f == 0 ? std::vector<bool>(balls.size(), true) : kept_balls(balls, mass, in.pieces);
        Eigen::AlignedBox3d box;
        for (size_t i = 0; i < balls.size(); ++i) {
            if (!keep[i]) continue;
            Framed item{balls[i], {}};
            Eigen::AlignedBox3d around(balls[i].centre - Vec3::Constant(balls[i].radius),
                                       balls[i].centre + Vec3::Constant(balls[i].radius));
            if (with_boxes && i < in.pieces && in.turns[f].size() == in.pieces) {
                Eigen::AlignedBox3d of_corners;
                for (int k = 0; k < 8; ++k) {
                    const Vec3 corner = in.boxes[i].corner(Eigen::AlignedBox3d::CornerType(k));
                    item.corners.push_back(in.turns[f][i] * corner + balls[i].centre);
                    of_corners.extend(item.corners.back());
                }
                around = around.intersection(of_corners);  // both hold the piece
            }
            box.extend(around);
            framed[f].push_back(item);
        }
        if (box.isEmpty()) box.extend(Vec3::Zero());
        if (in.ground) {
            const double below = std::max(in.ground_height, box.min().y() - kGroundReach * size);
            const Vec3 ground(box.center().x(), std::min(below, box.min().y()), box.center().z());
            framed[f].push_back({{ground, 0.0}, {}});
            box.extend(ground);
        }
        centres[f] = box.center();
    }
    // 2. The target: the centres smoothed.
    const std::vector<Vec3> targets = smooth(centres, window);
    // 3. The distance each frame needs from its target; the window's largest need, smoothed.
    std::vector<double> need(n, 0.0);
    for (size_t f = 0; f < n; ++f) {
        // The distance at which a ball about `q` (from the target) fills the inner 90% at most.
        auto fit = [&](const Vec3& q, double radius) {
            const double depth = q.dot(dir);
            return std::max(depth + (std::abs(q.dot(right)) + radius) / (kAutoFill * tan_h),
                            depth + (std::abs(q.dot(up)) + radius) / (kAutoFill * tan_v));
        };
        // At least 10 cm across is framed, as animation_bounds does.
        double d = 0.05 / (kAutoFill * tan_v);
        for (const Framed& item : framed[f]) {
            double by = fit(item.ball.centre - targets[f], item.ball.radius);
            if (!item.corners.empty()) {
                double by_corners = 0;
                for (const Vec3& c : item.corners) by_corners = std::max(by_corners, fit(c - targets[f], 0));
                by = std::min(by, by_corners);
            }
            d = std::max(d, by);
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

std::vector<uint32_t> main_mass(const std::vector<Ball>& pieces, const std::vector<double>& given) {
    const uint32_t n = uint32_t(pieces.size());
    double total = 0;
    for (uint32_t i = 0; i < n; ++i) total += given[i];
    const bool alike = !(total > 0 && std::isfinite(total));  // then the pieces count alike
    const std::vector<double> mass = alike ? std::vector<double>(n, 1.0) : given;
    if (alike) total = n;
    std::vector<uint32_t> order(n);
    for (uint32_t i = 0; i < n; ++i) order[i] = i;
    // The weighted median per axis: the first centre, in order along the axis, by which half the
    // mass is reached.
    Vec3 median = Vec3::Zero();
    for (int axis = 0; axis < 3; ++axis) {
        std::vector<uint32_t> along = order;
        std::sort(along.begin(), along.end(), [&](uint32_t a, uint32_t b) {
            const double ca = pieces[a].centre[axis], cb = pieces[b].centre[axis];
            return ca != cb ? ca < cb : a < b;
        });
        double sum = 0;
        for (uint32_t i : along) {
            median[axis] = pieces[i].centre[axis];
            if ((sum += mass[i]) >= total / 2) break;
        }
    }
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        const double da = (pieces[a].centre - median).norm(), db = (pieces[b].centre - median).norm();
        return da != db ? da < db : a < b;
    });
    std::vector<uint32_t> out;
    double sum = 0;
    for (uint32_t i : order) {
        if (sum >= kMainMass * total * (1 - 1e-12)) break;
        out.push_back(i);
        sum += mass[i];
    }
    std::sort(out.begin(), out.end());
    return out;
}

double screen_fill(const Camera& c, const std::vector<Ball>& balls) {
    const double sx = c.projection(0, 0), sy = c.projection(1, 1);  // NDC per unit of x / depth
    double lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY, hi_y = -INFINITY;
    for (const Ball& b : balls) {
        const Eigen::Vector3d p = (c.view.cast<double>() * b.centre.homogeneous()).head<3>();
        const double depth = -p.z();
        if (!(depth > 0)) return INFINITY;  // behind the eye: not a framing
        lo_x = std::min(lo_x, sx * (p.x() - b.radius) / depth);
        hi_x = std::max(hi_x, sx * (p.x() + b.radius) / depth);
        lo_y = std::min(lo_y, sy * (p.y() - b.radius) / depth);
        hi_y = std::max(hi_y, sy * (p.y() + b.radius) / depth);
    }
    if (balls.empty()) return 0;
    return std::max(hi_x - lo_x, hi_y - lo_y) / 2;  // NDC spans 2 across the image
}

bool ground_at_bottom(const Camera& c, double ground_height, Vec3* at) {
    const Eigen::Matrix3d to_world = c.view.block<3, 3>(0, 0).cast<double>().transpose();
    const Vec3 ray = to_world * Vec3(0, -1 / double(c.projection(1, 1)), -1);
    const Vec3 eye = c.position.cast<double>();
    if (!(ray.y() < 0) || !(eye.y() > ground_height)) return false;
    *at = eye + ray * ((ground_height - eye.y()) / ray.y());
    return true;
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
    for (uint32_t i = 0; i < t.pieces; ++i) radius[i] = piece_ball_radius(scene.model->pieces[i]);
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
        const Eigen::AlignedBox3d box = piece_box(scene.model->pieces[i]);
        for (int k = 0; k < 8; ++k) corners[i].push_back(box.corner(Eigen::AlignedBox3d::CornerType(k)));
    }
    out.least = 1;
    for (uint32_t f = 0; f < t.frames(); ++f) {
        uint32_t seen = 0;
        for (uint32_t i = 0; i < t.pieces; ++i) {
            const BodyPose& pose = t.pose(f, i);
            const Eigen::Quaterniond r = pose.rotation.cast<double>().normalized();
            bool in = true;  // its box wholly in view, or else its ball
            for (const Vec3& q : corners[i])
                in = in && ball_in_view(camera(f), {r * q + pose.position.cast<double>(), 0.0});
            if (in || ball_in_view(camera(f), {pose.position.cast<double>(), radius[i]})) ++seen;
        }
        const double share = t.pieces ? double(seen) / t.pieces : 1.0;
        out.in_view.push_back(share);
        if (share < out.least) out.least = share, out.least_frame = f;
    }
    out.first = out.in_view.empty() ? 1.0 : out.in_view.front();
    std::vector<double> mass(t.pieces);
    for (uint32_t i = 0; i < t.pieces; ++i) mass[i] = scene.model->pieces[i].mass.mass;
    const Eigen::AlignedBox3d bounds = animation_bounds(scene);
    const double fade_start = kFadeStart * bounds.sizes().norm() / 2;
    for (uint32_t f = 0; f < t.frames(); ++f) {
        std::vector<Ball> centres, corner_points;
        for (uint32_t i = 0; i < t.pieces; ++i) centres.push_back({t.pose(f, i).position.cast<double>(), radius[i]});
        for (uint32_t i : main_mass(centres, mass)) {
            const BodyPose& pose = t.pose(f, i);
            const Mat3 r = pose.rotation.cast<double>().normalized().toRotationMatrix();
            for (const Vec3& q : corners[i]) corner_points.push_back({r * q + pose.position.cast<double>(), 0.0});
        }
        out.fill.push_back(screen_fill(camera(f), corner_points));
        Vec3 at;
        if (!scene.scene.ground) continue;
        if (!ground_at_bottom(camera(f), scene.scene.ground_height, &at) ||
            Eigen::Vector2d(at.x() - bounds.center().x(), at.z() - bounds.center().z()).norm() > fade_start)
            ++out.frames_without_ground;
    }
    if (!out.fill.empty()) {
        const auto least = std::min_element(out.fill.begin(), out.fill.end());
        out.fill_least = *least;
        out.fill_least_frame = uint32_t(least - out.fill.begin());
        std::vector<double> sorted = out.fill;
        std::sort(sorted.begin(), sorted.end());
        out.fill_median = sorted[sorted.size() / 2];
    }
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
