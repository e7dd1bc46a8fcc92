#include "render/scene_bounds.h"

#include <algorithm>

namespace shatter {

double shape_radius(const ShapeSettings& shape) {
    switch (shape.kind) {
        case ShapeKind::Box: return shape.size.norm() / 2;
        case ShapeKind::Sphere: return shape.radius;
        default: return 0;
    }
}

std::vector<Ball> animation_balls(const RenderScene& scene) {
    std::vector<Ball> balls;
    const Trajectory& t = *scene.trajectory;
    std::vector<double> radius(t.bodies(), 0.0);
    for (uint32_t i = 0; i < t.pieces; ++i) radius[i] = piece_radius(scene.model->pieces[i]);
    const std::vector<KinematicSettings> props = scene_props(scene.scene);
    for (uint32_t k = 0; k < t.props; ++k) radius[t.pieces + k] = shape_radius(props[k].shape);
    for (uint32_t f = 0; f < t.frames(); ++f)
        for (uint32_t b = 0; b < t.bodies(); ++b) balls.push_back({t.pose(f, b).position.cast<double>(), radius[b]});
    for (const ColliderSettings& c : scene.scene.colliders)
        if (c.shape.kind == ShapeKind::Box || c.shape.kind == ShapeKind::Sphere)
            balls.push_back({c.pose.position, shape_radius(c.shape)});
    return balls;
}

Eigen::AlignedBox3d animation_bounds(const std::vector<Ball>& balls) {
    Eigen::AlignedBox3d box;
    for (const Ball& b : balls) {
        box.extend(b.centre - Vec3::Constant(b.radius));
        box.extend(b.centre + Vec3::Constant(b.radius));
    }
    if (box.isEmpty()) box.extend(Vec3::Zero());
    // Never a degenerate box: at least 10 cm across.
    const Vec3 grow = (Vec3::Constant(0.1) - box.sizes()).cwiseMax(0.0) / 2;
    box.extend(box.min() - grow);
    box.extend(box.max() + grow);
    return box;
}

}  // namespace shatter
