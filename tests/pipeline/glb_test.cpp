// The .glb export (pipeline/export_glb.h), checked by reading it back with assimp and by the
// Khronos validator: one node per piece and kinematic body, one animation channel per node with
// a key at every frame at time frame / fps, a known pose that comes back within 1e-5, vertices
// about each piece's centre of mass in metres (+Y up, no conversion), render's colours, a
// textured input's texture embedded with its texture coordinates, the
// same bytes for the same input, and an atomic write that leaves no temporary behind.
//
// The validator test needs node and the npm package gltf-validator, which
// scripts/install-node-tools.sh installs into BUILD/node_modules (`make test` calls it); it is
// skipped, saying why, when either is missing. SHATTER_NODE_MODULES overrides the location.
#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/model_io.h"
#include "core/palette.h"
#include "core/render_settings.h"
#include "core/scene_settings.h"
#include "pipeline/export_glb.h"
#include "pipeline/process.h"
#include "prescore/crack_creases.h"
#include "prescore/prescore.h"
#include "render/camera_path.h"
#include "render/mesh_builder.h"
#include "render/png_io.h"
#include "render/texture.h"
#include "scenes/box_model.h"
#include "support/duck.h"
#include "support/run_command.h"
#include "support/temp_dir.h"
#include "support/unit_cube.h"

