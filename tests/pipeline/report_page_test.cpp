// The three pages (pipeline/report_page.h, pipeline/batch_page.h, render/diff_page.h), opened from
// file:// in headless Chromium the way a person opens them: no console error, no request that is
// not a file beside the page (nor data:/blob:), every image loads, a screenshot that is not
// blank, and every number shown equal to the JSON the page reports on. The run's page also plays
// its .glb: the 3D view loads every piece, the animation lasts (frames - 1) / fps, and views at
// the start and the end of it differ; the view is the movie's camera (the .glb's, which is
// render's) at the start and at the end, a drag leaves it, and the Movie camera button returns.
//
// Needs node, the npm package puppeteer-core (scripts/install-node-tools.sh puts it into
// BUILD/node_modules; `make test` calls it) and Debian's chromium (scripts/install-deps.sh); a
// test is skipped, saying which is missing, without them. SHATTER_NODE_MODULES overrides where
// the npm packages are.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <set>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "core/html.h"
#include "pipeline/batch.h"
#include "pipeline/batch_page.h"
#include "pipeline/process.h"
#include "pipeline/report_page.h"
#include "render/image_diff.h"
#include "render/png_io.h"
#include "support/cube_shot.h"
#include "support/run_command.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using namespace testing_support;
namespace fs = std::filesystem;
using json = nlohmann::json;

std::optional<std::string> node_modules() {
    std::vector<fs::path> candidates;
    if (const char* env = std::getenv("SHATTER_NODE_MODULES")) candidates.emplace_back(env);
    candidates.push_back(fs::path(SHATTER_BINARY).parent_path().parent_path() / "node_modules");
    if (const char* home = std::getenv("HOME")) candidates.push_back(fs::path(home) / ".cache/shatter/node/node_modules");
    for (const fs::path& c : candidates)
        if (fs::exists(c / "puppeteer-core" / "package.json")) return c.string();
    return std::nullopt;
}

// Why the browser tests cannot run here, or "" when they can.
std::string missing_browser() {
    if (!find_program("node")) return "node is not installed (fix: apt-get install nodejs npm)";
    if (!node_modules())
        return "the npm package puppeteer-core is not installed (fix: bash scripts/install-node-tools.sh BUILD_DIR)";
    if (!fs::exists("/usr/bin/chromium")) return "/usr/bin/chromium is not installed (fix: bash scripts/install-deps.sh)";
    return "";
}

#define SKIP_WITHOUT_BROWSER()                        \
    do {                                              \
        const std::string why = missing_browser();    \
        if (!why.empty()) GTEST_SKIP() << why;        \
    } while (0)

// Opens PAGE with tests/pipeline/check_page.js; screenshots go to OUT_DIR.
json open_page(const std::string& page, const std::string& out_dir, bool viewer = false) {
    std::vector<std::string> argv = {*find_program("node"), std::string(SHATTER_SOURCE_DIR) + "/tests/pipeline/check_page.js",
                                     *node_modules(), page, out_dir};
    if (viewer) argv.push_back("--viewer");
    const ProcessResult r = run_process(argv);
    EXPECT_TRUE(r.ok()) << r.describe() << "\n" << r.err;
    try {
        return json::parse(r.out);
    } catch (const json::exception& e) {
        ADD_FAILURE() << "check_page.js printed no JSON: " << r.out << r.err;
        return json::object();
    }
}

// What every page must be: loaded from file:// with nothing else asked for, no error, every
// image there, and a screenshot that shows something (many colours, not one flat field).
void expect_clean_page(const json& seen, const std::string& page, const std::string& screenshot) {
    EXPECT_EQ(seen.value("console_errors", json::array()), json::array()) << page;
    EXPECT_EQ(seen.value("page_errors", json::array()), json::array()) << page;
    EXPECT_EQ(seen.value("failed_requests", json::array()), json::array()) << page;
    EXPECT_EQ(seen.value("broken_images", json::array()), json::array()) << page;
    ASSERT_TRUE(seen.contains("requests")) << page;
    EXPECT_FALSE(seen["requests"].empty());
    for (const auto& url : seen["requests"]) {
        const std::string u = url.get<std::string>();
        EXPECT_TRUE(u.rfind("file://", 0) == 0 || u.rfind("data:", 0) == 0 || u.rfind("blob:", 0) == 0)
            << page << " asked for " << u;
    }
    const std::string html = slurp(page);
    EXPECT_EQ(html.find("http://"), std::string::npos) << page;
    EXPECT_EQ(html.find("https://"), std::string::npos) << page;
    const Image shot = load_png(screenshot);
    std::set<uint32_t> colours;
    for (size_t i = 0; i + 2 < shot.rgb.size(); i += 3)
        colours.insert(uint32_t(shot.rgb[i]) << 16 | uint32_t(shot.rgb[i + 1]) << 8 | shot.rgb[i + 2]);
    EXPECT_GT(colours.size(), 100u) << screenshot << " looks blank";
    EXPECT_GT(shot.height, 400u) << screenshot;
}

