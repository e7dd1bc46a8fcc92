#include "pipeline/run.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <numeric>
#include <sstream>
#include <thread>

#include <fmt/format.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/spdlog.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/generate_settings.h"
#include "core/model_io.h"
#include "core/shot.h"
#include "core/stage_file.h"
#include "core/trajectory.h"
#include "core/utf8.h"
#include "pipeline/encode.h"
#include "pipeline/export_glb.h"
#include "pipeline/instability_record.h"
#include "pipeline/plot.h"
#include "pipeline/report_page.h"
#include "pipeline/run_metrics.h"
#include "pipeline/sheets.h"
#include "pipeline/stage_cache.h"
#include "meshio/companions.h"
#include "prescore/prescore.h"
#include "render/camera_path.h"
#include "render/render.h"
#include "simulate/recording.h"
#include "simulate/simulate.h"

namespace shatter {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

const char* to_string(Stage stage) {
    switch (stage) {
        case Stage::Prescore: return "prescore";
        case Stage::Simulate: return "simulate";
        case Stage::Render: return "render";
        case Stage::Encode: return "encode";
        case Stage::Sheet: return "sheet";
        case Stage::Plot: return "plot";
        case Stage::Export: return "export";
        case Stage::Report: return "report";
    }
    return "?";
}

std::optional<Stage> parse_stage(const std::string& text) {
    for (Stage s : kAllStages)
        if (text == to_string(s)) return s;
    return std::nullopt;
}

const char* to_string(StageOutcome outcome) {
    switch (outcome) {
        case StageOutcome::Ran: return "ran";
        case StageOutcome::UpToDate: return "up to date";
        case StageOutcome::FromCache: return "from cache";
        case StageOutcome::NotAsked: return "not asked";
        case StageOutcome::Failed: return "FAILED";
    }
    return "?";
}

std::pair<uint32_t, uint32_t> chunk_frames(uint32_t frames, uint32_t chunk, uint32_t chunks) {
    return {uint32_t(uint64_t(frames) * chunk / chunks), uint32_t(uint64_t(frames) * (chunk + 1) / chunks)};
}

std::string default_output_dir(const std::string& shot) {
    return (fs::path("out") / as_utf8(fs::path(shot).stem().string())).string();
}

namespace {

// A sink added to the logger for the lifetime of a run.
class AttachedSink {
public:
    explicit AttachedSink(std::shared_ptr<spdlog::sinks::sink> sink) : sink_(std::move(sink)) {
        spdlog::default_logger()->sinks().push_back(sink_);
    }
    ~AttachedSink() {
        auto& sinks = spdlog::default_logger()->sinks();
        sinks.erase(std::remove(sinks.begin(), sinks.end(), sink_), sinks.end());
    }
    AttachedSink(const AttachedSink&) = delete;
    AttachedSink& operator=(const AttachedSink&) = delete;

private:
    std::shared_ptr<spdlog::sinks::sink> sink_;
};

// run.log in the output folder, every message with its time.
std::shared_ptr<spdlog::sinks::sink> run_log_sink(const std::string& path) {
    try {
        auto sink = std::make_shared<spdlog::sinks::basic_file_sink_mt>(path, false);
        sink->set_pattern("[%Y-%m-%d %H:%M:%S.%e] [%l] %v");
        return sink;
    } catch (const spdlog::spdlog_ex& e) {
        throw_io_error(path, e.what());
    }
}

// Keeps the run's warnings (each once, in order) for its summary.
class WarningsKept : public spdlog::sinks::base_sink<std::mutex> {
public:
    std::vector<std::string> taken() {
        std::lock_guard<std::mutex> lock(mutex_);
        return std::move(kept_);
    }

protected:
    void sink_it_(const spdlog::details::log_msg& msg) override {  // under mutex_
        if (msg.level != spdlog::level::warn) return;  // errors end the run and are its summary's
        std::string text(msg.payload.data(), msg.payload.size());
        if (std::find(kept_.begin(), kept_.end(), text) == kept_.end()) kept_.push_back(std::move(text));
    }
    void flush_() override {}

private:
    std::vector<std::string> kept_;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

class Runner {
public:
    explicit Runner(const RunOptions& options)
        : options_(options),
          shot_(load_shot_or_mesh(options.shot, options.overrides)),
          dir_(options.output_dir.empty() ? default_output_dir(options.shot) : options.output_dir),
          name_(as_utf8(fs::path(options.shot).stem().string())),  // (outputs named in UTF-8)
          stamps_(dir_.string()),
          cache_(options.cache_dir) {
        if (options.chunks == 0 || options.chunk >= options.chunks)
            throw Error(ExitCode::Usage, fmt::format("--chunk {}/{}: not a chunk (fix: I/N with 0 <= I < N)",
                                                     options.chunk, options.chunks));
        result_.output_dir = dir_.string();
        result_.name = name_;
    }
    ~Runner() { finish_beside(); }
    Runner(const Runner&) = delete;
    Runner& operator=(const Runner&) = delete;

