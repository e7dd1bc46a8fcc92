// The trajectory: what simulate writes and render reads. Per recorded frame, the pose of every
// piece and of every kinematic body ("prop"). Versioned binary (magic "SHTTRAJE",
// docs/formats.md); the settings JSON holds the scene, object, material and simulate settings
// and the model's file hash, so that render draws the scene that was simulated and refuses a
// trajectory of another model.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "core/geometry.h"

namespace shatter {

// A rigid transform: world = rotation * (x - origin) + position, where for a piece `origin` is
// its centre of mass in the model frame (Piece::mass.center) and for a prop its own origin (0).
struct BodyPose {
    Eigen::Vector3f position = Eigen::Vector3f::Zero();             // (unit: m)
    Eigen::Quaternionf rotation = Eigen::Quaternionf::Identity();   // unit quaternion
};

struct Trajectory {
    std::string producer;
    std::string settings_json;
    double fps = 30;             // (unit: frames/s); frame f is at time f / fps
    uint32_t pieces = 0;
    uint32_t props = 0;          // kinematic bodies, in the order of SceneSettings::kinematic
    bool complete = true;        // false: the simulation stopped early (e.g. went unstable)
    std::vector<BodyPose> poses; // frame-major: poses[f * (pieces + props) + body]

    uint32_t bodies() const { return pieces + props; }
    uint32_t frames() const { return bodies() ? static_cast<uint32_t>(poses.size() / bodies()) : 0; }
    const BodyPose& pose(uint32_t frame, uint32_t body) const { return poses[size_t(frame) * bodies() + body]; }
};

constexpr std::string_view kTrajectoryMagic = "SHTTRAJE";
constexpr uint32_t kTrajectoryVersion = 1;

std::string encode_trajectory(const Trajectory& t);
// Validates (counts, finite numbers, unit quaternions within 1e-3); throws Error(BadInput).
Trajectory decode_trajectory(std::string_view bytes, const std::string& source);
void save_trajectory(const std::string& path, const Trajectory& t);  // atomic
Trajectory load_trajectory(const std::string& path);

}  // namespace shatter