namespace shatter {
namespace {

using namespace testing_support;
namespace fs = std::filesystem;

constexpr double kFps = 24;  // 1/24 s is not a binary fraction: times must still come back as f / fps
constexpr uint32_t kFrames = 13;
const Eigen::Vector3f kKnownPosition(0.25f, 1.5f, -0.75f);  // piece 1 at frame 7
const Eigen::Quaternionf kKnownRotation(Eigen::AngleAxisf(2.5f, Eigen::Vector3f(1, 2, 3).normalized()));

// Three boxes; piece 0 has two fracture triangles and one cavity triangle.
Model test_model() {
    BoxModelBuilder b;
    b.box(Vec3(0, 0.5, 0), Vec3(1, 1, 1));
    b.box(Vec3(1.0, 0.5, 0), Vec3(1, 1, 1));
    b.box(Vec3(0.5, 1.25, 0), Vec3(2, 0.5, 0.4));
    Model m = b.take();
    m.pieces[0].surface.kinds[2] = m.pieces[0].surface.kinds[3] = FaceKind::Fracture;
    m.pieces[0].surface.kinds[5] = FaceKind::Cavity;
    return m;
}

SceneSettings test_scene() {
    SceneSettings s;
    KinematicSettings pusher;
    pusher.name = "pusher";
    pusher.shape.kind = ShapeKind::Box;
    pusher.shape.size = Vec3(0.5, 0.2, 0.3);
    s.kinematic.push_back(pusher);
    KinematicSettings ball;  // no name
    ball.shape.kind = ShapeKind::Sphere;
    ball.shape.radius = 0.3;
    ball.colour = {0.8f, 0.1f, 0.1f};
    s.kinematic.push_back(ball);
    return s;
}

// Every body moves and turns a little per frame; piece 1 sits at a known pose at frame 7 and
// piece 2's quaternion changes sign every other frame (the same rotation).
Trajectory test_trajectory(const Model& m, uint32_t frames = kFrames, bool with_props = true) {
    Trajectory t;
    t.fps = kFps;
    t.pieces = uint32_t(m.pieces.size());
    if (with_props) {
        t.props = 2;
        nlohmann::ordered_json j;
        j["scene"] = to_json(test_scene());
        t.settings_json = j.dump();
    }
    for (uint32_t f = 0; f < frames; ++f)
        for (uint32_t b = 0; b < t.bodies(); ++b) {
            BodyPose p;
            const Eigen::Vector3f start = b < t.pieces ? m.pieces[b].mass.center.cast<float>()
                                                       : Eigen::Vector3f(-2.0f + b, 0.5f, 1.0f);
            p.position = start + Eigen::Vector3f(0.1f * b, -0.05f * f, 0.02f * f);
            p.rotation = Eigen::AngleAxisf(0.1f * f * (b + 1), Eigen::Vector3f(b % 3 == 0, b % 3 == 1, 1).normalized());
            if (b == 2 && f % 2 == 1) p.rotation.coeffs() = -p.rotation.coeffs();
            if (b == 1 && f == 7) {
                p.position = kKnownPosition;
                p.rotation = kKnownRotation;
            }
            t.poses.push_back(p);
        }
    return t;
}

struct Imported {
    Assimp::Importer importer;
    const aiScene* scene = nullptr;
    explicit Imported(const std::string& path) {
        scene = importer.ReadFile(path, 0);
        if (!scene) ADD_FAILURE() << "assimp cannot read " << path << ": " << importer.GetErrorString();
    }
    const aiNode* node(const std::string& name) const { return scene->mRootNode->FindNode(name.c_str()); }
    const aiNodeAnim* channel(const std::string& name) const {
        const aiAnimation* a = scene->mAnimations[0];
        for (unsigned i = 0; i < a->mNumChannels; ++i)
            if (name == a->mChannels[i]->mNodeName.C_Str()) return a->mChannels[i];
        return nullptr;
    }
    Colour base_colour(const aiMesh* mesh) const {
        aiColor4D c;
        EXPECT_EQ(scene->mMaterials[mesh->mMaterialIndex]->Get(AI_MATKEY_BASE_COLOR, c), AI_SUCCESS);
        return {c.r, c.g, c.b};
    }
};

// q and -q are the same rotation.
void expect_same_rotation(const aiQuaternion& got, const Eigen::Quaternionf& want, double tol) {
    const double sign = got.w * want.w() + got.x * want.x() + got.y * want.y() + got.z * want.z() < 0 ? -1 : 1;
    EXPECT_NEAR(sign * got.w, want.w(), tol);
    EXPECT_NEAR(sign * got.x, want.x(), tol);
    EXPECT_NEAR(sign * got.y, want.y(), tol);
    EXPECT_NEAR(sign * got.z, want.z(), tol);
}

TEST(GlbExport, HasANodePerBodyAMeshPerFaceKindAndAKeyPerFrameAtFrameOverFps) {
    TempDir dir;
    const Model m = test_model();
    export_glb(m, test_trajectory(m), dir.file("a.glb"));
    Imported g(dir.file("a.glb"));
    ASSERT_TRUE(g.scene);
    const std::vector<std::string> names = {"piece_0", "piece_1", "piece_2", "prop_0_pusher", "prop_1"};
    ASSERT_EQ(g.scene->mRootNode->mNumChildren, names.size());
    for (size_t i = 0; i < names.size(); ++i) EXPECT_EQ(g.scene->mRootNode->mChildren[i]->mName.C_Str(), names[i]);
    EXPECT_EQ(g.node("piece_0")->mNumMeshes, 3u);  // outer, fracture, cavity
    for (const char* n : {"piece_1", "piece_2", "prop_0_pusher", "prop_1"}) EXPECT_EQ(g.node(n)->mNumMeshes, 1u) << n;
    EXPECT_EQ(g.scene->mNumMeshes, 7u);

    ASSERT_EQ(g.scene->mNumAnimations, 1u);
    const aiAnimation* anim = g.scene->mAnimations[0];
    ASSERT_EQ(anim->mNumChannels, names.size());
    ASSERT_GT(anim->mTicksPerSecond, 0);
    for (const std::string& n : names) {
        const aiNodeAnim* ch = g.channel(n);
        ASSERT_TRUE(ch) << n;
        ASSERT_EQ(ch->mNumPositionKeys, kFrames) << n;
        ASSERT_EQ(ch->mNumRotationKeys, kFrames) << n;
        // No scale channel; assimp's importer turns a rest scale (written when the exporter's
        // decomposition of the rest pose gives 1 +- 1e-7) into one constant key.
        ASSERT_LE(ch->mNumScalingKeys, 1u) << n;
        for (unsigned k = 0; k < ch->mNumScalingKeys; ++k)
            for (int i = 0; i < 3; ++i) EXPECT_NEAR(ch->mScalingKeys[k].mValue[i], 1.0, 1e-5) << n;
        for (uint32_t f = 0; f < kFrames; ++f) {
            EXPECT_NEAR(ch->mPositionKeys[f].mTime / anim->mTicksPerSecond, f / kFps, 1e-6) << n << " frame " << f;
            EXPECT_NEAR(ch->mRotationKeys[f].mTime / anim->mTicksPerSecond, f / kFps, 1e-6) << n << " frame " << f;
        }
    }
    EXPECT_NEAR(anim->mDuration / anim->mTicksPerSecond, (kFrames - 1) / kFps, 1e-6);
}

// A projectile ([[scene.projectile]]) is a prop after the kinematic bodies: its own node, mesh
// and colour, animated by the trajectory's poses.
TEST(GlbExport, AProjectileIsExportedAfterTheKinematicBodies) {
    TempDir dir;
    const Model m = test_model();
    SceneSettings scene = test_scene();
    ProjectileSettings ball;
    ball.name = "ball";
    ball.shape.kind = ShapeKind::Sphere;
    ball.shape.radius = 0.05;
    ball.colour = {0.1f, 0.7f, 0.2f};
    scene.projectiles.push_back(ball);
    const Trajectory pieces_only = test_trajectory(m, kFrames, false);
    Trajectory t = pieces_only;
    t.props = 3;
    nlohmann::ordered_json j;
    j["scene"] = to_json(scene);
    t.settings_json = j.dump();
    t.poses.clear();
    for (uint32_t f = 0; f < kFrames; ++f) {
        for (uint32_t b = 0; b < t.pieces; ++b) t.poses.push_back(pieces_only.pose(f, b));
        for (uint32_t k = 0; k < 3; ++k) {
            BodyPose p;
            p.position = Eigen::Vector3f(float(k), 1.0f - 0.1f * f, 0.0f);
            t.poses.push_back(p);
        }
    }
    export_glb(m, t, dir.file("a.glb"));
    Imported g(dir.file("a.glb"));
    ASSERT_TRUE(g.scene);
    const aiNode* node = g.node("prop_2_ball");
    ASSERT_TRUE(node);
    ASSERT_EQ(node->mNumMeshes, 1u);
    const Colour c = g.base_colour(g.scene->mMeshes[node->mMeshes[0]]);
    EXPECT_NEAR(c[1], 0.7f, 1e-6);
    const aiNodeAnim* ch = g.channel("prop_2_ball");
    ASSERT_TRUE(ch);
    ASSERT_EQ(ch->mNumPositionKeys, kFrames);
    EXPECT_NEAR(ch->mPositionKeys[kFrames - 1].mValue.y, 1.0 - 0.1 * (kFrames - 1), 1e-5);
    // A trajectory that moves fewer props than its scene describes is refused.
    Trajectory short_of_props = pieces_only;
    short_of_props.settings_json = t.settings_json;
    EXPECT_THROW(export_glb(m, short_of_props, dir.file("b.glb")), Error);
}

TEST(GlbExport, AKnownPoseComesBackWithin1e5AndTheRestPoseIsFrameZero) {
    TempDir dir;
    const Model m = test_model();
    const Trajectory t = test_trajectory(m);
    export_glb(m, t, dir.file("a.glb"));
    Imported g(dir.file("a.glb"));
    ASSERT_TRUE(g.scene);
    const aiNodeAnim* ch = g.channel("piece_1");
    ASSERT_TRUE(ch);
    const aiVector3D p = ch->mPositionKeys[7].mValue;
    EXPECT_NEAR(p.x, kKnownPosition.x(), 1e-5);
    EXPECT_NEAR(p.y, kKnownPosition.y(), 1e-5);
    EXPECT_NEAR(p.z, kKnownPosition.z(), 1e-5);
    expect_same_rotation(ch->mRotationKeys[7].mValue, kKnownRotation, 1e-5);

    // Every key of every body, and each node's rest transform = its pose at frame 0.
    for (uint32_t b = 0; b < t.bodies(); ++b) {
        const std::string name = g.scene->mRootNode->mChildren[b]->mName.C_Str();
        const aiNodeAnim* c = g.channel(name);
        for (uint32_t f = 0; f < kFrames; ++f) {
            const BodyPose& want = t.pose(f, b);
            for (int i = 0; i < 3; ++i) EXPECT_NEAR(c->mPositionKeys[f].mValue[i], want.position[i], 1e-5);
            expect_same_rotation(c->mRotationKeys[f].mValue, want.rotation, 1e-5);
        }
        aiVector3D scale, position;
        aiQuaternion rotation;
        g.node(name)->mTransformation.Decompose(scale, rotation, position);
        for (int i = 0; i < 3; ++i) {
            EXPECT_NEAR(position[i], t.pose(0, b).position[i], 1e-5) << name;
            EXPECT_NEAR(scale[i], 1.0, 1e-5) << name;
        }
        expect_same_rotation(rotation, t.pose(0, b).rotation, 1e-5);
    }
}

TEST(GlbExport, RotationKeysStayOnOneHemisphereSoInterpolationTurnsTheShortWay) {
    TempDir dir;
    const Model m = test_model();
    export_glb(m, test_trajectory(m), dir.file("a.glb"));  // piece 2 flips sign every other frame
    Imported g(dir.file("a.glb"));
    ASSERT_TRUE(g.scene);
    const aiNodeAnim* ch = g.channel("piece_2");
    ASSERT_TRUE(ch);
    for (uint32_t f = 1; f < kFrames; ++f) {
        const aiQuaternion& a = ch->mRotationKeys[f - 1].mValue;
        const aiQuaternion& b = ch->mRotationKeys[f].mValue;
        EXPECT_GT(a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z, 0.9) << "frame " << f;
    }
}

TEST(GlbExport, PieceVerticesAreAboutTheCentreOfMassInMetresWithRendersColours) {
    TempDir dir;
    const Model m = test_model();
    export_glb(m, test_trajectory(m), dir.file("a.glb"));
    Imported g(dir.file("a.glb"));
    ASSERT_TRUE(g.scene);
    // Piece 2 is a 2 x 0.5 x 0.4 m box: its vertices are the corners +-(1, 0.25, 0.2).
    const aiNode* n = g.node("piece_2");
    ASSERT_EQ(n->mNumMeshes, 1u);
    const aiMesh* mesh = g.scene->mMeshes[n->mMeshes[0]];
    EXPECT_EQ(mesh->mNumFaces, 12u);
    ASSERT_TRUE(mesh->HasNormals());
    for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
        EXPECT_NEAR(std::abs(mesh->mVertices[i].x), 1.0, 1e-6);
        EXPECT_NEAR(std::abs(mesh->mVertices[i].y), 0.25, 1e-6);
        EXPECT_NEAR(std::abs(mesh->mVertices[i].z), 0.2, 1e-6);
        EXPECT_NEAR(mesh->mNormals[i].Length(), 1.0, 1e-6);
    }
    // Without render settings, render's defaults: a model without materials in material_colour.
    const RenderSettings look;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(g.base_colour(mesh)[i], look.material_colour[size_t(i)], 1e-6);

