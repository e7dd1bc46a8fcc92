// `shatter run` driven like a user drives it: every output in one folder, stages skipped when up
// to date and re-run when their inputs change, and a run killed at any moment that resumes to the
// same bytes as an uninterrupted one.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <thread>

#include <nlohmann/json.hpp>

#include "support/cube_shot.h"
#include "support/run_command.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

namespace fs = std::filesystem;
using testing_support::run_shatter;
using testing_support::stage_status;
using testing_support::slurp;
using testing_support::TempDir;
using testing_support::kCubeShot;
using testing_support::write_cube_shot;

// A 10 cm cube in 4 pieces dropped from 0.5 m: 16 frames of 160x90, a couple of seconds in all.

int run_command_status(const std::vector<std::string>& args) { return testing_support::run_command(args).exit_code; }

// Every file of an output folder (recursively) and its bytes, except the two that have times: the
// log and the report's stage times.
std::map<std::string, std::string> folder_bytes(const std::string& dir) {
    std::map<std::string, std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        if (!e.is_regular_file()) continue;
        const std::string rel = fs::relative(e.path(), dir).string();
        if (rel == "run.log" || rel == "report.times.js") continue;
        out[rel] = slurp(e.path().string());
    }
    return out;
}

TEST(RunCommand, WritesEveryOutputIntoOneFolderAndSkipsWhatIsUpToDate) {
    TempDir dir;
    const std::string shot = write_cube_shot(dir);
    const std::string out = dir.file("out");
    auto r = run_shatter({"run", shot, "-o", out, "--no-progress"});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    for (const char* f : {"cube.model", "cube.pieces.ply", "cube.traj", "cube.breaks.jsonl", "cube.energy.csv",
                          "cube.mp4", "cube.contact.png", "cube.energy.png", "cube.glb", "summary.json", "run.log", "report.html",
                          "frames/frame_00000.png", "frames/frame_00015.png"})
        EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
    EXPECT_FALSE(fs::exists(fs::path(out) / "frames/frame_00016.png"));  // 0.5 s at 30 fps: 16 frames
    EXPECT_NE(r.out.find("stages:"), std::string::npos);
    EXPECT_NE(r.out.find("results:"), std::string::npos);
    // The energy books close to round-off over the whole run (the drop gives ~1 J), and the summary
    // says so.
    const nlohmann::json summary = nlohmann::json::parse(slurp(out + "/summary.json"));
    const nlohmann::json& sim = summary.at("simulation");
    ASSERT_TRUE(sim.contains("energy_books_drift_J")) << sim.dump();
    EXPECT_LT(sim["energy_books_drift_J"].get<double>(), 1e-6) << sim.dump();
    EXPECT_NE(r.out.find("energy:   kinetic + potential"), std::string::npos) << r.out;
    const std::string log = slurp(out + "/run.log");
    EXPECT_NE(log.find("simulate: ran"), std::string::npos) << log;

    const auto before = folder_bytes(out);
    auto again = run_shatter({"run", shot, "-o", out, "--no-progress"});
    ASSERT_EQ(again.exit_code, 0) << again.err;
    for (const char* stage : {"prescore", "simulate", "render", "encode", "sheet", "plot", "export", "report"})
        EXPECT_NE(stage_status(again.out, stage).find("(up to date)"), std::string::npos) << stage << "\n" << again.out;
    EXPECT_EQ(folder_bytes(out), before);
}