    RunResult run() {
        // A missing mesh, or interior texture, is bad input found before the output folder is touched.
        if (!shot_.mesh.path.empty() && !shot_.generate) file_hash(shot_.mesh.path);
        if (!shot_.render.interior_texture.empty() && asked(Stage::Render))
            read_file(shot_.render.interior_texture, "[render] interior_texture");
        make_directories(dir_.string());
        if (options_.chunks == 1) remove_stale_temporaries();
        AttachedSink log(run_log_sink((dir_ / "run.log").string()));
        const auto warnings = std::make_shared<WarningsKept>();
        AttachedSink keep(warnings);
        const auto start = std::chrono::steady_clock::now();
        spdlog::info("run: {} -> {}{}", options_.shot, dir_.string(),
                     options_.overrides.empty() ? "" : fmt::format(" (--set {})", fmt::join(options_.overrides, " ")));
        steps_ = steps();
        {
            // The stages beside render end before the log's sinks are detached, also when a stage throws.
            struct FinishBeside {
                Runner& runner;
                ~FinishBeside() { runner.finish_beside(); }
            } finish{*this};
            for (const StageStep& step : steps_) run_step(step);
        }
        result_.seconds = seconds_since(start);
        write_report_times(dir_.string(), result_.stages);
        // The stages' own warnings first, from their files (also those of stages that were up to
        // date), then what this run logged besides.
        for (StageWarning& w : summary_warnings(result_.summary)) result_.warnings.push_back(std::move(w.text));
        for (std::string& w : warnings->taken())
            if (std::find(result_.warnings.begin(), result_.warnings.end(), w) == result_.warnings.end())
                result_.warnings.push_back(std::move(w));
        return std::move(result_);
    }

    // The stages whose outputs are current, in pipeline order up to the first that is not (the
    // stamps' check, without running anything; for `shatter submit`). Finishing stages are not
    // checked: they are cheap and always left to the final job.
    std::vector<Stage> up_to_date() {
        std::vector<Stage> out;
        steps_ = steps();
        for (const StageStep& step : steps_) {
            if (step.kind == StageKind::Finishing || !current(step, key_of(step))) break;
            out.push_back(step.stage);
        }
        return out;
    }

private:
    std::string file(const char* suffix) const { return (dir_ / (name_ + suffix)).string(); }

    // A killed run leaves NAME.tmp.PID files (never mistaken for outputs) and a tool's NAME.tmp.PID
    // folder (pipeline/tool_output.h); the next run removes them. Not while render chunks of a
    // cluster job may be writing theirs (chunks > 1).
    void remove_stale_temporaries() const {
        std::error_code ec;
        for (const fs::path& d : {dir_, dir_ / "frames", dir_ / ".shatter"})
            for (const auto& entry : fs::directory_iterator(d, ec))
                if (entry.path().filename().string().find(".tmp.") != std::string::npos)
                    for (int attempt = 0; attempt < 3 && fs::exists(entry.path(), ec); ++attempt)
                        fs::remove_all(entry.path(), ec);  // (again if a killed run's tool wrote into it meanwhile)
    }
    std::string frames_dir() const { return (dir_ / "frames").string(); }

    bool asked(Stage s) const {
        return options_.stages.empty() || std::find(options_.stages.begin(), options_.stages.end(), s) != options_.stages.end();
    }
    // True when a stage after `s` that reads the outputs of `s` is asked for: every later stage
    // reads the model and the trajectory, only those that need the frames read render's.
    bool needed_later(Stage s) const {
        for (Stage later : kAllStages)
            if (later > s && asked(later) && (s != Stage::Render || step_of(later).needs_frames)) return true;
        return false;
    }
    StageReport& report(Stage s) {
        result_.stages.push_back({s, StageOutcome::NotAsked, 0, {}});
        if (asked(s)) spdlog::info("[{}/{}] {}", size_t(s) + 1, std::size(kAllStages), to_string(s));
        return result_.stages.back();
    }
    void log_outcome(const StageReport& r) {
        spdlog::info("{}: {} ({:.2f}s)", to_string(r.stage), to_string(r.outcome), r.seconds);
    }
    // A stage that was not asked for must be up to date for the stages after it.
    [[noreturn]] void missing(Stage s, const std::string& what) const {
        throw Error(ExitCode::BadInput,
                    fmt::format("{}: {} {} missing or out of date (fix: run its stage first: shatter run {} -o {} "
                                "--stages {})", dir_.string(), what, s == Stage::Render ? "are" : "is", options_.shot,
                                dir_.string(), to_string(s)));
    }

    // ---- the run as a list of stages, run by one loop (run_step)
    enum class StageKind {
        Shared,     // prescore, simulate: outputs shared through the cache; an error ends the run
        Frames,     // render: frames drawn into frames/, a chunk at a time; an error ends the run
        Finishing,  // encode, sheet, plot, export, report: an error is reported and the run goes on
    };
    struct StageStep {
        Stage stage;
        StageKind kind;
        std::function<json()> inputs;   // what the stage's key is made of
        StageCache::Files files = {};   // {name in the cache, name in the output folder} (Frames: none)
        std::function<void()> compute;  // writes the outputs
        const char* what = "";          // the outputs, for "... is missing or out of date"
        bool needs_frames = false;      // a finishing stage that reads the frames
        std::function<void()> before = {};  // runs at the stage's place, asked or not
        std::function<void()> after = {};   // runs after the stage when it was asked
        std::function<void()> compute_beside = {};  // compute, beside render (encode: waiting for each frame)
    };