// Every data-key/data-value pair equals the JSON's value at that pointer, byte for byte.
void expect_values_match(const json& shown, const json& source, const std::string& what) {
    for (const auto& [pointer, value] : shown.items()) {
        const json::json_pointer p(pointer);
        ASSERT_TRUE(source.contains(p)) << what << " has no " << pointer;
        EXPECT_EQ(value.get<std::string>(), source.at(p).dump()) << what << " " << pointer;
    }
}

bool up_to_date(const std::string& out, const std::string& stage) {
    return stage_status(out, stage).find("(up to date)") != std::string::npos;
}

// Sets an environment variable for one scope (the shatter child inherits it).
class ScopedEnv {
public:
    ScopedEnv(const char* name, const std::string& value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        ::setenv(name, value.c_str(), 1);
    }
    ~ScopedEnv() {
        if (old_) ::setenv(name_, old_->c_str(), 1);
        else ::unsetenv(name_);
    }

private:
    const char* name_;
    std::optional<std::string> old_;
};

// The 3D view's camera against the .glb's "camera" node at its first and last key: the same place,
// direction and vertical field of view (three.js keeps the degrees, glTF the radians).
void expect_movie_camera(const std::string& glb, const json& seen) {
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(glb, 0);
    ASSERT_TRUE(scene && scene->mNumCameras == 1 && scene->mNumAnimations == 1) << glb;
    const aiCamera& lens = *scene->mCameras[0];
    const aiAnimation& anim = *scene->mAnimations[0];
    const aiNodeAnim* keys = nullptr;
    for (unsigned i = 0; i < anim.mNumChannels; ++i)
        if (std::string(anim.mChannels[i]->mNodeName.C_Str()) == "camera") keys = anim.mChannels[i];
    ASSERT_TRUE(keys && keys->mNumPositionKeys > 1) << "the cube's camera follows its pieces";
    const auto expect_at = [&](const json& view, unsigned key, const char* when) {
        ASSERT_TRUE(view.is_object()) << when;
        EXPECT_TRUE(view["following"].get<bool>()) << when;
        const aiVector3D& p = keys->mPositionKeys[key].mValue;
        const aiQuaternion& q = keys->mRotationKeys[key].mValue;
        const Eigen::Vector3d look = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized() * Eigen::Vector3d(0, 0, -1);
        for (int i = 0; i < 3; ++i) {
            EXPECT_NEAR(view["position"][i].get<double>(), p[i], 1e-4) << when << " " << view.dump();
            EXPECT_NEAR(view["direction"][i].get<double>(), look[i], 1e-4) << when << " " << view.dump();
        }
        // assimp 5.2 reads glTF's yfov times the aspect into mHorizontalFOV.
        EXPECT_NEAR(view["fov"].get<double>(), lens.mHorizontalFOV / lens.mAspect * 180 / M_PI, 1e-3) << when;
    };
    const unsigned last = keys->mNumPositionKeys - 1;
    expect_at(seen["start"], 0, "at the start");
    expect_at(seen["end"], last, "at the end");
    expect_at(seen["back"], last, "after the Movie camera button");
    // A drag turns the view about a point ahead of it: it is not the movie's any more.
    const json& dragged = seen["dragged"];
    EXPECT_FALSE(dragged["following"].get<bool>()) << dragged.dump();
    double turned = 0;
    for (int i = 0; i < 3; ++i)
        turned = std::max(turned, std::abs(dragged["direction"][i].get<double>() - seen["end"]["direction"][i].get<double>()));
    EXPECT_GT(turned, 0.05) << "a drag across the view did not turn it: " << dragged.dump();
}