// A material too strong for the drop breaks nothing; at a fixed step the user chose (h = 1/240 s)
// its joints' omega h is far above 1, so the impact's force was resolved to a fraction of its
// peak, and the run says which setting resolves it. The weak cube breaks and is told nothing, nor
// is a run that ends before the cube lands.
TEST(RunCommand, AStiffMaterialThatBreaksNothingIsToldHowToResolveItsImpact) {
    TempDir dir;
    const std::string shot = write_cube_shot(dir);
    auto weak = run_shatter({"run", shot, "-o", dir.file("weak"), "--no-progress", "--stages", "prescore,simulate",
                             "--set", "simulate.substeps=8"});
    ASSERT_EQ(weak.exit_code, 0) << weak.out << weak.err;
    EXPECT_EQ((weak.out + weak.err).find("no joint broke"), std::string::npos) << weak.out << weak.err;
    auto strong = run_shatter({"run", shot, "-o", dir.file("strong"), "--no-progress", "--stages", "prescore,simulate",
                               "--set", "material.strength=1e9", "--set", "simulate.substeps=8"});
    ASSERT_EQ(strong.exit_code, 0) << strong.out << strong.err;
    const std::string said = strong.out + strong.err;
    EXPECT_NE(said.find("no joint broke"), std::string::npos) << said;
    EXPECT_NE(said.find("substeps = \"auto\" (the default"), std::string::npos) << said;
    // The summary at the end says it again (standard output), and a run without warnings has none.
    const size_t listed = strong.out.find("\nwarnings: ");
    ASSERT_NE(listed, std::string::npos) << strong.out;
    EXPECT_NE(strong.out.find("  - simulate: no joint broke", listed), std::string::npos) << strong.out;
    EXPECT_EQ(weak.out.find("warnings: "), std::string::npos) << weak.out;
    // The trajectory keeps it: summary.json and `shatter info` show it, and a run that finds
    // simulate up to date (nothing logged) still lists it at the end.
    const nlohmann::json summary = nlohmann::json::parse(slurp(dir.file("strong/summary.json")));
    size_t kept = 0;
    for (const auto& w : summary["simulation"].value("warnings", nlohmann::json::array()))
        kept += w.get<std::string>().rfind("simulate: no joint broke", 0) == 0;
    EXPECT_EQ(kept, 1u) << summary.dump(2);
    EXPECT_FALSE(nlohmann::json::parse(slurp(dir.file("weak/summary.json")))["simulation"].contains("warnings"));
    std::string traj;
    for (const auto& e : fs::directory_iterator(dir.file("strong")))
        if (e.path().extension() == ".traj") traj = e.path().string();
    const auto info = run_shatter({"info", traj});
    EXPECT_NE(info.out.find("warning       simulate: no joint broke"), std::string::npos) << info.out;
    auto again = run_shatter({"run", shot, "-o", dir.file("strong"), "--no-progress", "--stages", "prescore,simulate",
                              "--set", "material.strength=1e9", "--set", "simulate.substeps=8"});
    ASSERT_EQ(again.exit_code, 0) << again.out << again.err;
    EXPECT_NE(stage_status(again.out, "simulate").find("(up to date)"), std::string::npos) << again.out;
    EXPECT_EQ(again.err.find("no joint broke"), std::string::npos) << again.err;
    EXPECT_NE(again.out.find("  - simulate: no joint broke"), std::string::npos) << again.out;
    // Still in the air at the end (0.2 s of its 0.3 s fall): no impact, nothing to warn of.
    auto falling = run_shatter({"run", shot, "-o", dir.file("falling"), "--no-progress", "--stages", "prescore,simulate",
                                "--set", "material.strength=1e9", "--set", "simulate.duration=0.2", "--set",
                                "simulate.substeps=8"});
    ASSERT_EQ(falling.exit_code, 0) << falling.out << falling.err;
    EXPECT_EQ((falling.out + falling.err).find("no joint broke"), std::string::npos) << falling.out << falling.err;
}

// A mesh file whose name is not UTF-8 (a Latin-1 name, as files from elsewhere may have): its
// outputs are named in UTF-8 (the name read as Latin-1), and the model's settings, summary.json
// and the stamps hold valid text; before, writing the model's settings JSON stopped prescore.
TEST(RunCommand, AMeshNamedInLatin1RunsWithItsOutputsNamedInUtf8) {
    TempDir dir;
    const std::string mesh = dir.file("b\xe6r.obj");  // "bær" in Latin-1
    fs::copy_file(SHATTER_SOURCE_DIR "/tests/fixtures/cube.obj", mesh);
    const std::string out = dir.file("out");
    const auto r = run_shatter({"run", mesh, "-o", out, "--no-progress", "--stages", "prescore,simulate",
                                "--set", "simulate.duration=0.3"});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_TRUE(fs::exists(fs::path(out) / "b\xc3\xa6r.model"));
    const nlohmann::json summary = nlohmann::json::parse(slurp(out + "/summary.json"));
    EXPECT_EQ(summary["files"]["model"], "b\xc3\xa6r.model");
    EXPECT_EQ(fs::path(summary["shot"].get<std::string>()).filename().string(), "b\xc3\xa6r.obj");
    // The stamps hold the names the outputs have: a second run finds every stage up to date.
    const auto again = run_shatter({"run", mesh, "-o", out, "--no-progress", "--stages", "prescore,simulate",
                                    "--set", "simulate.duration=0.3"});
    ASSERT_EQ(again.exit_code, 0) << again.out << again.err;
    EXPECT_NE(stage_status(again.out, "simulate").find("(up to date)"), std::string::npos) << again.out;
}