    std::vector<StageStep> steps() {
        return {
            {.stage = Stage::Prescore, .kind = StageKind::Shared, .inputs = [&] { return prescore_inputs(); },
             .files = {{"model", name_ + ".model"}, {"pieces.ply", name_ + ".pieces.ply"}},
             .compute = [&] { compute_prescore(); }, .what = "the model"},
            {.stage = Stage::Simulate, .kind = StageKind::Shared, .inputs = [&] { return simulate_inputs(); },
             .files = {{"traj", name_ + ".traj"}, {"breaks.jsonl", name_ + ".breaks.jsonl"},
                       {"energy.csv", name_ + ".energy.csv"}, {"instability.json", name_ + ".instability.json"}},
             .compute = [&] { compute_simulate(); }, .what = "the trajectory", .after = [&] { report_instability(); }},
            {.stage = Stage::Render, .kind = StageKind::Frames, .inputs = [&] { return render_inputs(); },
             .compute = [&] { compute_render(); }, .what = "the frames"},
            {.stage = Stage::Encode, .kind = StageKind::Finishing, .inputs = [&] { return json{{"render", render_key()}}; },
             .files = {{"", name_ + ".mp4"}},
             .compute = [&] { encode_mp4(frames_dir(), trajectory().frames(), trajectory().fps, file(".mp4")); },
             .what = "the movie", .needs_frames = true,
             .compute_beside = [&] {
                 encode_mp4(frames_dir(), trajectory().frames(), trajectory().fps, file(".mp4"),
                            [&](uint32_t f) { return frame_drawn(f); }, &pixels_);
             }},
            {.stage = Stage::Sheet, .kind = StageKind::Finishing, .inputs = [&] { return json{{"render", render_key()}}; },
             .files = {{"", name_ + ".contact.png"}},
             .compute = [&] { write_contact_sheet(frames_dir(), trajectory().frames(), trajectory().fps, file(".contact.png")); },
             .what = "the contact sheet", .needs_frames = true,
             .compute_beside = [&] {
                 write_contact_sheet(frames_dir(), trajectory().frames(), trajectory().fps, file(".contact.png"), {},
                                     [&](uint32_t f) { return frame_drawn(f); });
             }},
            {.stage = Stage::Plot, .kind = StageKind::Finishing,
             .inputs = [&] { return json{{"energy", file_hash(file(".energy.csv"))}, {"title", name_}}; },
             .files = {{"", name_ + ".energy.png"}},
             .compute = [&] { plot_energy({{name_, file(".energy.csv")}}, name_, file(".energy.png")); },
             .what = "the energy plot"},
            {.stage = Stage::Export, .kind = StageKind::Finishing,
             .inputs = [&] { return render_inputs(); },  // render's colours and interior texture
             .files = {{"", name_ + ".glb"}},
             .compute = [&] { export_glb(model(), trajectory(), file(".glb"), &shot_.render); }, .what = "the glTF file"},
            // summary.json is written at the report's place, whether the report is asked or not.
            {.stage = Stage::Report, .kind = StageKind::Finishing,
             .inputs = [&] { return report_stage_inputs(dir_.string(), name_, shot_, result_.summary); },
             .files = report_files(), .compute = [&] { write_report(dir_.string(), name_, shot_, result_.summary); },
             .what = "the report", .before = [&] { write_summary(); }},
        };
    }
    StageCache::Files report_files() const {
        StageCache::Files files;
        for (const std::string& f : report_stage_outputs()) files.push_back({"", f});
        return files;
    }
    std::string key_of(const StageStep& step) {
        return step.kind == StageKind::Frames ? render_key() : stage_key(to_string(step.stage), step.inputs());
    }
    std::vector<std::string> output_names(const StageStep& step) const {
        std::vector<std::string> names;
        for (const auto& [cached, name] : step.files) names.push_back(name);
        return names;
    }
    // The stamp holds `key` and every output is there (the stamp lists the files it hashed; an
    // output it does not list, or that is gone, makes the stage run again).
    bool current(const StageStep& step, const std::string& key) {
        if (!stamps_.current(to_string(step.stage), key)) return false;
        if (step.kind == StageKind::Frames) return all_frames_present();
        std::error_code ec;
        for (const std::string& name : output_names(step))
            if (!fs::exists(dir_ / name, ec)) return false;
        return true;
    }

