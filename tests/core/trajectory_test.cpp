// The trajectory file: exact round trip, refusal of every damaged or malformed file, the frozen
// version-1 fixture, and the summary `shatter info` prints.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

#include "core/binary_io.h"
#include "core/error.h"
#include "core/scene_settings.h"
#include "core/stage_file.h"
#include "core/trajectory.h"
#include "core/trajectory_summary.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::TempDir;

// 2 pieces and 1 prop over 3 frames at 10 fps: piece 0 slides +x at 1 m/s, piece 1 falls 0.1 m
// then 0.3 m while turning about y, the prop moves +z at 2 m/s.
Trajectory small_trajectory() {
    Trajectory t;
    t.producer = producer_string();
    t.settings_json = R"({"simulate":{"fps":10}})";
    t.fps = 10;
    t.pieces = 2;
    t.props = 1;
    t.complete = false;
    for (int f = 0; f < 3; ++f) {
        BodyPose a, b, prop;
        a.position = Eigen::Vector3f(0.1f * f, 1, 0);
        b.position = Eigen::Vector3f(1, f == 0 ? 2.0f : f == 1 ? 1.9f : 1.6f, 0);
        b.rotation = Eigen::Quaternionf(Eigen::AngleAxisf(0.25f * f * float(M_PI), Eigen::Vector3f::UnitY()));
        prop.position = Eigen::Vector3f(0, 0.5f, -1 + 0.2f * f);
        t.poses.insert(t.poses.end(), {a, b, prop});
    }
    return t;
}

ExitCode decode_error(std::string_view bytes, std::string* message) {
    try {
        decode_trajectory(bytes, "t.traj");
    } catch (const Error& e) {
        *message = e.what();
        return e.code();
    }
    return ExitCode::Ok;
}

// A trajectory file around a hand-made payload.
std::string with_payload(const ByteWriter& w) {
    return pack_stage_file({std::string(kTrajectoryMagic), kTrajectoryVersion, "test", "{}"}, w.data());
}

ByteWriter payload_head(double fps, uint32_t pieces, uint32_t props, uint32_t frames) {
    ByteWriter w;
    w.f64(fps);
    w.u32(pieces);
    w.u32(props);
    w.u8(1);
    w.u32(frames);
    return w;
}

void put_pose(ByteWriter& w, float x, float y, float z, float qx, float qy, float qz, float qw) {
    for (float v : {x, y, z, qx, qy, qz, qw}) w.f32(v);
}

void expect_refused(std::string_view bytes, const char* part) {
    std::string message;
    EXPECT_EQ(decode_error(bytes, &message), ExitCode::BadInput) << part;
    EXPECT_NE(message.find(part), std::string::npos) << message;
    EXPECT_NE(message.find("t.traj"), std::string::npos) << message;
}

TEST(TrajectoryFile, RoundTripKeepsEveryFieldAndEncodesToTheSameBytes) {
    const Trajectory t = small_trajectory();
    const std::string bytes = encode_trajectory(t);
    const Trajectory back = decode_trajectory(bytes, "t.traj");
    EXPECT_EQ(back.producer, t.producer);
    EXPECT_EQ(back.settings_json, t.settings_json);
    EXPECT_EQ(back.fps, 10);
    EXPECT_EQ(back.pieces, 2u);
    EXPECT_EQ(back.props, 1u);
    EXPECT_FALSE(back.complete);
    ASSERT_EQ(back.frames(), 3u);
    for (uint32_t f = 0; f < 3; ++f)
        for (uint32_t b = 0; b < 3; ++b) {
            EXPECT_EQ(back.pose(f, b).position, t.pose(f, b).position);
            EXPECT_EQ(back.pose(f, b).rotation.coeffs(), t.pose(f, b).rotation.coeffs());
        }
    EXPECT_EQ(encode_trajectory(back), bytes);
    // envelope (40 bytes + producer + settings), payload head (21 bytes), 9 poses of 28 bytes
    EXPECT_EQ(bytes.size(), 40 + t.producer.size() + t.settings_json.size() + 21 + 9 * 28);
}

TEST(TrajectoryFile, SaveAndLoadGoThroughTheFile) {
    TempDir dir;
    save_trajectory(dir.file("a.traj"), small_trajectory());
    EXPECT_EQ(encode_trajectory(load_trajectory(dir.file("a.traj"))), encode_trajectory(small_trajectory()));
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"a.traj"});
}

TEST(TrajectoryFile, EmptyTrajectoryRoundTrips) {
    Trajectory t;
    t.pieces = 3;
    const Trajectory back = decode_trajectory(encode_trajectory(t), "t.traj");
    EXPECT_EQ(back.frames(), 0u);
    EXPECT_EQ(back.pieces, 3u);
}