    // Piece 0's fracture and cavity faces have render's shades of its colour.
    const aiNode* n0 = g.node("piece_0");
    ASSERT_EQ(n0->mNumMeshes, 3u);
    const FaceKind kinds[3] = {FaceKind::Outer, FaceKind::Fracture, FaceKind::Cavity};
    const unsigned faces[3] = {9, 2, 1};
    for (int k = 0; k < 3; ++k) {
        const aiMesh* part = g.scene->mMeshes[n0->mMeshes[k]];
        EXPECT_EQ(part->mNumFaces, faces[k]) << k;
        const Colour want = face_colour(look.material_colour, kinds[k], look);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(g.base_colour(part)[i], want[i], 1e-6) << k;
    }
    // The sphere prop has its radius and its scene colour.
    const aiMesh* ball = g.scene->mMeshes[g.node("prop_1")->mMeshes[0]];
    for (unsigned i = 0; i < ball->mNumVertices; ++i) EXPECT_NEAR(ball->mVertices[i].Length(), 0.3, 1e-6);
    EXPECT_NEAR(g.base_colour(ball)[0], 0.8, 1e-6);
}

TEST(GlbExport, SameInputGivesTheSameBytesWhateverTheFileName) {
    TempDir dir;
    const Model m = test_model();
    const Trajectory t = test_trajectory(m);
    export_glb(m, t, dir.file("a.glb"));
    export_glb(m, t, dir.file("second name.glb"));
    const std::string a = slurp(dir.file("a.glb"));
    EXPECT_GT(a.size(), 1000u);
    EXPECT_EQ(a.substr(0, 4), "glTF");
    EXPECT_TRUE(a == slurp(dir.file("second name.glb")));
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a.glb", "second name.glb"}));  // no temporaries
}

TEST(GlbExport, WithoutPropsOnlyPiecesAreExported) {
    TempDir dir;
    const Model m = test_model();
    export_glb(m, test_trajectory(m, 2, false), dir.file("a.glb"));
    Imported g(dir.file("a.glb"));
    ASSERT_TRUE(g.scene);
    EXPECT_EQ(g.scene->mRootNode->mNumChildren, 3u);
    EXPECT_EQ(g.scene->mAnimations[0]->mNumChannels, 3u);
}

TEST(GlbExport, AnUnwritableTargetIsAnIoErrorAndLeavesNoTemporary) {
    TempDir dir;
    const Model m = test_model();
    const Trajectory t = test_trajectory(m);
    fs::create_directory(dir.file("taken.glb"));  // rename onto a directory fails
    try {
        export_glb(m, t, dir.file("taken.glb"));
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Io);
        EXPECT_NE(std::string(e.what()).find("taken.glb"), std::string::npos) << e.what();
    }
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"taken.glb"}));
    dir.write("file", "x");
    try {
        export_glb(m, t, dir.file("file/out.glb"));  // a parent that is not a directory
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Io);
    }
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"file", "taken.glb"}));
}