    void run_step(const StageStep& step) {
        if (step.stage == Stage::Report) join_beside();  // (before summary.json, which lists their files)
        StageReport& r = report(step.stage);
        if (const auto b = std::find_if(beside_.begin(), beside_.end(), [&](const Beside& b) { return b.stage == step.stage; });
            b != beside_.end()) {
            b->index = result_.stages.size() - 1;  // running beside render; joined before the report
            return;
        }
        if (step.before) step.before();
        const bool finishing = step.kind == StageKind::Finishing;
        if (!asked(step.stage) && (finishing || !needed_later(step.stage))) return;
        const auto start = std::chrono::steady_clock::now();
        const std::string name = to_string(step.stage);
        try {
            if (step.needs_frames && !current(step_of(Stage::Render), render_key())) missing(Stage::Render, "the frames");
            const std::string key = key_of(step);
            const bool is_current = current(step, key);
            if (!asked(step.stage)) {  // needed by a later stage
                if (!is_current) missing(step.stage, step.what);
                return;
            }
            if (is_current && !options_.force) {
                r.outcome = StageOutcome::UpToDate;
            } else {
                stamps_.remove(name);
                r.outcome = step.kind == StageKind::Shared ? compute_shared(step, key) : compute_local(step, key, step.compute);
            }
        } catch (const Error& e) {
            if (!finishing) throw;
            failed(r, e.what());
            if (result_.exit_code == 0) result_.exit_code = static_cast<int>(e.code());
        }
        r.seconds = seconds_since(start);
        log_outcome(r);
        if (step.after) step.after();
    }
    const StageStep& step_of(Stage s) const { return steps_.at(size_t(s)); }
    // A finishing stage's failure, kept in its report and logged: the run goes on.
    static void failed(StageReport& r, const char* what) {
        r.outcome = StageOutcome::Failed;
        r.error = what;
        spdlog::error("{}: {}", to_string(r.stage), what);
    }
    // Shared stages: another worker may be computing the same key (the cache's lock), or have
    // computed it (fetched from the cache).
    StageOutcome compute_shared(const StageStep& step, const std::string& key) {
        const std::string name = to_string(step.stage);
        std::optional<FileLock> lock;
        if (cache_.enabled()) {
            lock.emplace(cache_.lock_path(name, key));
            if (!options_.force && cache_.fetch(name, key, dir_.string(), step.files)) {
                stamps_.write(name, key, output_names(step));
                return StageOutcome::FromCache;
            }
        }
        step.compute();
        cache_.store(name, key, dir_.string(), step.files);
        stamps_.write(name, key, output_names(step));
        return StageOutcome::Ran;
    }
    // Render (stamped once every frame is there: a chunk of a cluster job draws only its own)
    // and the finishing stages, by `compute` (theirs, or the one beside render).
    StageOutcome compute_local(const StageStep& step, const std::string& key, const std::function<void()>& compute) {
        compute();
        if (step.kind != StageKind::Frames) stamps_.write(to_string(step.stage), key, output_names(step));
        else if (all_frames_present()) stamps_.write(to_string(step.stage), key, {});
        return StageOutcome::Ran;
    }

    // ---- prescore
    json prescore_inputs() const {
        json mesh = to_json(shot_.mesh);
        mesh.erase("path");
        if (!shot_.mesh.path.empty()) {
            mesh["file"] = fs::path(shot_.mesh.path).filename().string();
            mesh["hash"] = file_hash(shot_.mesh.path);
            // Its material libraries, buffers and textures: a changed texture re-runs prescore.
            json companions = json::object();
            const fs::path dir = fs::path(shot_.mesh.path).parent_path();
            for (const std::string& f : companion_files(shot_.mesh.path)) companions[f] = file_hash((dir / f).string());
            if (!companions.empty()) mesh["companions"] = companions;
        }
        json inputs = {{"mesh", mesh}, {"prescore", to_json(shot_.prescore)}};
        if (shot_.generate) inputs["generate"] = to_json(*shot_.generate);
        // Impact seeds fly the object through the scene first (prescore/impact.h).
        if (shot_.prescore.seeds == SeedMode::Impact && !shot_.generate) {
            inputs["scene"] = to_json(shot_.scene);
            inputs["object"] = to_json(shot_.object);
            // The damage number (recorded, and the automatic ratio and radius) reads the material.
            inputs["material"] = {{"strength", shot_.material.strength},
                                  {"density", shot_.material.density.value_or(shot_.prescore.density)}};
            json colliders = json::array();  // mesh colliders' triangles are flown against
            for (const ColliderSettings& c : shot_.scene.colliders)
                if (c.shape.kind == ShapeKind::Mesh) colliders.push_back(file_hash(c.shape.mesh));
            if (!colliders.empty()) inputs["collider_meshes"] = colliders;
        }
        return inputs;
    }
    void compute_prescore() {
        PrescoreReport report;
        const Model model = prescore_shot(shot_, &report);
        save_prescore_outputs(model, file(".model"));  // NAME.model and NAME.pieces.ply
        spdlog::info("prescore: {} pieces, {} tets, {} constraints", model.pieces.size(), model.mesh.tets.size(),
                     model.constraints.size());
    }

    const std::string& model_hash() {
        if (model_hash_.empty()) model_hash_ = file_hash(file(".model"));
        return model_hash_;
    }
    const Model& model() {
        if (!model_) model_ = load_model(file(".model"));
        return *model_;
    }