TEST(RunCommand, ChangingAlphaRedoesSimulateAndAfterButNotPrescore) {
    TempDir dir;
    const std::string shot = write_cube_shot(dir);
    const std::string out = dir.file("out");
    ASSERT_EQ(run_shatter({"run", shot, "-o", out, "--no-progress"}).exit_code, 0);
    auto r = run_shatter({"run", shot, "-o", out, "--no-progress", "--set", "material.alpha=0"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(stage_status(r.out, "prescore").find("(up to date)"), std::string::npos) << r.out;
    for (const char* stage : {"simulate", "render", "encode", "sheet", "plot", "export", "report"}) {
        const std::string status = stage_status(r.out, stage);
        EXPECT_FALSE(status.empty()) << stage << "\n" << r.out;
        EXPECT_EQ(status.find("("), std::string::npos) << stage << " should have run: " << status;
    }
    EXPECT_NE(slurp(out + "/summary.json").find("\"alpha\": 0.0"), std::string::npos);
}

// The mesh's material library and texture are inputs of prescore as much as the mesh file is.
TEST(RunCommand, ChangingTheMeshsTextureRedoesPrescore) {
    TempDir dir;
    const std::string shot = write_cube_shot(dir);
    const std::string out = dir.file("out");
    {
        std::ofstream obj(dir.file("cube.obj"), std::ios::app);
        obj << "mtllib cube.mtl\n";
    }
    dir.write("cube.mtl", "newmtl white\nKd 1 1 1\nmap_Kd skin.png\n");
    dir.write("skin.png", "one");
    const std::vector<std::string> run = {"run", shot, "-o", out, "--no-progress", "--stages", "prescore"};
    ASSERT_EQ(run_shatter(run).exit_code, 0);
    auto same = run_shatter(run);
    EXPECT_NE(stage_status(same.out, "prescore").find("(up to date)"), std::string::npos) << same.out;
    dir.write("skin.png", "two");
    auto changed = run_shatter(run);
    ASSERT_EQ(changed.exit_code, 0) << changed.err;
    EXPECT_EQ(stage_status(changed.out, "prescore").find("("), std::string::npos) << changed.out;
}

TEST(RunCommand, BadOverridesAndStagesAreRefusedBeforeAnythingIsWritten) {
    TempDir dir;
    const std::string shot = write_cube_shot(dir);
    auto r = run_shatter({"run", shot, "-o", dir.file("out"), "--set", "material.alpha=-2"});
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_NE(r.err.find("--set material.alpha=-2"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir.file("out")));
    r = run_shatter({"run", shot, "-o", dir.file("out"), "--stages", "render,movie"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("'movie' is not a stage"), std::string::npos) << r.err;
    r = run_shatter({"run", shot, "-o", dir.file("out"), "--stages", "render"});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find("missing or out of date"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--stages prescore"), std::string::npos) << r.err;
    r = run_shatter({"run", dir.file("nope.toml")});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find("nope.toml"), std::string::npos) << r.err;
}

// Starts `shatter run`, waits until `ready` holds (or the run ends), and kills it with SIGKILL.
// Returns true when the kill landed before the run ended.
bool kill_when(const std::vector<std::string>& args, const std::function<bool()>& ready) {
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, 1);
        ::dup2(null, 2);
        std::vector<char*> argv;
        std::string exe = SHATTER_BINARY;
        argv.push_back(exe.data());
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    int status = 0;
    for (;;) {
        if (::waitpid(pid, &status, WNOHANG) == pid) return false;  // ended before the moment came
        if (ready()) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    return WIFSIGNALED(status);
}

TEST(RunCommand, KilledAtAnyMomentAndRunAgainItEndsWithTheSameBytes) {
    TempDir dir;
    const std::string shot = write_cube_shot(dir);
    const std::string reference = dir.file("reference");
    ASSERT_EQ(run_shatter({"run", shot, "-o", reference, "--no-progress"}).exit_code, 0);
    const auto expected = folder_bytes(reference);

    const auto started = std::chrono::steady_clock::now();
    struct Moment {
        const char* name;
        std::function<bool(const std::string&)> ready;
    };
    const std::vector<Moment> moments = {
        {"during prescore", [&](const std::string&) { return std::chrono::steady_clock::now() - started > std::chrono::milliseconds(0); }},
        {"during simulate", [](const std::string& out) { return fs::exists(out + "/cube.model"); }},
        {"during render", [](const std::string& out) { return fs::exists(out + "/frames/frame_00004.png"); }},
        {"before encode", [](const std::string& out) { return fs::exists(out + "/frames/frame_00015.png"); }},
        {"during the finishing stages", [](const std::string& out) { return fs::exists(out + "/cube.mp4"); }},
    };
    int landed = 0;
    for (const Moment& m : moments) {
        const std::string out = dir.file(std::string("killed ") + m.name);
        landed += kill_when({"run", shot, "-o", out, "--no-progress"}, [&] { return m.ready(out); });
        auto r = run_shatter({"run", shot, "-o", out, "--no-progress"});
        ASSERT_EQ(r.exit_code, 0) << m.name << ": " << r.err;
        const auto got = folder_bytes(out);
        for (const auto& [name, bytes] : got) EXPECT_TRUE(expected.count(name)) << m.name << ": extra file " << name;
        for (const auto& [name, bytes] : expected) {
            auto it = got.find(name);
            ASSERT_NE(it, got.end()) << m.name << ": " << name << " missing";
            EXPECT_TRUE(it->second == bytes) << m.name << ": " << name << " differs";
        }
    }
    EXPECT_GE(landed, 3) << "most kills should land while the run is still going";
}

// `shatter run MESH`: a mesh file instead of a shot runs the default shot on it (the demo's
// settings, the mesh made 0.3 m long): the fixture's unit cube becomes a 0.3 m cube of
// 0.027 m^3, whose mass at the default density is 1100 kg/m^3 x 0.027 m^3 = 29.7 kg.
TEST(RunCommand, AMeshFileRunsTheDefaultShotOnIt) {
    TempDir dir;
    std::filesystem::copy_file(SHATTER_SOURCE_DIR "/tests/fixtures/cube.obj", dir.file("cube.obj"));
    const std::string out = dir.file("out");
    // (joints = "auto": the default shot's are direct, which simulate does not choose; auto takes
    // direct joints for these 4 pieces, and says so.)
    auto r = run_shatter({"run", dir.file("cube.obj"), "-o", out, "--no-progress", "--set", "simulate.duration=0.3",
                          "--set", "render.width=160", "--set", "render.height=90", "--set", "prescore.pieces=4",
                          "--set", "prescore.resolution=5", "--set", "prescore.hollow=false", "--set",
                          "simulate.joints=auto"});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    for (const char* f : {"cube.model", "cube.traj", "cube.mp4", "cube.glb", "summary.json", "frames/frame_00008.png"})
        EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
    const std::string log = slurp(out + "/run.log");
    EXPECT_NE(log.find("auto: size 0.3 m"), std::string::npos) << log;
    // What prescore chose is in the summary (JSON and the closing lines) and on the page, with why.
    const nlohmann::json summary = nlohmann::json::parse(slurp(out + "/summary.json"));
    ASSERT_TRUE(summary["model"].contains("auto")) << summary.dump(1);
    const std::string what = summary["model"]["auto"][0]["what"], why = summary["model"]["auto"][0]["why"];
    EXPECT_EQ(what.rfind("size 0.3 m", 0), 0u) << what;
    EXPECT_NE(why.find("the file has no units"), std::string::npos) << why;
    EXPECT_NE(r.out.find("chosen:   size 0.3 m"), std::string::npos) << r.out;
    // And what simulate chose: the joints' solve, by the pieces' count.
    ASSERT_TRUE(summary["simulation"].contains("auto")) << summary.dump(1);
    const std::string joints = summary["simulation"]["auto"][0]["what"];
    EXPECT_EQ(joints, "[simulate] joints = \"direct\"");
    EXPECT_NE(r.out.find("; " + joints), std::string::npos) << r.out;
    const std::string page = slurp(out + "/report.html");
    EXPECT_NE(page.find("<table id=\"chosen\">\n<tr><td class=\"muted\">prescore</td><th>size 0.3 m"), std::string::npos);
    EXPECT_NE(page.find("the file has no units"), std::string::npos);
    auto info = run_shatter({"info", out + "/cube.model"});
    ASSERT_EQ(info.exit_code, 0) << info.err;
    EXPECT_NE(info.out.find("29.7 kg"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("chosen        size 0.3 m"), std::string::npos) << info.out;
    info = run_shatter({"info", out + "/cube.traj"});
    ASSERT_EQ(info.exit_code, 0) << info.err;
    EXPECT_NE(info.out.find("chosen        " + joints), std::string::npos) << info.out;
    // A mesh that is not there is the same clear error as from a shot.
    r = run_shatter({"run", dir.file("nowhere.stl"), "-o", dir.file("a")});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find("nowhere.stl"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir.file("a")));
}

// A shot with a projectile, mesh to movie: a 2 cm steel ball (0.26 kg) thrown at the cube resting
// on the ground strikes it; the ball is drawn in the frames and exported to the .glb as the
// first prop, and its energy is in the books (the run's kinetic energy at t = 0 is the ball's).
TEST(RunCommand, AProjectileIsThrownDrawnAndExported) {
    TempDir dir;
    std::filesystem::copy_file(SHATTER_SOURCE_DIR "/tests/fixtures/cube.obj", dir.file("cube.obj"));
    std::string shot = kCubeShot;
    shot.replace(shot.find("position = [0, 0.5, 0]"), 22, "position = [0, 0, 0]\nplace = \"base\"");
    shot += R"(
[[scene.projectile]]
name = "ball"
shape = "sphere"
radius = 0.02
position = [-0.3, 0.05, 0]
velocity = [6, 0.5, 0]
)";
    const std::string out = dir.file("out");
    auto r = run_shatter({"run", dir.write("cube.toml", shot), "-o", out, "--no-progress"});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_NE(slurp(out + "/cube.glb").find("prop_0_ball"), std::string::npos);
    const std::string csv = slurp(out + "/cube.energy.csv");
    const size_t row = csv.find('\n') + 1;  // the first row, t = 0: kinetic energy after time
    const double kinetic = std::stod(csv.substr(csv.find(',', row) + 1));
    const double mass = 7800 * 4.0 / 3.0 * M_PI * 0.02 * 0.02 * 0.02;
    EXPECT_NEAR(kinetic, 0.5 * mass * (36 + 0.25), 1e-6);
    const nlohmann::json summary = nlohmann::json::parse(slurp(out + "/summary.json"));
    EXPECT_GT(summary["simulation"]["breaks"].get<int>(), 0) << summary.dump();
    // The books close to 1e-5 of the energy in play: measured 1.5e-5 J of the ball's 4.7 J at this
    // 1/240 s step with iterative joints (the cube dropped alone: 1e-8 J); the error falls with the
    // step (8e-8 J at 1/1,920 s) and with direct joints (1.5e-7 J).
    EXPECT_LT(std::abs(summary["simulation"]["energy_books_drift_J"].get<double>()), 1e-5 * kinetic) << summary.dump();
}

TEST(RunCommand, MissingMeshMalformedShotAndUnknownKeysAreClearErrors) {
    TempDir dir;
    write_cube_shot(dir);
    const std::string missing = dir.write("missing.toml", "[mesh]\npath = \"nowhere.obj\"\n");
    auto r = run_shatter({"run", missing, "-o", dir.file("a")});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find("nowhere.obj"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir.file("a/missing.model")));
    const std::string malformed = dir.write("malformed.toml", "[mesh]\npath = \"cube.obj\"\n[material\nalpha = 1\n");
    r = run_shatter({"run", malformed, "-o", dir.file("b")});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find("malformed.toml:3"), std::string::npos) << r.err;
    const std::string unknown = dir.write("unknown.toml", "[mesh]\npath = \"cube.obj\"\n[material]\nalpah = 1\n");
    r = run_shatter({"run", unknown, "-o", dir.file("c")});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find("unknown.toml:4"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("did you mean 'alpha'"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir.file("c")));
    // An interior texture that is not there: refused before the output folder is made (the path
    // is the shot folder's), not after prescore and simulate.
    const std::string texture = dir.write("texture.toml", "[mesh]\npath = \"cube.obj\"\n[render]\ninterior_texture = \"stone.png\"\n");
    r = run_shatter({"run", texture, "-o", dir.file("d")});
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_NE(r.err.find(dir.file("stone.png")), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir.file("d")));
}

