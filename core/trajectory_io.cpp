// Reading and writing the trajectory file (magic "SHTTRAJE", docs/formats.md). Payload:
//   f64 fps, u32 pieces, u32 props, u8 complete, u32 frames,
//   then frames x (pieces + props) x (f32 x, y, z position; f32 x, y, z, w unit quaternion).
#include <cassert>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/binary_io.h"
#include "core/error.h"
#include "core/stage_file.h"
#include "core/trajectory.h"

namespace shatter {

namespace {

constexpr size_t kPoseBytes = 7 * 4;
constexpr float kQuaternionTolerance = 1e-3f;

float finite_f32(ByteReader& r, const char* what) {
    const float v = r.f32();
    if (!std::isfinite(v)) r.fail(std::string(what) + " is not a finite number");
    return v;
}

BodyPose get_pose(ByteReader& r, uint32_t frame, uint32_t body) {
    BodyPose p;
    for (int i = 0; i < 3; ++i) p.position[i] = finite_f32(r, "a body position");
    float q[4];
    for (float& c : q) c = finite_f32(r, "a body rotation");
    p.rotation = Eigen::Quaternionf(q[3], q[0], q[1], q[2]);
    const float norm = p.rotation.norm();
    if (!(std::fabs(norm - 1.0f) <= kQuaternionTolerance))
        r.fail(fmt::format("the rotation of body {} in frame {} is not a unit quaternion (|q| = {:g})", body, frame,
                           norm));
    return p;
}

}  // namespace

std::string encode_trajectory(const Trajectory& t) {
    assert(t.poses.size() == size_t(t.frames()) * t.bodies() && "poses must be whole frames of every body");
    ByteWriter w;
    w.f64(t.fps);
    w.u32(t.pieces);
    w.u32(t.props);
    w.u8(t.complete ? 1 : 0);
    const uint32_t frames = t.frames();
    w.u32(frames);
    const size_t n = size_t(frames) * t.bodies();
    for (size_t i = 0; i < n; ++i) {
        const BodyPose& p = t.poses[i];
        for (int c = 0; c < 3; ++c) w.f32(p.position[c]);
        w.f32(p.rotation.x());
        w.f32(p.rotation.y());
        w.f32(p.rotation.z());
        w.f32(p.rotation.w());
    }
    StageHeader h{std::string(kTrajectoryMagic), kTrajectoryVersion, t.producer, t.settings_json};
    return pack_stage_file(h, w.data());
}

Trajectory decode_trajectory(std::string_view bytes, const std::string& source) {
    StageFile f = unpack_stage_file(bytes, source, kTrajectoryMagic, "trajectory", 1, kTrajectoryVersion);
    ByteReader r(f.payload, source, f.payload_offset);
    Trajectory t;
    t.producer = f.header.producer;
    t.settings_json = f.header.settings_json;
    t.fps = r.f64();
    if (!std::isfinite(t.fps) || t.fps <= 0) r.fail(fmt::format("the frame rate {} is not a positive number", t.fps));
    t.pieces = r.u32();
    t.props = r.u32();
    if (uint64_t(t.pieces) + t.props > UINT32_MAX) r.fail("the counts of pieces and props do not fit in 32 bits");
    const uint8_t complete = r.u8();
    if (complete > 1) r.fail(fmt::format("the 'complete' flag is {}, not 0 or 1", complete));
    t.complete = complete == 1;
    const uint32_t frames = r.u32();
    const uint64_t poses = uint64_t(frames) * t.bodies();
    if (frames > 0 && t.bodies() == 0) r.fail(fmt::format("{} frames of no bodies (0 pieces, 0 props)", frames));
    if (poses > r.remaining() / kPoseBytes)
        r.fail(fmt::format("{} frames x {} bodies do not fit in the {} bytes left", frames, t.bodies(), r.remaining()));
    t.poses.resize(poses);
    for (uint32_t fr = 0; fr < frames; ++fr)
        for (uint32_t b = 0; b < t.bodies(); ++b) t.poses[size_t(fr) * t.bodies() + b] = get_pose(r, fr, b);
    if (r.remaining() != 0) r.fail(fmt::format("{} unexpected bytes after the last frame", r.remaining()));
    return t;
}

void save_trajectory(const std::string& path, const Trajectory& t) { write_file_atomic(path, encode_trajectory(t)); }

Trajectory load_trajectory(const std::string& path) {
    return decode_trajectory(read_file(path, "trajectory file"), path);
}

}  // namespace shatter