    // ---- simulate
    json simulate_inputs() {
        json colliders = json::array();
        for (const ColliderSettings& c : shot_.scene.colliders)
            if (c.shape.kind == ShapeKind::Mesh) colliders.push_back(file_hash(c.shape.mesh));
        return {{"model", model_hash()},       {"scene", to_json(shot_.scene)},       {"collider_meshes", colliders},
                {"object", to_json(shot_.object)}, {"material", to_json(shot_.material)}, {"simulate", to_json(shot_.simulate)}};
    }
    void compute_simulate() {
        const SimulationInput input{shot_.scene, shot_.object, shot_.material, shot_.simulate};
        const SimulationResult sim = simulate(model(), input, model_hash());
        save_trajectory(file(".traj"), sim.trajectory);
        write_file_atomic(file(".breaks.jsonl"), break_log_jsonl(sim.breaks));
        write_file_atomic(file(".energy.csv"), energy_csv(sim.energy));
        write_file_atomic(file(".instability.json"),
                          instability_record(shot_.simulate.on_instability, sim).dump(2, ' ', false, json::error_handler_t::replace) + "\n");
        spdlog::info("simulate: {} frames, {} steps, {} of {} constraints broke, {} of {} pieces asleep at the end",
                     sim.trajectory.frames(), sim.steps, sim.breaks.size(), model().constraints.size(), sim.asleep,
                     model().pieces.size());
    }
    // After simulate (ran or up to date): what the instability guard did, and an incomplete run's exit code.
    void report_instability() {
        const json& record = instability();
        if (record.at("clamps").get<uint64_t>() > 0)
            spdlog::warn("simulate: {} (on_instability = clamp), the first {}",
                         clamped_steps(record.at("clamps").get<uint64_t>()), instability_where(record.at("first_clamp")));
        if (!trajectory().complete) {
            spdlog::error("simulate: the simulation stopped early: {}; the frames before are kept in {}, marked "
                          "incomplete", record.at("stopped").is_object() ? record.at("stopped").at("what").get<std::string>()
                                                                         : std::string("(no record)"),
                          file(".traj"));
            if (result_.exit_code == 0) result_.exit_code = static_cast<int>(ExitCode::Unstable);
        }
    }
    // NAME.instability.json as simulate wrote it.
    const json& instability() {
        if (!instability_) instability_ = parse_instability_record(read_file(file(".instability.json"), "instability record"),
                                                                   file(".instability.json"));
        return *instability_;
    }

    const std::string& trajectory_hash() {
        if (trajectory_hash_.empty()) trajectory_hash_ = file_hash(file(".traj"));
        return trajectory_hash_;
    }
    const Trajectory& trajectory() {
        if (!trajectory_) trajectory_ = load_trajectory(file(".traj"));
        return *trajectory_;
    }