// Without ffmpeg the movie cannot be made: exit code 6 with the fix, and every other output is
// still made.
TEST(RunCommand, WithoutFfmpegTheOtherOutputsAreStillMade) {
    TempDir dir;
    const std::string shot = write_cube_shot(dir);
    const std::string out = dir.file("out");
    auto r = testing_support::run_command({"/usr/bin/env", "PATH=" + dir.file("empty-path"), SHATTER_BINARY, "run", shot,
                                           "-o", out, "--no-progress"});
    EXPECT_EQ(r.exit_code, 6) << r.out << r.err;
    EXPECT_NE(r.err.find("ffmpeg"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("make deps"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out + "/cube.mp4"));
    for (const char* f : {"cube.model", "cube.traj", "frames/frame_00015.png", "cube.contact.png", "cube.glb", "summary.json"})
        EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
    EXPECT_NE(r.out.find("FAILED:   encode"), std::string::npos) << r.out;
    EXPECT_NE(slurp(out + "/report.html").find("No movie"), std::string::npos);  // the page says so
    // With ffmpeg back, only the movie is made (and the page that shows it).
    auto again = run_shatter({"run", shot, "-o", out, "--no-progress"});
    EXPECT_EQ(again.exit_code, 0) << again.err;
    EXPECT_TRUE(fs::exists(out + "/cube.mp4"));
    EXPECT_EQ(slurp(out + "/report.html").find("No movie"), std::string::npos);
    EXPECT_NE(slurp(out + "/report.html").find("<video"), std::string::npos);
    EXPECT_NE(stage_status(again.out, "render").find("(up to date)"), std::string::npos) << again.out;
}

// File names are bytes, never commands: a shot, mesh and output folder named with spaces, quotes,
// $(...), backticks, semicolons, a newline and non-ASCII letters go through every stage,
// ffmpeg included, and nothing they spell is run.
TEST(RunCommand, HostileNamesWorkEverywhereAndRunNothing) {
    TempDir dir;
    const std::string hostile = "it's \"$(touch pwned)\" `touch pwned`; touch pwned\nZ\u00fcrich \u00e9t\u00e9 %d";
    const fs::path folder = dir.path() / hostile;
    fs::create_directories(folder);
    fs::copy_file(SHATTER_SOURCE_DIR "/tests/fixtures/cube.obj", folder / (hostile + ".obj"));
    std::string shot_text = kCubeShot;
    const std::string plain = "\"cube.obj\"";
    shot_text.replace(shot_text.find(plain), plain.size(), "'''" + hostile + ".obj'''");  // a TOML literal string
    const std::string shot = (folder / (hostile + ".toml")).string();
    std::ofstream(shot) << shot_text;
    const std::string out = (folder / ("out " + hostile)).string();
    auto r = testing_support::run_command({SHATTER_BINARY, "run", shot, "-o", out, "--no-progress"}, dir.path().string());
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    for (const std::string f : {".model", ".traj", ".mp4", ".contact.png", ".energy.png", ".glb"})
        EXPECT_TRUE(fs::exists(fs::path(out) / (hostile + f))) << f;
    EXPECT_TRUE(fs::exists(fs::path(out) / "frames/frame_00015.png"));
    for (const auto& e : fs::recursive_directory_iterator(dir.path()))
        EXPECT_NE(e.path().filename().string(), "pwned") << "a file name was run as a command";
}

// A disk that fills while frames are written: a clear message naming the file and the reason, the
// Io exit code, and the finished stages intact (their stamps still verify, so a run on a roomier
// disk would only redo the frames). The disk holds prescore's and simulate's outputs (192 kB in
// 4 kB blocks: the cube's piece whose cut fails drawn with the input's triangles, 561 parts) and a
// few frames.
TEST(RunCommand, AFullDiskFailsClearlyAndKeepsWhatWasFinished) {
    TempDir dir;
    const std::string shot = write_cube_shot(dir);
    const std::string disk = dir.file("small disk");
    fs::create_directories(disk);
    if (::geteuid() != 0 || run_command_status({"/bin/mount", "-t", "tmpfs", "-o", "size=240k", "tmpfs", disk}) != 0)
        GTEST_SKIP() << "cannot mount a small tmpfs here (needs root)";
    const std::string out = disk + "/out";
    auto r = run_shatter({"run", shot, "-o", out, "--no-progress", "--set", "render.width=480", "--set", "render.height=270"});
    const std::string model = slurp(out + "/cube.model");
    const bool simulated = fs::exists(out + "/.shatter/simulate.json");
    run_command_status({"/bin/umount", disk});
    EXPECT_EQ(r.exit_code, 4) << r.out << r.err;
    EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(".png"), std::string::npos) << r.err;
    EXPECT_FALSE(model.empty());
    EXPECT_TRUE(simulated);
    auto reference = run_shatter({"run", shot, "-o", dir.file("roomy"), "--no-progress", "--stages", "prescore"});
    ASSERT_EQ(reference.exit_code, 0) << reference.err;
    EXPECT_TRUE(model == slurp(dir.file("roomy/cube.model")));
}