TEST(ReportPage, RunPageLoadsOfflineShowsTheSummaryAndPlaysTheGlb) {
    SKIP_WITHOUT_BROWSER();
    if (!fs::exists(fs::path(*node_modules()) / "three" / "package.json"))
        GTEST_SKIP() << "the npm package three is not installed (fix: bash scripts/install-node-tools.sh BUILD_DIR)";
    TempDir dir;
    const std::string shot = write_cube_shot(dir);
    const std::string out = dir.file("out");
    ScopedEnv modules("SHATTER_NODE_MODULES", *node_modules());
    const auto r = run_shatter({"run", shot, "-o", out, "--no-progress"});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    const std::string page = out + "/report.html";
    ASSERT_TRUE(fs::exists(page));
    for (const char* f : {"viewer/three.min.js", "viewer/GLTFLoader.js", "viewer/OrbitControls.js", "report.times.js"})
        EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
    const json summary = json::parse(slurp(out + "/summary.json"));
    EXPECT_EQ(summary["files"]["report"], "report.html");

    const json seen = open_page(page, dir.path().string(), true);
    expect_clean_page(seen, page, dir.file("page.png"));
    EXPECT_EQ(seen.value("title", ""), "cube");
    // The numbers a reviewer reads, each shown and equal to summary.json's.
    const json& values = seen["values"];
    for (const char* key : {"/model/pieces", "/model/constraints", "/simulation/breaks", "/simulation/fragments",
                            "/simulation/stored_energy_J", "/simulation/injected_energy_J", "/alpha"})
        EXPECT_TRUE(values.contains(key)) << key;
    expect_values_match(values, summary, "report.html");
    // The 3D view: every piece of the model, the animation of every frame, and it moves.
    ASSERT_TRUE(seen.contains("viewer"));
    EXPECT_TRUE(seen["viewer"]["loaded"].get<bool>()) << seen["viewer"].dump() << seen.value("viewer_timeout", "");
    EXPECT_EQ(seen["viewer"]["pieces"], summary["model"]["pieces"]);
    const double frames = summary["simulation"]["frames"].get<double>(), fps = summary["simulation"]["fps"].get<double>();
    EXPECT_NEAR(seen["viewer"]["duration"].get<double>(), (frames - 1) / fps, 1e-4);
    const Image start = load_png(dir.file("viewer_start.png")), end = load_png(dir.file("viewer_end.png"));
    ASSERT_EQ(start.width, end.width);
    const DiffMetrics moved = compare_images(start, end, 8);
    EXPECT_GT(moved.pixels_over, 200u) << "the 3D view at the start and the end of the animation look alike";
    std::cout << "viewer: " << seen["viewer"].dump() << ", " << moved.pixels_over << " pixels differ between t = 0 and t = "
              << seen["viewer"]["duration"] << " s\n";
    expect_movie_camera(out + "/cube.glb", seen["viewer"]["cameras"]);

    // The same inputs, the same page; a re-run keeps it (the report stage is up to date).
    const std::string out2 = dir.file("out2");
    ASSERT_EQ(run_shatter({"run", shot, "-o", out2, "--no-progress"}).exit_code, 0);
    EXPECT_EQ(slurp(out2 + "/report.html"), slurp(page));
    const auto again = run_shatter({"run", shot, "-o", out, "--no-progress"});
    EXPECT_TRUE(up_to_date(again.out, "report")) << again.out;
    // The times: the latest run's (all up to date) and the time each stage took when it last ran.
    const std::string times = slurp(out + "/report.times.js");
    EXPECT_NE(times.find("\"stage\":\"render\",\"outcome\":\"up to date\""), std::string::npos) << times;
    EXPECT_EQ(times.find("\"last_ran_s\":null"), std::string::npos) << times;
}

TEST(ReportPage, WithoutTheViewerThePageSaysSoAndShowsEverythingElse) {
    SKIP_WITHOUT_BROWSER();
    TempDir dir;
    const std::string shot = write_cube_shot(dir);
    const std::string out = dir.file("out");
    {
        ScopedEnv modules("SHATTER_NODE_MODULES", dir.file("no-node-modules"));
        const auto r = run_shatter({"run", shot, "-o", out, "--no-progress"});
        ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    }
    const std::string page = out + "/report.html";
    const std::string html = slurp(page);
    EXPECT_NE(html.find("id=\"viewer-missing\""), std::string::npos);
    EXPECT_NE(html.find("scripts/install-node-tools.sh"), std::string::npos);
    EXPECT_EQ(html.find("viewer/three.min.js"), std::string::npos);
    EXPECT_FALSE(fs::exists(fs::path(out) / "viewer"));
    const json seen = open_page(page, dir.path().string());
    expect_clean_page(seen, page, dir.file("page.png"));
    expect_values_match(seen["values"], json::parse(slurp(out + "/summary.json")), "report.html");

    // The viewer installed later: the report stage runs again (its key has the viewer's files).
    if (fs::exists(fs::path(*node_modules()) / "three" / "package.json")) {
        ScopedEnv modules("SHATTER_NODE_MODULES", *node_modules());
        const auto r = run_shatter({"run", shot, "-o", out, "--no-progress"});
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_TRUE(up_to_date(r.out, "export")) << r.out;
        EXPECT_FALSE(stage_status(r.out, "report").empty()) << r.out;
        EXPECT_FALSE(up_to_date(r.out, "report")) << r.out;
        EXPECT_TRUE(fs::exists(fs::path(out) / "viewer/three.min.js"));
        EXPECT_EQ(slurp(page).find("id=\"viewer-missing\""), std::string::npos);
    }
}