TEST(GlbExport, RefusesATrajectoryOfAnotherModelOrScene) {
    TempDir dir;
    const Model m = test_model();
    Trajectory t = test_trajectory(m);
    t.pieces = 2;  // same poses, read as 2 pieces + 2 props
    try {
        export_glb(m, t, dir.file("a.glb"));
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        EXPECT_NE(std::string(e.what()).find("2 pieces but the model has 3"), std::string::npos) << e.what();
    }
    Trajectory no_scene = test_trajectory(m);
    no_scene.settings_json = "{}";  // 2 props, but no scene describing them
    try {
        export_glb(m, no_scene, dir.file("a.glb"));
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        EXPECT_NE(std::string(e.what()).find("kinematic bodies"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(dir.entries().empty());
}

// Where scripts/install-node-tools.sh put the validator: $SHATTER_NODE_MODULES, else
// BUILD/node_modules (BUILD: the build tree of the shatter binary under test), else
// ~/.cache/shatter/node/node_modules.
std::optional<std::string> validator_modules() {
    std::vector<fs::path> candidates;
    if (const char* env = std::getenv("SHATTER_NODE_MODULES")) candidates.emplace_back(env);
    candidates.push_back(fs::path(SHATTER_BINARY).parent_path().parent_path() / "node_modules");
    if (const char* home = std::getenv("HOME")) candidates.push_back(fs::path(home) / ".cache/shatter/node/node_modules");
    for (const fs::path& c : candidates)
        if (fs::exists(c / "gltf-validator" / "package.json")) return c.string();
    return std::nullopt;
}

// Runs tests/pipeline/validate_gltf.js (the Khronos glTF validator) on `glb`; its first line reads
// "errors N warnings M". Returns N, or -1 when the validator did not run; *out gets its output,
// or why it did not run.
int validator_errors(const std::string& node, const std::string& modules, const std::string& glb, std::string* out) {
    const std::string driver = std::string(SHATTER_SOURCE_DIR) + "/tests/pipeline/validate_gltf.js";
    const ProcessResult r = run_process({node, driver, modules, glb});
    if (!r.ok()) {
        *out = r.describe() + "\n" + r.err;
        return -1;
    }
    *out = r.out;
    std::istringstream summary(r.out);
    std::string word;
    int errors = -1;
    summary >> word >> errors;
    return errors;
}

TEST(GlbExport, KhronosValidatorReportsNoErrors) {
    const auto node = find_program("node");
    if (!node) GTEST_SKIP() << "node is not installed (fix: apt-get install nodejs npm)";
    const auto modules = validator_modules();
    if (!modules)
        GTEST_SKIP() << "the npm package gltf-validator is not installed (fix: bash scripts/install-node-tools.sh "
                        "BUILD_DIR, or set SHATTER_NODE_MODULES)";
    TempDir dir;
    const Model m = test_model();
    export_glb(m, test_trajectory(m), dir.file("a.glb"));
    std::string out;
    ASSERT_EQ(validator_errors(*node, *modules, dir.file("a.glb"), &out), 0) << out;
    std::cout << "gltf-validator: " << out.substr(0, out.find('\n')) << "\n";
}

// With render settings, the camera render draws with: a node "camera" holding a perspective
// camera of the shot's field of view and aspect, keyed at every frame when it follows the
// pieces (render/camera_path.h), at the fixed camera's pose otherwise; the validator accepts it.
TEST(GlbExport, HoldsRendersCameraAnimatedWhenItMoves) {
    TempDir dir;
    const Model m = test_model();
    const Trajectory t = test_trajectory(m);
    RenderSettings follow;
    follow.fov = 40;
    export_glb(m, t, dir.file("follow.glb"), &follow);
    RenderScene rs;
    rs.model = &m;
    rs.trajectory = &t;
    rs.scene = test_scene();
    const std::vector<Camera> path = make_camera_path(rs, follow);
    ASSERT_EQ(path.size(), kFrames);
    {
        Imported g(dir.file("follow.glb"));
        ASSERT_TRUE(g.scene);
        ASSERT_EQ(g.scene->mNumCameras, 1u);
        const aiCamera* c = g.scene->mCameras[0];
        EXPECT_STREQ(c->mName.C_Str(), "camera");
        EXPECT_NEAR(c->mAspect, 1280.0 / 720.0, 1e-5);
        // assimp 5.2's importer reads glTF's yfov times the aspect into mHorizontalFOV.
        EXPECT_NEAR(c->mHorizontalFOV / c->mAspect, 40 * M_PI / 180, 1e-5);
        const aiNodeAnim* ch = g.channel("camera");
        ASSERT_TRUE(ch);
        ASSERT_EQ(ch->mNumPositionKeys, kFrames);
        for (uint32_t f = 0; f < kFrames; ++f) {
            for (int i = 0; i < 3; ++i) EXPECT_NEAR(ch->mPositionKeys[f].mValue[i], path[f].position[i], 1e-5) << f;
            // The camera looks down its -z: the rotated -z is the direction to the target.
            const aiQuaternion& q = ch->mRotationKeys[f].mValue;
            const Eigen::Vector3f look = Eigen::Quaternionf(q.w, q.x, q.y, q.z) * Eigen::Vector3f(0, 0, -1);
            EXPECT_NEAR((look - (path[f].target - path[f].position).normalized()).norm(), 0, 1e-5) << f;
        }
        // What a DCC tool computes from the keys, the view matrix (the inverse of the node's
        // transform [R | p]: [R^T | -R^T p]), is the matrix render draws frame f with.
        double worst = 0;
        for (uint32_t f = 0; f < kFrames; ++f) {
            const aiQuaternion& q = ch->mRotationKeys[f].mValue;
            const aiVector3D& p = ch->mPositionKeys[f].mValue;
            const Eigen::Matrix3d r = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
            Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
            view.block<3, 3>(0, 0) = r.transpose();
            view.block<3, 1>(0, 3) = -r.transpose() * Eigen::Vector3d(p.x, p.y, p.z);
            worst = std::max(worst, (view - path[f].view.cast<double>()).cwiseAbs().maxCoeff());
        }
        EXPECT_LT(worst, 1e-6);
        std::cout << "camera: the keys' view matrices within " << worst << " of render's\n";
        EXPECT_GT((path.front().position - path.back().position).norm(), 1e-3);  // it does move
    }
    RenderSettings placed = follow;
    placed.camera_position = Vec3(1, 2, 3);
    placed.camera_target = Vec3(0, 0.5, 0);
    export_glb(m, t, dir.file("placed.glb"), &placed);
    Imported g(dir.file("placed.glb"));
    ASSERT_TRUE(g.scene);
    EXPECT_FALSE(g.channel("camera"));  // it does not move
    aiVector3D scale, position;
    aiQuaternion rotation;
    g.node("camera")->mTransformation.Decompose(scale, rotation, position);
    EXPECT_NEAR(position.x, 1, 1e-6);
    EXPECT_NEAR(position.y, 2, 1e-6);
    EXPECT_NEAR(position.z, 3, 1e-6);
    const auto node = find_program("node");
    const auto modules = validator_modules();
    if (!node || !modules) GTEST_SKIP() << "node or gltf-validator missing: the validator part is skipped";
    for (const char* name : {"follow.glb", "placed.glb"}) {
        std::string out;
        EXPECT_EQ(validator_errors(*node, *modules, dir.file(name), &out), 0) << name << ": " << out;
    }
}

// A 1,000-piece model (10 x 10 x 10 boxes, past the palette's 36-colour cycle): every node and
// key is there. Few frames: assimp's exporter costs O(accessors x file size) (1,000 pieces x
// 121 frames took ~7 s here), so the scale test keeps the file small. Prints the time; never
// fails on it.
TEST(GlbExport, AThousandPieceModelExportsEveryNodeAndKey) {
    constexpr uint32_t kFewFrames = 11;
    TempDir dir;
    const Model m = box_grid(10, 10, 10, 0.1, Vec3(0, 0, 0), 1000, 1);
    Trajectory t;
    t.fps = 30;
    t.pieces = uint32_t(m.pieces.size());
    for (uint32_t f = 0; f < kFewFrames; ++f)
        for (uint32_t b = 0; b < t.pieces; ++b) {
            BodyPose p;
            p.position = m.pieces[b].mass.center.cast<float>() + Eigen::Vector3f(0, -0.01f * f, 0);
            p.rotation = Eigen::AngleAxisf(0.01f * f, Eigen::Vector3f::UnitY());
            t.poses.push_back(p);
        }
    const auto start = std::chrono::steady_clock::now();
    export_glb(m, t, dir.file("big.glb"));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "export_glb: 1000 pieces x " << kFewFrames << " frames in " << seconds << " s, "
              << fs::file_size(dir.file("big.glb")) << " bytes\n";
    Imported g(dir.file("big.glb"));
    ASSERT_TRUE(g.scene);
    EXPECT_EQ(g.scene->mRootNode->mNumChildren, 1000u);
    EXPECT_EQ(g.scene->mNumMeshes, 1000u);
    ASSERT_EQ(g.scene->mAnimations[0]->mNumChannels, 1000u);
    const aiNodeAnim* last = g.channel("piece_999");
    ASSERT_TRUE(last);
    EXPECT_EQ(last->mNumPositionKeys, kFewFrames);
    EXPECT_NEAR(last->mPositionKeys[kFewFrames - 1].mValue.y, m.pieces[999].mass.center.y() - 0.1, 1e-5);
    const RenderSettings look;  // render's defaults: a model without materials in material_colour
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(g.base_colour(g.scene->mMeshes[g.node("piece_999")->mMeshes[0]])[i],
                                            look.material_colour[size_t(i)], 1e-6);
}

// scripts/crack_creases.py (docs/render.md, "Faired cracks") reads the crack faces back from a
// .glb as prescore made them: the same inner edges, creases and crease length per area as
// crack_creases() counts on the model's render surfaces (float positions in the file: within 1%).
// A 10 cm cube prescored into 4 pieces at resolution 10 (its OBJ written into `dir`).
Model prescored_cube(TempDir& dir, bool crack_fairing) {
    std::string cube;
    for (const auto& c : kCorners) cube += fmt::format("v {} {} {}\n", c[0], c[1], c[2]);
    for (const auto& f : kFaces) cube += fmt::format("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    MeshSettings mesh;
    mesh.path = dir.write("cube.obj", cube);
    mesh.scale = 0.1;
    PrescoreSettings settings;
    settings.pieces = 4;
    settings.resolution = 10;
    settings.crack_fairing = crack_fairing;
    return prescore(mesh, settings, nullptr);
}

TEST(GlbExport, TheCreaseScriptMeasuresTheCracksAsPrescoreDoes) {
    TempDir dir;
    const Model m = prescored_cube(dir, false);  // its cracks the tet faces (creased)
    export_glb(m, test_trajectory(m, kFrames, false), dir.file("r.glb"));
    const auto r = run_command({"/usr/bin/python3", SHATTER_SOURCE_DIR "/scripts/crack_creases.py", "--json", dir.file("r.glb")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json got = nlohmann::json::parse(r.out);
    std::vector<RenderSurface> surfaces;
    for (const Piece& p : m.pieces) surfaces.push_back(*p.render);
    const CrackCreases want = crack_creases(surfaces, 1.0);
    ASSERT_GT(want.inner_edges, 10u);
    ASSERT_GT(want.creases, 0u);
    EXPECT_EQ(got["inner_edges"].get<size_t>(), want.inner_edges);
    EXPECT_EQ(got["creases"].get<size_t>(), want.creases);
    EXPECT_NEAR(got["crack_area_m2"].get<double>(), want.area, 0.01 * want.area);
    EXPECT_NEAR(got["density"].get<double>() / got["diagonal_m"].get<double>(), want.density, 0.01 * want.density);
}

// A model with render surfaces (tests/fixtures/model-v2.model: a 10 cm cube in 2 pieces): each
// piece exports its render surface, indexed, with its normals (the cube's outer faces: the axes),
// one primitive per face kind, and the Khronos validator reports no errors.
TEST(GlbExport, RenderSurfacesExportIndexedWithTheirNormals) {
    TempDir dir;
    const Model m = load_model(SHATTER_SOURCE_DIR "/tests/fixtures/model-v2.model");
    export_glb(m, test_trajectory(m, kFrames, false), dir.file("r.glb"));
    Imported g(dir.file("r.glb"));
    ASSERT_TRUE(g.scene);
    for (uint32_t i = 0; i < m.pieces.size(); ++i) {
        ASSERT_TRUE(m.pieces[i].render);
        const aiNode* n = g.node(fmt::format("piece_{}", i));
        ASSERT_TRUE(n);
        size_t faces = 0, vertices = 0;
        for (unsigned k = 0; k < n->mNumMeshes; ++k) {
            const aiMesh* mesh = g.scene->mMeshes[n->mMeshes[k]];
            ASSERT_TRUE(mesh->HasNormals());
            faces += mesh->mNumFaces;
            vertices += mesh->mNumVertices;
            for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
                const aiVector3D& nv = mesh->mNormals[v];
                EXPECT_NEAR(nv.Length(), 1.0, 1e-5);
                aiString material;
                g.scene->mMaterials[mesh->mMaterialIndex]->Get(AI_MATKEY_NAME, material);
                if (std::string(material.C_Str()).find("outer") != std::string::npos) {
                    EXPECT_NEAR(std::max({std::abs(nv.x), std::abs(nv.y), std::abs(nv.z)}), 1.0, 1e-5);
                }
            }
        }
        EXPECT_EQ(faces, m.pieces[i].render->triangles.size());
        EXPECT_LT(vertices, 3 * faces);  // indexed: the triangles share vertices
    }
    const auto node = find_program("node");
    const auto modules = validator_modules();
    if (!node || !modules) GTEST_SKIP() << "node or gltf-validator missing: the validator part is skipped";
    std::string out;
    EXPECT_EQ(validator_errors(*node, *modules, dir.file("r.glb"), &out), 0) << out;
}

}  // namespace
}  // namespace shatter

namespace shatter {
namespace {

// The GLB's JSON chunk and its binary chunk.
std::pair<nlohmann::json, std::string> glb_chunks(const std::string& bytes) {
    auto u32 = [&](size_t at) {
        uint32_t v = 0;
        std::memcpy(&v, bytes.data() + at, 4);
        return v;
    };
    const uint32_t json_length = u32(12);
    const size_t bin = 20 + json_length;
    return {nlohmann::json::parse(bytes.substr(20, json_length)), bytes.substr(bin + 8, u32(bin))};
}

// A textured input keeps its texture in the .glb: assimp-testmodels' duck (its TGA texture
// beside the Collada file) in 6 pieces exports one image, stored in the binary chunk as PNG
// (glTF allows PNG and JPEG only) that decodes to the texture's 512 x 512, a texture naming it,
// an outer material whose baseColorTexture resolves to it, outer primitives with TEXCOORD_0
// using that material, fracture primitives with their own (CrackUv) and untextured materials;
// and the Khronos validator finds no error.
TEST(GlbExport, ATexturedInputEmbedsItsTextureWithTexcoords) {
    if (!fs::exists(testing_support::kDuck))
        GTEST_SKIP() << testing_support::kDuck << " is missing (fix: scripts/install-deps.sh)";
    const Model m = testing_support::prescore_duck();
    TempDir dir;
    export_glb(m, test_trajectory(m, 3, false), dir.file("duck.glb"));
    std::ifstream in(dir.file("duck.glb"), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto [j, bin] = glb_chunks(bytes);
    ASSERT_EQ(j["images"].size(), 1u);
    const auto& image = j["images"][0];
    EXPECT_EQ(image["mimeType"], "image/png");
    const auto& view = j["bufferViews"][image["bufferView"].get<size_t>()];
    const std::string png = bin.substr(view.value("byteOffset", size_t(0)), view["byteLength"].get<size_t>());
    std::string why;
    const auto decoded = decode_image(png, &why);
    ASSERT_TRUE(decoded) << why;
    EXPECT_EQ(decoded->width, 512u);
    EXPECT_EQ(decoded->height, 512u);
    ASSERT_EQ(j["textures"].size(), 1u);
    EXPECT_EQ(j["textures"][0]["source"], 0);
    std::set<size_t> textured_materials;
    for (size_t i = 0; i < j["materials"].size(); ++i) {
        const auto& pbr = j["materials"][i]["pbrMetallicRoughness"];
        if (pbr.contains("baseColorTexture")) {
            EXPECT_EQ(pbr["baseColorTexture"]["index"], 0);
            textured_materials.insert(i);
        }
    }
    ASSERT_EQ(textured_materials.size(), 1u);
    size_t textured = 0, fracture = 0;
    for (const auto& mesh_json : j["meshes"])
        for (const auto& p : mesh_json["primitives"]) {
            const size_t material = p["material"].get<size_t>();
            const std::string name = j["materials"][material].value("name", "");
            const bool crack = name.size() > 9 && name.substr(name.size() - 9) == "_fracture";
            EXPECT_EQ(p["attributes"].contains("TEXCOORD_0"), textured_materials.count(material) == 1 || crack) << name;
            textured += textured_materials.count(material);
            fracture += crack;
        }
    EXPECT_EQ(textured, m.pieces.size());  // every piece shows some of the duck's outside
    EXPECT_GT(fracture, 0u);               // and its fracture faces
    ::testing::Test::RecordProperty("glb_bytes", std::to_string(bytes.size()));

    const auto node = find_program("node");
    const auto modules = validator_modules();
    if (!node || !modules) GTEST_SKIP() << "node or gltf-validator missing: the validator part is skipped";
    std::string out;
    ASSERT_EQ(validator_errors(*node, *modules, dir.file("duck.glb"), &out), 0) << out;
    std::cout << "gltf-validator (duck): " << out.substr(0, out.find('\n')) << "\n";
}

}  // namespace
}  // namespace shatter

namespace shatter {
namespace {

// A 10 cm cube as an ASCII PLY whose bottom corners are red and top corners blue.
std::string coloured_cube_ply() {
    std::string s = "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
                    "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 12\n"
                    "property list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < 8; ++i)
        s += fmt::format("{} {} {} {}\n", i & 1 ? 0.1 : 0.0, i & 2 ? 0.1 : 0.0, i & 4 ? 0.1 : 0.0,
                         i & 2 ? "0 0 255" : "255 0 0");
    // Outward triangles of the six faces (corner i at x = bit 0, y = bit 1, z = bit 2).
    for (const char* f : {"0 2 3", "0 3 1", "4 5 7", "4 7 6", "0 1 5", "0 5 4", "2 6 7", "2 7 3", "0 4 6", "0 6 2",
                          "1 3 7", "1 7 5"})
        s += fmt::format("3 {}\n", f);
    return s;
}

// Vertex colours reach the .glb: every outer primitive of a cube whose PLY has vertex colours
// carries COLOR_0 (red at the bottom, blue at the top, so some of each), its material white;
// fracture primitives none; the validator finds no error.
TEST(GlbExport, AnInputsVertexColoursBecomeColor0) {
    TempDir dir;
    MeshSettings mesh;
    mesh.path = dir.write("cube.ply", coloured_cube_ply());
    PrescoreSettings settings;
    settings.pieces = 2;
    settings.resolution = 4;
    const Model m = prescore(mesh, settings, nullptr);
    ASSERT_FALSE(m.materials.empty());
    for (const Piece& p : m.pieces) ASSERT_EQ(p.render->colour.size(), p.render->vertices.size());
    export_glb(m, test_trajectory(m, 3, false), dir.file("cube.glb"));
    Imported g(dir.file("cube.glb"));
    ASSERT_TRUE(g.scene);
    size_t coloured = 0, plain = 0;
    double reddest = 0, bluest = 0;
    for (unsigned i = 0; i < g.scene->mNumMeshes; ++i) {
        const aiMesh* mesh_i = g.scene->mMeshes[i];
        if (!mesh_i->HasVertexColors(0)) {
            ++plain;
            continue;
        }
        ++coloured;
        const Colour base = g.base_colour(mesh_i);
        for (float c : base) EXPECT_NEAR(c, 1.0, 1e-6);
        for (unsigned v = 0; v < mesh_i->mNumVertices; ++v) {
            const aiColor4D& c = mesh_i->mColors[0][v];
            reddest = std::max(reddest, double(c.r - c.b));
            bluest = std::max(bluest, double(c.b - c.r));
        }
    }
    EXPECT_EQ(coloured, m.pieces.size());
    EXPECT_GT(plain, 0u);  // the fracture faces
    EXPECT_GT(reddest, 0.99);
    EXPECT_GT(bluest, 0.99);

    const auto node = find_program("node");
    const auto modules = validator_modules();
    if (!node || !modules) GTEST_SKIP() << "node or gltf-validator missing: the validator part is skipped";
    std::string out;
    ASSERT_EQ(validator_errors(*node, *modules, dir.file("cube.glb"), &out), 0) << out;
}

// The crack faces' texture coordinates of `glb` (exported from `m`): each vertex's point in the
// unbroken object (vertex + its piece's centre of mass), over the tet mesh's bounding box in
// units of `unit` (m; 0: its diagonal), projected along its normal's largest axis; both sides of
// a crack, the same points, get the same coordinates. Their material's name.
std::string expect_crack_texcoords(const Model& m, const std::string& glb, double unit) {
    Imported g(glb);
    EXPECT_TRUE(g.scene);
    if (!g.scene) return "";
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
    for (const Vec3& v : m.mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const double diagonal = unit > 0 ? unit : (hi - lo).norm();
    std::string material;
    // Per crack triangle (by its corners' points, 0.1 um): the piece it was first seen in and its
    // corners' coordinates by point.
    using Point = std::array<long long, 3>;
    std::map<std::array<Point, 3>, std::pair<uint32_t, std::map<Point, aiVector3D>>> seen;
    size_t checked = 0, shared = 0;
    for (uint32_t p = 0; p < m.pieces.size(); ++p) {
        const aiNode* n = g.node(fmt::format("piece_{}", p));
        EXPECT_TRUE(n);
        if (!n) return "";
        for (unsigned k = 0; k < n->mNumMeshes; ++k) {
            const aiMesh* part = g.scene->mMeshes[n->mMeshes[k]];
            aiString name;
            g.scene->mMaterials[part->mMaterialIndex]->Get(AI_MATKEY_NAME, name);
            if (std::string(name.C_Str()).find("fracture") == std::string::npos) continue;
            material = name.C_Str();
            EXPECT_TRUE(part->HasTextureCoords(0)) << name.C_Str();
            if (!part->HasTextureCoords(0)) return "";
            std::vector<Point> point(part->mNumVertices);
            for (unsigned i = 0; i < part->mNumVertices; ++i) {
                const Vec3 x = Vec3(part->mVertices[i].x, part->mVertices[i].y, part->mVertices[i].z) + m.pieces[p].mass.center;
                const Vec3 u = (x - lo) / diagonal;
                const Vec3 normal = Vec3(part->mNormals[i].x, part->mNormals[i].y, part->mNormals[i].z).cwiseAbs();
                const int axis = normal.x() >= normal.y() && normal.x() >= normal.z() ? 0 : (normal.y() >= normal.z() ? 1 : 2);
                const int a = axis == 0 ? 1 : 0, b = axis == 2 ? 1 : 2;
                const aiVector3D& t = part->mTextureCoords[0][i];  // assimp's convention: v up
                EXPECT_NEAR(t.x, u[a], 1e-5);
                EXPECT_NEAR(1 - t.y, u[b], 1e-5);
                ++checked;
                point[i] = {std::llround(x.x() * 1e7), std::llround(x.y() * 1e7), std::llround(x.z() * 1e7)};
            }
            for (unsigned f = 0; f < part->mNumFaces; ++f) {
                const unsigned* c = part->mFaces[f].mIndices;
                std::array<Point, 3> key = {point[c[0]], point[c[1]], point[c[2]]};
                std::sort(key.begin(), key.end());
                std::map<Point, aiVector3D> uv;
                for (int j = 0; j < 3; ++j) uv[point[c[j]]] = part->mTextureCoords[0][c[j]];
                const auto [it, fresh] = seen.emplace(key, std::make_pair(p, uv));
                if (fresh || it->second.first == p) continue;
                ++shared;  // the same triangle on the crack's other side
                for (const auto& [at, t] : uv) {
                    EXPECT_NEAR(it->second.second[at].x, t.x, 1e-5);
                    EXPECT_NEAR(it->second.second[at].y, t.y, 1e-5);
                }
            }
        }
    }
    EXPECT_GT(checked, 50u);
    EXPECT_GT(shared, 10u);  // triangles seen from both sides
    return material;
}

// Crack faces carry texture coordinates (an interior texture set in the user's tool can use
// them), in units of the object's diagonal.
TEST(GlbExport, CrackFacesHaveBoxProjectedTexcoordsThatAgreeAcrossEachCrack) {
    TempDir dir;
    const Model m = prescored_cube(dir, true);
    export_glb(m, test_trajectory(m, kFrames, false), dir.file("c.glb"));
    expect_crack_texcoords(m, dir.file("c.glb"), 0);
}

// With [render] interior_texture, the crack faces share one material whose base colour texture is
// that image, embedded, and their coordinates count its repeats (interior_texture_size).
TEST(GlbExport, AnInteriorTextureIsEmbeddedOnTheCrackFacesInItsRepeats) {
    TempDir dir;
    const Model m = prescored_cube(dir, true);
    Image stone(8, 8);
    for (size_t i = 0; i < stone.rgb.size(); ++i) stone.rgb[i] = uint8_t(37 * i);
    save_png(dir.file("stone.png"), stone);
    RenderSettings look;
    look.interior_texture = dir.file("stone.png");
    look.interior_texture_size = 0.02;
    export_glb(m, test_trajectory(m, kFrames, false), dir.file("c.glb"), &look);
    EXPECT_EQ(expect_crack_texcoords(m, dir.file("c.glb"), 0.02), "interior_fracture");
    Imported g(dir.file("c.glb"));
    ASSERT_TRUE(g.scene);
    const aiMaterial* interior = nullptr;
    for (unsigned i = 0; i < g.scene->mNumMaterials; ++i) {
        aiString name;
        g.scene->mMaterials[i]->Get(AI_MATKEY_NAME, name);
        if (std::string(name.C_Str()) == "interior_fracture") interior = g.scene->mMaterials[i];
    }
    ASSERT_TRUE(interior);
    aiString path;
    ASSERT_EQ(interior->GetTexture(aiTextureType_BASE_COLOR, 0, &path), AI_SUCCESS);
    const aiTexture* embedded = g.scene->GetEmbeddedTexture(path.C_Str());
    ASSERT_TRUE(embedded);
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(embedded->pcData), embedded->mWidth),
              read_file(dir.file("stone.png")));  // the PNG as it is
}

}  // namespace
}  // namespace shatter