    // ---- render
    json render_inputs() {
        json in = {{"model", model_hash()}, {"trajectory", trajectory_hash()}, {"render", to_json(shot_.render)}};
        // An interior texture by its bytes: an image changed under the same name draws again.
        if (!shot_.render.interior_texture.empty()) in["interior_texture"] = file_hash(shot_.render.interior_texture);
        return in;
    }
    const std::string& render_key() {
        if (render_key_.empty()) render_key_ = stage_key("render", render_inputs());
        return render_key_;
    }
    bool all_frames_present() {
        std::error_code ec;
        for (uint32_t f = 0; f < trajectory().frames(); ++f)
            if (!fs::exists(fs::path(frames_dir()) / frame_file_name(f), ec)) return false;
        return true;
    }
    // The frames folder holds frames of one render key (frames/.key); frames of another are removed.
    void prepare_frames_dir() {
        FileLock lock((dir_ / ".shatter" / "render.lock").string());
        const fs::path key_file = fs::path(frames_dir()) / ".key";
        std::error_code ec;
        std::string current;
        if (fs::exists(key_file, ec)) current = read_file(key_file.string(), "frames key");
        if (current == render_key() + "\n" && !options_.force) return;
        make_directories(frames_dir());
        for (const auto& entry : fs::directory_iterator(frames_dir(), ec))
            if (entry.path().filename().string().rfind("frame_", 0) == 0) fs::remove(entry.path(), ec);
        write_file_atomic(key_file.string(), render_key() + "\n");
    }
    // ---- encode, sheet, plot and export beside render
    //
    // Started once the frames folder is ready (prepare_frames_dir: no stale frame left to read),
    // each on a thread of its own, with what they read (model, trajectory, their hashes, the render
    // key) loaded first, so that the threads share only const state, the stamps' files (one per
    // stage) and the logger. Encode and the sheet wait for each frame's file they read (written
    // atomically by render's writer) until render is over. A chunk of a cluster render leaves them
    // to the final job.
    struct BesideResult {
        StageReport report;
        int exit_code = 0;
    };
    struct Beside {
        Stage stage;
        std::future<BesideResult> done;
        size_t index = SIZE_MAX;  // its report in result_.stages, once the loop is at its place
    };
    void start_beside() {
        model();
        trajectory();
        model_hash();
        trajectory_hash();
        render_key();
        render_over_ = false;
        for (Stage s : {Stage::Encode, Stage::Sheet, Stage::Plot, Stage::Export}) {
            if (!asked(s) || ((s == Stage::Encode || s == Stage::Sheet) && options_.chunks != 1)) continue;
            const StageStep* step = &step_of(s);
            encoding_beside_ = encoding_beside_ || s == Stage::Encode;
            beside_.push_back({s, std::async(std::launch::async, [this, step] { return finish_beside_render(*step); })});
        }
    }
    BesideResult finish_beside_render(const StageStep& step) {
        BesideResult out{.report = {step.stage, StageOutcome::Ran, 0, {}, true}};
        const auto start = std::chrono::steady_clock::now();
        const std::string name = to_string(step.stage);
        try {
            const std::string key = key_of(step);
            if (current(step, key) && !options_.force) {
                out.report.outcome = StageOutcome::UpToDate;
            } else {
                stamps_.remove(name);
                out.report.outcome = compute_local(step, key, step.compute_beside ? step.compute_beside : step.compute);
            }
        } catch (const Error& e) {
            failed(out.report, e.what());
            out.exit_code = static_cast<int>(e.code());
        } catch (const std::exception& e) {  // (a thread must not end by an exception)
            failed(out.report, e.what());
            out.exit_code = static_cast<int>(ExitCode::Internal);
        }
        out.report.seconds = seconds_since(start);
        return out;
    }
    // Frame f's file is there (true), or render is over without it (false).
    bool frame_drawn(uint32_t f) {
        const fs::path path = fs::path(frames_dir()) / frame_file_name(f);
        for (;;) {
            const bool over = render_over_;
            std::error_code ec;
            if (fs::exists(path, ec)) return true;
            if (over) return false;
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
    }
    // Their reports, in pipeline order, into the run's.
    void join_beside() {
        render_over_ = true;
        for (Beside& b : beside_) {
            BesideResult r = b.done.get();
            if (b.index == SIZE_MAX) continue;  // (not reached: the loop passes every stage before the report)
            result_.stages[b.index] = std::move(r.report);
            log_outcome(result_.stages[b.index]);
            if (r.exit_code != 0 && result_.exit_code == 0) result_.exit_code = r.exit_code;
        }
        beside_.clear();
    }
    // When the run ends by an error: the threads end, their results dropped.
    void finish_beside() {
        render_over_ = true;
        for (Beside& b : beside_)
            if (b.done.valid()) b.done.wait();
        beside_.clear();
    }

    void compute_render() {
        prepare_frames_dir();
        start_beside();
        struct RenderOver {
            std::atomic<bool>& over;
            ~RenderOver() { over = true; }
        } render_over{render_over_};
        const RenderScene scene = make_render_scene(model(), file(".model"), trajectory(), file(".traj"));
        RenderOptions ro;
        ro.progress = options_.progress;
        ro.skip_existing = true;
        // Encode, beside render, takes the frames' pixels from memory (it reads the files of those
        // that do not fit, and of frames drawn before).
        if (encoding_beside_)
            ro.on_pixels = [this](uint32_t f, uint32_t w, uint32_t h, const std::vector<uint8_t>& rgb) {
                pixels_.put(f, w, h, rgb);
            };
        ro.size_source = options_.shot + ": [render] width, height";
        const auto [first, end] = chunk_frames(trajectory().frames(), options_.chunk, options_.chunks);
        const FrameRange range{first, end};
        if (range.first < range.end) {
            const RenderReport rr = render_frames(scene, shot_.render, range, frames_dir(), ro);
            spdlog::info("render: {} of frames {}..{} drawn ({} already there{})", rr.frames, range.first, range.end - 1,
                         range.end - range.first - rr.frames,
                         rr.repeated ? fmt::format("; {} the same picture as the frame before, its file written again",
                                                   rr.repeated)
                                     : "");
        }
        const CameraCoverage cover = camera_coverage(scene, shot_.render);
        spdlog::info("render: camera {}: {:.0f}% of the pieces in view in the first frame, at least {:.0f}% in "
                     "every frame (frame {}), {:.2f} s still at the end; the main mass fills {:.0f}% of the image at "
                     "least (frame {}), {:.0f}% in the median frame; {} frames without ground at the bottom",
                     shot_.render.camera_position ? "placed by the shot" : to_string(shot_.render.camera), 100 * cover.first,
                     100 * cover.least, cover.least_frame, cover.still_at_end, 100 * cover.fill_least,
                     cover.fill_least_frame, 100 * cover.fill_median, cover.frames_without_ground);
    }

    // summary.json: what the run made, deterministic (no times; those are in run.log).
    void write_summary() {
        std::error_code ec;
        if (!fs::exists(file(".model"), ec) || !fs::exists(file(".traj"), ec) ||
            !current(step_of(Stage::Simulate), stage_key("simulate", simulate_inputs())))
            return;
        const Model& m = model();
        size_t parts = 0;
        for (const Piece& p : m.pieces) parts += p.collision.size();
        json s;
        s["shot"] = as_utf8(options_.shot);
        s["overrides"] = json::array();
        for (const std::string& o : options_.overrides) s["overrides"].push_back(as_utf8(o));
        s["model"] = {{"pieces", m.pieces.size()},
                      {"constraints", m.constraints.size()},
                      {"tets", m.mesh.tets.size()},
                      {"collision_parts", parts}};
        // What prescore chose for the mesh, and why (the model's settings keep it).
        const json model_settings = json::parse(m.settings_json, nullptr, false);
        if (json chosen = stage_choices(model_settings); !chosen.empty()) s["model"]["auto"] = std::move(chosen);
        if (json warned = stage_warnings(model_settings); !warned.empty()) s["model"]["warnings"] = std::move(warned);
        if (model_settings.is_object() && model_settings.contains("impact")) s["model"]["impact"] = model_settings["impact"];
        s["alpha"] = shot_.material.alpha;
        s["simulation"] = simulation_facts(m, trajectory(), read_file(file(".breaks.jsonl"), "break log"),
                                           read_file(file(".energy.csv"), "energy series"));
        // What simulate chose (joints, a stiffness raised), and why (the trajectory's settings keep it).
        const json trajectory_settings = json::parse(trajectory().settings_json, nullptr, false);
        if (json chosen = stage_choices(trajectory_settings); !chosen.empty()) s["simulation"]["auto"] = std::move(chosen);
        if (json warned = stage_warnings(trajectory_settings); !warned.empty())
            s["simulation"]["warnings"] = std::move(warned);
        s["instability"] = instability();
        json files = json::object();
        for (const char* suffix : {".model", ".pieces.ply", ".traj", ".breaks.jsonl", ".energy.csv", ".instability.json", ".mp4",
                                   ".contact.png", ".energy.png", ".glb"})
            if (fs::exists(file(suffix), ec)) files[std::string(suffix).substr(1)] = name_ + suffix;
        if (all_frames_present()) files["frames"] = "frames/frame_%05d.png";
        if (asked(Stage::Report) || fs::exists(dir_ / "report.html", ec)) files["report"] = "report.html";
        s["files"] = files;
        // Paths and file names as the file system has them, which need not be UTF-8: made valid.
        write_file_atomic((dir_ / "summary.json").string(), s.dump(2, ' ', false, json::error_handler_t::replace) + "\n");
        result_.summary = std::move(s);
    }

    const RunOptions& options_;
    Shot shot_;
    fs::path dir_;
    std::string name_;
    StageStamps stamps_;
    StageCache cache_;
    RunResult result_;
    std::string model_hash_, trajectory_hash_, render_key_;
    std::optional<Model> model_;
    std::optional<Trajectory> trajectory_;
    std::optional<json> instability_;
    std::vector<StageStep> steps_;
    std::vector<Beside> beside_;
    std::atomic<bool> render_over_{true};
    FramePixels pixels_;           // frames' pixels from render to encode beside it
    bool encoding_beside_ = false;  // (set before render starts)
};

}  // namespace

RunResult run_shot(const RunOptions& options) { return Runner(options).run(); }

std::vector<Stage> up_to_date_stages(const RunOptions& options) { return Runner(options).up_to_date(); }

namespace {

// "impact: at (x, y, z) m, speed v m/s; pieces graded ..." (seeds = "impact").
std::string format_impact(const json& impact) {
    const json contacts = impact.value("contacts", json::array());
    const json* first = nullptr;
    for (const json& c : contacts)
        if (c.value("grades", false)) {
            first = &c;
            break;
        }
    if (!first)
        return fmt::format("impact:   none that closes ({} contact{}); pieces not graded: uniform seeds\n",
                           contacts.size(), contacts.size() == 1 ? "" : "s");
    const json& p = (*first)["point_m"];
    if (!impact.value("graded", false))
        return fmt::format("impact:   at ({:.3f}, {:.3f}, {:.3f}) m, speed {:.2f} m/s, on the {} after {:.3f} s; pieces not "
                           "graded: uniform seeds (damage number rho v^2 / strength {:.3g}: impact_ratio {:.3g}, too "
                           "gentle)\n",
                           p[0].get<double>(), p[1].get<double>(), p[2].get<double>(),
                           (*first)["speed_m_per_s"].get<double>(), (*first)["with"].get<std::string>(),
                           (*first)["time_s"].get<double>(), impact.value("damage_number", 0.0),
                           impact.value("ratio", 1.0));
    return fmt::format("impact:   at ({:.3f}, {:.3f}, {:.3f}) m, speed {:.2f} m/s, on the {} after {:.3f} s; pieces graded: "
                       "seeds {:.3g} times denser there, falling off over {:.3g} m{}\n",
                       p[0].get<double>(), p[1].get<double>(), p[2].get<double>(),
                       (*first)["speed_m_per_s"].get<double>(), (*first)["with"].get<std::string>(),
                       (*first)["time_s"].get<double>(), impact["ratio"].get<double>(), impact["radius_m"].get<double>(),
                       impact.value("ratio_auto", false) || impact.value("radius_auto", false)
                           ? fmt::format(" (auto: damage number rho v^2 / strength {:.3g})",
                                         impact.value("damage_number", 0.0))
                           : "");
}

}  // namespace

std::string format_run_summary(const RunResult& r) {
    std::string out;
    double total = 0;
    std::string times;
    for (const StageReport& s : r.stages) {
        if (s.outcome == StageOutcome::NotAsked) continue;
        total += s.seconds;
        times += fmt::format("{}{} {:.2f}s{}", times.empty() ? "" : ", ", to_string(s.stage), s.seconds,
                             (s.outcome == StageOutcome::Ran ? "" : fmt::format(" ({})", to_string(s.outcome))) +
                                 (s.beside_render ? " [beside render]" : ""));
    }
    const bool overlapped = std::any_of(r.stages.begin(), r.stages.end(), [](const StageReport& s) { return s.beside_render; });
    out += fmt::format("stages:   {} (total {:.2f}s{})\n", times, overlapped ? r.seconds : total,
                       overlapped ? ", the run's wall time" : "");
    if (!r.summary.empty()) {
        const json& m = r.summary["model"];
        const json& sim = r.summary["simulation"];
        out += fmt::format("model:    {} pieces, {} constraints, {} tets, {} collision parts\n", m["pieces"].get<size_t>(),
                           m["constraints"].get<size_t>(), m["tets"].get<size_t>(), m["collision_parts"].get<size_t>());
        std::string chosen;
        for (const json* list : {&m, &sim})
            if (list->contains("auto"))
                for (const json& c : (*list)["auto"]) chosen += (chosen.empty() ? "" : "; ") + c.value("what", std::string());
        if (!chosen.empty()) out += fmt::format("chosen:   {} (why: report.html, summary.json)\n", chosen);
        if (m.contains("impact")) out += format_impact(m["impact"]);
        const size_t breaks = sim["breaks"].get<size_t>(), fragments = sim["fragments"].get<size_t>();
        out += fmt::format("fracture: {} break{} -> {} fragment{}; {:.4g} J stored at the breaks, {:.4g} J injected "
                           "(alpha {:g}); peak piece speed {:.3g} m/s{}\n",
                           breaks, breaks == 1 ? "" : "s", fragments, fragments == 1 ? "" : "s", sim["stored_energy_J"].get<double>(),
                           sim["injected_energy_J"].get<double>(), r.summary["alpha"].get<double>(),
                           sim["peak_piece_speed_m_per_s"].get<double>(),
                           sim["complete"].get<bool>() ? "" : " (INCOMPLETE: the simulation went unstable)");
        // The energy books: what the breaks stored, alpha times it, and what the kicks gave back.
        const double stored = sim["stored_energy_J"].get<double>(), alpha = r.summary["alpha"].get<double>();
        const double injected = sim["injected_energy_J"].get<double>();
        // (The held energy is a sum of what breaks held less what later ones gave back: round-off
        // when every crack opened.)
        const double held = sim.value("held_energy_J", 0.0);
        const bool holds = held > 1e-9 * alpha * stored;
        if (breaks > 0)
            out += fmt::format("books:    stored {:.4g} J x alpha {:g} = {:.4g} J; injected {:.4g} J{}{}\n", stored, alpha,
                               alpha * stored, injected,
                               holds ? fmt::format(" + {:.4g} J held in cracks that did not open", held) : std::string(),
                               alpha * stored > 0
                                   ? fmt::format(" ({:.3f} x alpha x stored)", (injected + held) / (alpha * stored))
                                   : std::string());
        if (sim.contains("energy_books_drift_J")) {
            // The plot of those books, where the run made one.
            const json& files = r.summary.value("files", json::object());
            const std::string plot = files.contains("energy.png")
                                         ? fmt::format(" ({}/{})", r.output_dir, files["energy.png"].get<std::string>())
                                         : std::string();
            out += fmt::format("energy:   kinetic + potential + elastic + removed + damped + contacts + integration - "
                               "injected - driven stays within {:.2g} J over the run{}\n",
                               sim["energy_books_drift_J"].get<double>(), plot);
        }
        out += format_instability(r.summary.at("instability"));
    }
    out += fmt::format("results:  {}/\n", r.output_dir);
    if (!r.summary.empty())
        for (const auto& [what, name] : r.summary["files"].items())
            out += fmt::format("  {:<16} {}/{}\n", what, r.output_dir, name.get<std::string>());
    if (!r.warnings.empty()) {
        out += fmt::format("warnings: {} (prescore's and simulate's also in summary.json and report.html)\n",
                           r.warnings.size());
        for (const std::string& w : r.warnings) out += fmt::format("  - {}\n", w);
    }
    for (const StageReport& s : r.stages)
        if (s.outcome == StageOutcome::Failed) out += fmt::format("FAILED:   {}: {}\n", to_string(s.stage), s.error);
    return out;
}

}  // namespace shatter