TEST(BatchPage, IndexShowsEveryRunWithItsSummaryNumbersAndEachSweep) {
    SKIP_WITHOUT_BROWSER();
    TempDir dir;
    write_cube_shot(dir);
    const std::string batch = dir.write("sweep.toml", kCubeSweepBatch);
    const std::string out = dir.file("out");
    const auto r = run_shatter({"batch", batch, "-o", out});
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // the bad job
    const std::string page = out + "/index.html";
    ASSERT_TRUE(fs::exists(page)) << r.out;
    EXPECT_NE(r.out.find("wrote:  " + page), std::string::npos) << r.out;
    const std::string html = slurp(page);
    for (const char* link : {"cube/alpha-0/report.html", "cube/alpha-2/report.html", "cube/cube.strip.png",
                             "cube/cube.energy.png", "cube/cube.table.md", "bad/run/console.log"})
        EXPECT_NE(html.find(std::string("\"") + link + "\""), std::string::npos) << link;
    EXPECT_NE(html.find("render.width = 100000 is outside"), std::string::npos);

    const json seen = open_page(page, dir.path().string());
    expect_clean_page(seen, page, dir.file("page.png"));
    ASSERT_TRUE(seen.contains("runs"));
    EXPECT_EQ(seen["runs"].size(), 2u) << seen["runs"].dump();  // the failed run has no numbers
    for (const char* run : {"alpha-0", "alpha-2"}) {
        const json shown = seen["runs"].value(std::string("cube/") + run, json::object());
        EXPECT_TRUE(shown.contains("/simulation/breaks")) << run;
        EXPECT_TRUE(shown.contains("/simulation/fragments")) << run;
        expect_values_match(shown, json::parse(slurp(out + "/cube/" + run + "/summary.json")), run);
    }
}

// A run with warnings says how many beside its status, linking to the box at the top of its page;
// a run without says nothing more.
TEST(BatchPage, CountsEachRunsWarningsAndLinksToThem) {
    BatchFile batch;
    batch.path = "sweep.toml";
    batch.output_dir = "out";
    BatchJob job;
    job.name = "cube";
    job.shot = "cube.toml";
    job.output_dir = "out/cube";
    for (const char* label : {"alpha-0", "alpha-2"}) job.runs.push_back({label, label, {}, std::string("out/cube/") + label});
    batch.jobs.push_back(job);
    BatchResult result;
    for (const BatchRun& run : job.runs) {
        BatchRunResult r{"cube", run.label, run.caption, run.output_dir, 0, "", 1.0, {}};
        r.summary = json::parse(R"({"model": {"pieces": 4}, "simulation": {"frames": 16, "fps": 30, "breaks": 3}})");
        result.runs.push_back(r);
    }
    result.runs[1].summary["model"]["warnings"] = {"cube.obj: one"};
    result.runs[1].summary["simulation"]["warnings"] = {"simulate: two"};
    const std::string html = batch_page_html(batch, result);
    EXPECT_NE(html.find("<a class=\"warned\" href=\"cube/alpha-2/report.html#warnings\">2 warnings</a>"), std::string::npos)
        << html;
    EXPECT_EQ(html.find("cube/alpha-0/report.html#warnings"), std::string::npos) << html;
}

// Two frame folders: frame_00000 the same, frame_00001 with a bright square in the actual.
void write_frames(const TempDir& dir) {
    fs::create_directories(dir.file("expected"));
    fs::create_directories(dir.file("actual"));
    Image a(160, 90);
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c) a.rgb[(size_t(y) * a.width + x) * 3 + c] = uint8_t((x * 3 + y * 2 + c * 40) % 256);
    Image b = a;
    for (uint32_t y = 30; y < 60; ++y)
        for (uint32_t x = 60; x < 100; ++x)
            for (int c = 0; c < 3; ++c) b.rgb[(size_t(y) * b.width + x) * 3 + c] = 250;
    save_png(dir.file("expected/frame_00000.png"), a);
    save_png(dir.file("actual/frame_00000.png"), a);
    save_png(dir.file("expected/frame_00001.png"), a);
    save_png(dir.file("actual/frame_00001.png"), b);
}

