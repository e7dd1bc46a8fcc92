// The small scene the render tests, the golden images, the CLI tests and the render benchmark
// draw: the frozen 10 cm cube model in 2 pieces (tests/fixtures/model-v1.model) resting on the
// ground, then flying apart over 24 frames (each piece arcs outward and tumbles), beside a grey
// sphere and a post (static colliders) while a blue box (a kinematic body) slides in from the
// left. Header only: it needs render/ and SHATTER_SOURCE_DIR, so only targets that link render
// include it (the scenes library itself does not).
#pragma once

#include <cmath>
#include <string>

#include "core/model_io.h"
#include "core/scene_settings.h"
#include "core/trajectory.h"
#include "render/render.h"

namespace shatter::testing_support {

inline std::string fixture_model_path() { return std::string(SHATTER_SOURCE_DIR) + "/tests/fixtures/model-v1.model"; }

inline SceneSettings test_scene_settings() {
    SceneSettings s;
    ColliderSettings sphere;
    sphere.name = "ball";
    sphere.shape.kind = ShapeKind::Sphere;
    sphere.shape.radius = 0.04;
    sphere.pose.position = Vec3(0.20, 0.04, -0.16);
    ColliderSettings post;
    post.name = "post";
    post.shape.kind = ShapeKind::Box;
    post.shape.size = Vec3(0.02, 0.20, 0.02);
    post.pose.position = Vec3(-0.12, 0.10, -0.14);
    post.colour = {0.5f, 0.35f, 0.2f};
    s.colliders = {sphere, post};
    KinematicSettings pusher;
    pusher.name = "pusher";
    pusher.shape.kind = ShapeKind::Box;
    pusher.shape.size = Vec3(0.04, 0.04, 0.04);
    pusher.pose.position = Vec3(-0.30, 0.02, 0.06);
    pusher.velocity = Vec3(0.15, 0, 0);
    s.kinematic = {pusher};
    return s;
}

// Pieces start where the model puts them, shifted so the object's box sits on y = 0 centred on
// the origin; piece i then slides out along its own direction (spread evenly around y),
// arcs up and tumbles.
inline Trajectory test_trajectory(const Model& model, const SceneSettings& scene, uint32_t frames = 24) {
    Trajectory t;
    t.producer = "render tests";
    t.fps = 30;
    t.pieces = static_cast<uint32_t>(model.pieces.size());
    t.props = static_cast<uint32_t>(scene.kinematic.size());
    Eigen::AlignedBox3d box;
    for (const Piece& p : model.pieces)
        for (const Vec3& v : p.surface.vertices) box.extend(v);
    const Vec3 shift(-box.center().x(), -box.min().y(), -box.center().z());
    for (uint32_t f = 0; f < frames; ++f) {
        const double s = double(f) / std::max(1u, frames - 1);
        for (uint32_t i = 0; i < t.pieces; ++i) {
            const Vec3 c = model.pieces[i].mass.center;
            const double angle = 2 * M_PI * i / t.pieces + 0.6;
            const Vec3 out(std::cos(angle), 0, std::sin(angle));
            BodyPose p;
            const Vec3 pos = c + shift + out * (0.16 * s) + Vec3(0, 0.10 * std::sin(M_PI * s), 0);
            p.position = pos.cast<float>();
            const Vec3 axis = Vec3(out.z(), 0.3, -out.x()).normalized();
            p.rotation = Eigen::Quaternionf(Eigen::AngleAxisf(float(2.6 * s / (i + 1)), axis.cast<float>()));
            t.poses.push_back(p);
        }
        for (uint32_t k = 0; k < t.props; ++k) {
            BodyPose p;
            p.position = kinematic_position(scene.kinematic[k], f / t.fps).cast<float>();
            t.poses.push_back(p);
        }
    }
    return t;
}

// Model, trajectory and scene together (the scene borrows the two).
struct TestScene {
    Model model = load_model(fixture_model_path());
    SceneSettings settings = test_scene_settings();
    Trajectory trajectory = test_trajectory(model, settings);
    RenderScene scene() const {
        RenderScene s;
        s.model = &model;
        s.trajectory = &trajectory;
        s.scene = settings;
        s.collider_meshes.resize(settings.colliders.size());
        return s;
    }
};

// Small renders for tests: 320x180, the pieces in the palette (the test scene has no materials:
// the default, the input's colours, would draw them all alike), everything else as the defaults.
inline RenderSettings small_render_settings() {
    RenderSettings s;
    s.width = 320;
    s.height = 180;
    s.colours = Colours::Palette;
    return s;
}

}  // namespace shatter::testing_support