TEST(TrajectoryFile, EveryTruncationIsRefusedWithAClearError) {
    const std::string bytes = encode_trajectory(small_trajectory());
    for (size_t n = 0; n < bytes.size(); ++n) {
        std::string message;
        ASSERT_EQ(decode_error(std::string_view(bytes).substr(0, n), &message), ExitCode::BadInput) << "length " << n;
        EXPECT_NE(message.find("t.traj"), std::string::npos);
    }
}

TEST(TrajectoryFile, EveryFlippedBitIsRefusedOrOnlyChangesTheHeaderText) {
    const Trajectory t = small_trajectory();
    const std::string bytes = encode_trajectory(t);
    for (size_t i = 0; i < bytes.size(); ++i) {
        for (int bit = 0; bit < 8; ++bit) {
            std::string damaged = bytes;
            damaged[i] = static_cast<char>(damaged[i] ^ (1 << bit));
            std::string message;
            const ExitCode code = decode_error(damaged, &message);
            if (code == ExitCode::Ok) {  // the checksum covers the payload, not the producer or settings text
                const Trajectory back = decode_trajectory(damaged, "t.traj");
                EXPECT_TRUE(back.producer != t.producer || back.settings_json != t.settings_json) << "byte " << i;
            } else {
                EXPECT_EQ(code, ExitCode::BadInput);
            }
        }
    }
}

TEST(TrajectoryFile, NewerVersionIsRefusedAndSaysToUpdate) {
    std::string bytes = encode_trajectory(small_trajectory());
    bytes[8] = 2;  // version field
    expect_refused(bytes, "trajectory format version 2 is newer");
    expect_refused(bytes, "update shatter");
}

TEST(TrajectoryFile, AModelFileIsNamedAsSuch) {
    std::string bytes = encode_trajectory(small_trajectory());
    bytes.replace(0, 8, "SHTMODEL");
    expect_refused(bytes, "is a SHTMODEL file, not a trajectory file");
}

TEST(TrajectoryFile, NonUnitQuaternionIsRefused) {
    Trajectory t = small_trajectory();
    t.poses[4].rotation = Eigen::Quaternionf(1.01f, 0, 0, 0);
    expect_refused(encode_trajectory(t), "rotation of body 1 in frame 1 is not a unit quaternion (|q| = 1.01)");
    t.poses[4].rotation = Eigen::Quaternionf(0, 0, 0, 0);
    expect_refused(encode_trajectory(t), "not a unit quaternion");
    t.poses[4].rotation = Eigen::Quaternionf(1.0005f, 0, 0, 0);  // within 1e-3: accepted as written
    EXPECT_EQ(decode_trajectory(encode_trajectory(t), "t.traj").poses[4].rotation.w(), 1.0005f);
}

TEST(TrajectoryFile, NonFiniteNumbersAreRefused) {
    Trajectory t = small_trajectory();
    t.poses[2].position.y() = NAN;
    expect_refused(encode_trajectory(t), "a body position is not a finite number");
    t = small_trajectory();
    t.poses[2].rotation.x() = INFINITY;
    expect_refused(encode_trajectory(t), "a body rotation is not a finite number");
}

TEST(TrajectoryFile, FrameRateMustBeFiniteAndPositive) {
    for (double fps : {0.0, -30.0, double(NAN), double(INFINITY)}) {
        ByteWriter w = payload_head(fps, 1, 0, 1);
        put_pose(w, 0, 0, 0, 0, 0, 0, 1);
        expect_refused(with_payload(w), "is not a positive number");
    }
}

TEST(TrajectoryFile, FramesWithoutBodiesAreRefused) {
    ByteWriter w = payload_head(30, 0, 0, 5);
    expect_refused(with_payload(w), "5 frames of no bodies");
}

TEST(TrajectoryFile, CountsThatDoNotFitAreRefusedWithoutAllocating) {
    ByteWriter w = payload_head(30, 2, 1, 0xffffffffu);
    put_pose(w, 0, 0, 0, 0, 0, 0, 1);
    expect_refused(with_payload(w), "4294967295 frames x 3 bodies do not fit");
    ByteWriter big = payload_head(30, 0xffffffffu, 0xffffffffu, 0);
    expect_refused(with_payload(big), "do not fit in 32 bits");
}

TEST(TrajectoryFile, TrailingBytesAndABadCompleteFlagAreRefused) {
    ByteWriter w = payload_head(30, 1, 0, 1);
    put_pose(w, 0, 0, 0, 0, 0, 0, 1);
    w.u8(0);
    expect_refused(with_payload(w), "1 unexpected bytes after the last frame");
    ByteWriter flag;
    flag.f64(30);
    flag.u32(1);
    flag.u32(0);
    flag.u8(7);
    flag.u32(0);
    expect_refused(with_payload(flag), "'complete' flag is 7");
}