TEST(DiffPage, ShowsTheFailingImagesSideBySideWithTheirMetricsAndTolerances) {
    SKIP_WITHOUT_BROWSER();
    TempDir dir;
    write_frames(dir);
    const std::string report = dir.file("report");
    const auto r = run_shatter({"diff", dir.file("expected"), dir.file("actual"), "--report", report, "--max-rmse", "2"});
    ASSERT_EQ(r.exit_code, 1) << r.out << r.err;
    const std::string page = report + "/report.html";
    EXPECT_NE(r.out.find("wrote: " + page), std::string::npos) << r.out;
    // The folder is complete on its own: the failing image's three pictures are in it.
    for (const char* f : {"frame_00001.expected.png", "frame_00001.actual.png", "frame_00001.heat.png"})
        EXPECT_TRUE(fs::exists(fs::path(report) / f)) << f;
    EXPECT_FALSE(fs::exists(fs::path(report) / "frame_00000.expected.png"));
    const std::string html = slurp(page);
    EXPECT_NE(html.find("class=\"wipe\""), std::string::npos);
    EXPECT_NE(html.find("class=\"blink\""), std::string::npos);

    const json seen = open_page(page, dir.path().string());
    expect_clean_page(seen, page, dir.file("page.png"));
    const json summary = json::parse(slurp(report + "/summary.json"));
    const json& values = seen["values"];
    for (const char* key : {"/tolerance/max_rmse", "/tolerance/min_ssim", "/results/1/rmse", "/results/1/ssim",
                            "/results/0/rmse", "/results/1/fraction_over_threshold"})
        EXPECT_TRUE(values.contains(key)) << key;
    expect_values_match(values, summary, "diff report.html");
    EXPECT_EQ(values.value("/tolerance/max_rmse", ""), "2.0");

    // Same inputs, same page.
    const std::string report2 = dir.file("report2");
    ASSERT_EQ(run_shatter({"diff", dir.file("expected"), dir.file("actual"), "--report", report2, "--max-rmse", "2"}).exit_code, 1);
    std::string html2 = slurp(report2 + "/report.html");
    // The page names the folders it compared, not the report folder: the bytes are the same.
    EXPECT_EQ(html2, html);
}

// The model's and the trajectory's warnings open the page, each once, escaped, with the stage it
// came from; a summary without any has no such box.
TEST(ReportPage, ShowsTheStagesWarningsAtTheTop) {
    ReportPageInput in;
    in.name = "cube";
    in.summary = nlohmann::ordered_json::parse(R"({"shot": "cube.toml", "files": {}, "alpha": 1,
        "model": {"pieces": 2, "warnings": ["cube.obj: steps of 0.25 units <stepped>"]},
        "simulation": {"complete": true, "warnings": ["simulate: no joint broke & more"]},
        "instability": {}})");
    const std::string html = report_page_html(in);
    const size_t box = html.find("<div class=\"note\" id=\"warnings\">");
    ASSERT_NE(box, std::string::npos) << html;
    EXPECT_LT(box, html.find("<h2>Summary</h2>"));
    EXPECT_NE(html.find("prescore:</span> cube.obj: steps of 0.25 units &lt;stepped&gt;</li>", box), std::string::npos) << html;
    EXPECT_NE(html.find("simulate:</span> simulate: no joint broke &amp; more</li>", box), std::string::npos) << html;
    in.summary["model"].erase("warnings");
    in.summary["simulation"].erase("warnings");
    EXPECT_EQ(report_page_html(in).find("id=\"warnings\""), std::string::npos);
}

TEST(PageHelpers, EscapeBase64AndUrls) {
    EXPECT_EQ(html_escape("<a href=\"x\">'&'</a>"), "&lt;a href=&quot;x&quot;&gt;&#39;&amp;&#39;&lt;/a&gt;");
    // RFC 4648 section 10's test vectors.
    EXPECT_EQ(base64(""), "");
    EXPECT_EQ(base64("f"), "Zg==");
    EXPECT_EQ(base64("fo"), "Zm8=");
    EXPECT_EQ(base64("foo"), "Zm9v");
    EXPECT_EQ(base64("foob"), "Zm9vYg==");
    EXPECT_EQ(base64("fooba"), "Zm9vYmE=");
    EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
    EXPECT_EQ(base64(std::string("\xff\x00\x80", 3)), "/wCA");
    EXPECT_EQ(url_path("cube/alpha-0.5/a b#c?.png"), "cube/alpha-0.5/a%20b%23c%3F.png");
}

}  // namespace
}  // namespace shatter