TEST(RunCommand, AReadOnlyOutputFolderFailsClearly) {
    TempDir dir;
    const std::string shot = write_cube_shot(dir);
    const std::string out = dir.file("locked");
    fs::create_directories(out);
    fs::permissions(out, fs::perms::owner_read | fs::perms::owner_exec);
    if (::geteuid() == 0) {
        // root writes anywhere; a read-only bind mount stands in for a read-only disk
        if (run_command_status({"/bin/mount", "--bind", "-o", "ro", out, out}) != 0 &&
            run_command_status({"/bin/mount", "-o", "remount,ro,bind", out}) != 0)
            GTEST_SKIP() << "cannot make a read-only mount here";
        run_command_status({"/bin/mount", "-o", "remount,ro,bind", out});
    }
    auto r = run_shatter({"run", shot, "-o", out, "--no-progress"});
    if (::geteuid() == 0) run_command_status({"/bin/umount", out});
    fs::permissions(out, fs::perms::owner_all);
    EXPECT_EQ(r.exit_code, 4) << r.out << r.err;
    EXPECT_NE(r.err.find(out), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("Read-only file system") == std::string::npos ? r.err.find("Permission denied") : 0,
              std::string::npos) << r.err;
}

// duration = "auto" that never comes to rest: the 10 cm cube set down on frictionless ground
// sliding at 1 m/s keeps that speed (no friction, nothing else acting along the ground), so it
// is still moving at max_duration, and the run says so, naming a piece at 1 m/s.
TEST(RunCommand, APieceStillMovingAtMaxDurationIsNamed) {
    TempDir dir;
    fs::copy_file(SHATTER_SOURCE_DIR "/tests/fixtures/cube.obj", dir.file("cube.obj"));
    auto r = run_shatter({"run", dir.file("cube.obj"), "-o", dir.file("out"), "--no-progress", "--stages",
                          "prescore,simulate", "--set", "object.place=base", "--set", "object.position=[0,0,0]",
                          "--set", "object.velocity=[1,0,0]", "--set", "material.friction=0", "--set",
                          "scene.ground_friction=0", "--set", "simulate.max_duration=1"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("still moving at max_duration = 1 s"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(" at 1 m/s"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace shatter