// ---- the frozen fixture -------------------------------------------------------------------

TEST(TrajectoryFixture, Version1FixtureReadsWithItsKnownPoses) {
    const Trajectory t = load_trajectory(SHATTER_SOURCE_DIR "/tests/fixtures/trajectory-v1.traj");
    EXPECT_EQ(t.producer, "shatter 0.1.0");
    EXPECT_EQ(t.fps, 10);
    EXPECT_EQ(t.pieces, 2u);
    EXPECT_EQ(t.props, 1u);
    EXPECT_TRUE(t.complete);
    ASSERT_EQ(t.frames(), 3u);
    const float tol = 1e-6f;
    EXPECT_LT((t.pose(2, 0).position - Eigen::Vector3f(0.2f, 1, 0)).norm(), tol);
    EXPECT_LT((t.pose(1, 1).position - Eigen::Vector3f(1, 1.9f, 0)).norm(), tol);
    EXPECT_LT((t.pose(2, 1).position - Eigen::Vector3f(1, 1.6f, 0)).norm(), tol);
    // piece 1 turns 90 degrees about +y by frame 2: it takes +x to -z
    EXPECT_LT((t.pose(2, 1).rotation * Eigen::Vector3f::UnitX() - Eigen::Vector3f(0, 0, -1)).norm(), tol);
    EXPECT_LT((t.pose(2, 2).position - Eigen::Vector3f(0, 0.5f, -0.6f)).norm(), tol);
    EXPECT_EQ(t.pose(0, 0).rotation.coeffs(), Eigen::Quaternionf::Identity().coeffs());
    // The settings carry the scene, which reads back: one kinematic prop, the hammer.
    const nlohmann::json settings = nlohmann::json::parse(t.settings_json);
    const SceneSettings scene = scene_from_json(settings.at("scene"), "fixture");
    ASSERT_EQ(scene.kinematic.size(), 1u);
    EXPECT_EQ(scene.kinematic[0].name, "hammer");
    EXPECT_EQ(settings.at("simulate").at("fps"), 10.0);
}

// ---- summary ----------------------------------------------------------------------------------

TEST(TrajectorySummary, PathLengthsSpeedsAndFinalPositionsMatchHandValues) {
    Trajectory t = small_trajectory();
    const nlohmann::ordered_json j = trajectory_summary(t);
    EXPECT_EQ(j["kind"], "trajectory");
    EXPECT_EQ(j["frames"], 3u);
    EXPECT_EQ(j["fps"], 10.0);
    EXPECT_NEAR(j["duration_s"].get<double>(), 0.2, 1e-12);
    EXPECT_EQ(j["pieces"], 2u);
    EXPECT_EQ(j["props"], 1u);
    EXPECT_EQ(j["complete"], false);
    EXPECT_EQ(j["settings"]["simulate"]["fps"], 10);
    ASSERT_EQ(j["per_piece"].size(), 2u);  // props are not pieces
    EXPECT_NEAR(j["per_piece"][0]["path_length_m"].get<double>(), 0.2, 1e-6);
    EXPECT_NEAR(j["per_piece"][0]["max_speed_m_s"].get<double>(), 1.0, 1e-5);
    EXPECT_NEAR(j["per_piece"][1]["path_length_m"].get<double>(), 0.4, 1e-6);
    EXPECT_NEAR(j["per_piece"][1]["max_speed_m_s"].get<double>(), 3.0, 1e-5);
    EXPECT_NEAR(j["per_piece"][1]["final_position_m"][1].get<double>(), 1.6, 1e-6);
    EXPECT_NEAR(j["max_piece_speed_m_s"].get<double>(), 3.0, 1e-5);
    const std::string text = trajectory_summary_text(j);
    EXPECT_NE(text.find("frames        3 at 10 fps (0.2 s)"), std::string::npos) << text;
    EXPECT_NE(text.find("bodies        2 pieces, 1 props"), std::string::npos) << text;
    EXPECT_NE(text.find("NO: the simulation stopped early"), std::string::npos) << text;
}

TEST(TrajectorySummary, EmptyTrajectoryAndUnparsableSettingsStillSummarize) {
    Trajectory t;
    t.pieces = 1;
    t.settings_json = "not json";
    const nlohmann::ordered_json j = trajectory_summary(t);
    EXPECT_EQ(j["frames"], 0u);
    EXPECT_EQ(j["settings"], "not json");
    EXPECT_TRUE(j["per_piece"][0]["final_position_m"].is_null());
    EXPECT_NE(trajectory_summary_text(j).find("    0           0               0  -"), std::string::npos)
        << trajectory_summary_text(j);
}

}  // namespace
}  // namespace shatter
