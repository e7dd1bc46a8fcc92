#include "pipeline/batch.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "pipeline/batch_page.h"
#include "pipeline/plot.h"
#include "pipeline/process.h"
#include "pipeline/sheets.h"
#include "render/render.h"
#include "core/workers.h"

namespace shatter {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// The last line of a run's console that says what went wrong.
std::string last_error_line(const std::string& console) {
    std::string text;
    try {
        text = read_file(console, "console log");
    } catch (const Error&) {
        return "";
    }
    std::string last, any;
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(start, end - start);
        if (line.find("error") != std::string::npos || line.find("FAILED") != std::string::npos) last = line;
        if (!line.empty()) any = line;
        start = end + 1;
    }
    return last.empty() ? any : last;
}

struct Active {
    size_t index;
    std::unique_ptr<ChildProcess> child;
    std::chrono::steady_clock::time_point start;
};

double number_or(const json& j, const char* key, double fallback) {
    return j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

// The strip, the energy plot and the table of one sweep.
void sweep_outputs(const BatchJob& job, const std::vector<const BatchRunResult*>& runs, BatchResult& result) {
    std::vector<const BatchRunResult*> ok;
    for (const BatchRunResult* r : runs)
        if (r->exit_code == 0 && !r->summary.is_null()) ok.push_back(r);
    const fs::path dir(job.output_dir);
    auto attempt = [&](const std::string& what, const std::string& path, auto make) {
        try {
            make();
            result.made.push_back(path);
        } catch (const Error& e) {
            result.problems.push_back(fmt::format("{} {}: {}", job.name, what, e.what()));
        }
    };

    // Table: every run, failed ones too.
    std::string md = "| run | breaks | fragments | stored at breaks (J) | injected (J) | KE 0.1 s after first break (J) | "
                     "spread KE 0.1 s after (J) | peak piece speed (m/s) |\n|---|---:|---:|---:|---:|---:|---:|---:|\n";
    std::string csv = "run,breaks,fragments,stored_J,injected_J,kinetic_after_first_break_J,spread_after_first_break_J,"
                      "peak_speed_m_per_s\n";
    for (const BatchRunResult* r : runs) {
        if (r->summary.is_null()) {
            md += fmt::format("| {} | failed | | | | | | |\n", r->caption);
            csv += fmt::format("\"{}\",,,,,,,\n", r->caption);
            continue;
        }
        const json& s = r->summary["simulation"];
        const double ke = number_or(s, "kinetic_energy_after_first_break_J", NAN);
        const double spread = number_or(s, "spread_energy_after_first_break_J", NAN);
        auto cell = [](double v, const char* format) { return std::isnan(v) ? std::string("-") : fmt::format(fmt::runtime(format), v); };
        md += fmt::format("| {} | {} | {} | {:.4g} | {:.4g} | {} | {} | {:.3g} |\n", r->caption, s["breaks"].get<size_t>(),
                          s["fragments"].get<size_t>(), s["stored_energy_J"].get<double>(),
                          s["injected_energy_J"].get<double>(), cell(ke, "{:.4g}"), cell(spread, "{:.4g}"),
                          s["peak_piece_speed_m_per_s"].get<double>());
        csv += fmt::format("\"{}\",{},{},{:.9g},{:.9g},{},{},{:.9g}\n", r->caption, s["breaks"].get<size_t>(),
                           s["fragments"].get<size_t>(), s["stored_energy_J"].get<double>(),
                           s["injected_energy_J"].get<double>(), cell(ke, "{:.9g}"), cell(spread, "{:.9g}"),
                           s["peak_piece_speed_m_per_s"].get<double>());
    }
    const std::string md_path = (dir / (job.name + ".table.md")).string();
    const std::string csv_path = (dir / (job.name + ".table.csv")).string();
    attempt("table", md_path, [&] { write_file_atomic(md_path, md); });
    attempt("table", csv_path, [&] { write_file_atomic(csv_path, csv); });
    if (ok.size() < 2) return;

    // The energy plot: one kinetic-energy curve per run.
    std::vector<EnergyCurve> curves;
    for (const BatchRunResult* r : ok) {
        const std::string name = fs::path(job.shot).stem().string();
        curves.push_back({r->caption, (fs::path(r->output_dir) / (name + ".energy.csv")).string()});
    }
    const std::string plot = (dir / (job.name + ".energy.png")).string();
    attempt("energy plot", plot, [&] { plot_energy(curves, job.name, plot); });

    // The strip: every run at the same moment, by default 0.5 s after the latest first break.
    const double when = strip_moment(job, ok);
    std::vector<StripPanel> panels;
    for (const BatchRunResult* r : ok) {
        const json& s = r->summary["simulation"];
        const uint32_t frames = s["frames"].get<uint32_t>();
        const uint32_t f = std::min<uint32_t>(frames - 1, uint32_t(std::lround(when * s["fps"].get<double>())));
        panels.push_back({(fs::path(r->output_dir) / frame_at(*r, when)).string(),
                          fmt::format("{}  t = {:.2f} s", r->caption, f / s["fps"].get<double>())});
    }
    const std::string strip = (dir / (job.name + ".strip.png")).string();
    attempt("strip", strip, [&] { write_strip(panels, strip); });
}

}  // namespace

double strip_moment(const BatchJob& job, const std::vector<const BatchRunResult*>& ok) {
    if (job.strip_time) return *job.strip_time;
    double when = 0;
    for (const BatchRunResult* r : ok) when = std::max(when, number_or(r->summary["simulation"], "first_break_s", 0.0) + 0.5);
    return when;
}

std::string frame_at(const BatchRunResult& run, double when) {
    const json& s = run.summary["simulation"];
    const uint32_t frames = s["frames"].get<uint32_t>();
    const uint32_t f = std::min<uint32_t>(frames - 1, uint32_t(std::lround(when * s["fps"].get<double>())));
    return (fs::path("frames") / frame_file_name(f)).string();
}

BatchResult run_batch(const BatchFile& batch, const BatchOptions& options) {
    const std::string exe = options.shatter.empty() ? own_executable() : options.shatter;
    const uint32_t workers = options.workers ? options.workers : batch.workers;
    // The runs share the cores: each simulates on its share of them (core/workers.h; the
    // result does not depend on it), unless the user's environment says otherwise.
    if (workers > 1 && !std::getenv("SHATTER_THREADS"))
        setenv("SHATTER_THREADS", std::to_string(std::max(1u, usable_cores() / workers)).c_str(), 0);
    BatchResult result;
    for (const BatchJob& job : batch.jobs)
        for (const BatchRun& run : job.runs)
            result.runs.push_back({job.name, run.label, run.caption, run.output_dir, -1, {}, 0, nullptr});
    std::vector<const BatchRun*> specs;
    std::vector<const BatchJob*> spec_job;
    for (const BatchJob& job : batch.jobs)
        for (const BatchRun& run : job.runs) specs.push_back(&run), spec_job.push_back(&job);

    make_directories(batch.output_dir);
    std::deque<size_t> queue;
    for (size_t i = 0; i < specs.size(); ++i) queue.push_back(i);
    std::vector<Active> active;
    size_t finished = 0;
    while (!queue.empty() || !active.empty()) {
        while (!queue.empty() && active.size() < workers) {
            const size_t i = queue.front();
            queue.pop_front();
            const BatchRun& run = *specs[i];
            make_directories(run.output_dir);
            std::vector<std::string> argv = {exe, "run", spec_job[i]->shot, "-o", run.output_dir, "--cache",
                                             batch.cache_dir(), "--no-progress"};
            for (const std::string& o : run.overrides) argv.insert(argv.end(), {"--set", o});
            ProcessOptions po;
            po.output_file = (fs::path(run.output_dir) / "console.log").string();
            std::error_code ec;
            fs::remove(po.output_file, ec);
            active.push_back({i, std::make_unique<ChildProcess>(argv, po), std::chrono::steady_clock::now()});
        }
        bool any = false;
        for (size_t a = 0; a < active.size();) {
            std::optional<ProcessResult> done = active[a].child->poll();
            if (!done) {
                ++a;
                continue;
            }
            any = true;
            BatchRunResult& r = result.runs[active[a].index];
            r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - active[a].start).count();
            r.exit_code = done->signal ? 128 + done->signal : done->exit_code;
            const fs::path summary = fs::path(r.output_dir) / "summary.json";
            std::error_code ec;
            if (fs::exists(summary, ec)) {
                try {
                    r.summary = json::parse(read_file(summary.string(), "run summary"));
                } catch (const std::exception&) {
                    r.summary = nullptr;
                }
            }
            if (r.exit_code != 0) {
                r.error = last_error_line((fs::path(r.output_dir) / "console.log").string());
                if (r.error.empty()) r.error = done->describe();
            }
            ++finished;
            if (options.progress)
                fmt::print(stderr, "batch: [{}/{}] {}/{} {} ({:.1f}s){}\n", finished, specs.size(), r.job, r.label,
                           r.exit_code == 0 ? "ok" : "FAILED", r.seconds, r.exit_code == 0 ? "" : ": " + r.error);
            active.erase(active.begin() + a);
        }
        if (!any) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }

    size_t k = 0;
    for (const BatchJob& job : batch.jobs) {
        std::vector<const BatchRunResult*> runs;
        for (size_t j = 0; j < job.runs.size(); ++j) runs.push_back(&result.runs[k++]);
        if (job.runs.size() > 1) sweep_outputs(job, runs, result);
    }
    const std::string index = (fs::path(batch.output_dir) / "index.html").string();
    try {
        write_file_atomic(index, batch_page_html(batch, result));
        result.made.push_back(index);
    } catch (const Error& e) {
        result.problems.push_back(fmt::format("index.html: {}", e.what()));
    }
    for (const BatchRunResult& r : result.runs)
        if (r.exit_code != 0) result.exit_code = static_cast<int>(ExitCode::Differs);
    return result;
}

std::string format_batch_table(const BatchResult& result) {
    std::string out = fmt::format("{:<28} {:<8} {:>8} {:>7} {:>10} {:>12} {:>12}\n", "run", "status", "time (s)", "breaks",
                                  "fragments", "stored (J)", "injected (J)");
    size_t failed = 0;
    for (const BatchRunResult& r : result.runs) {
        const std::string name = r.job + "/" + r.label;
        if (r.summary.is_null() || r.exit_code != 0) {
            ++failed;
            out += fmt::format("{:<28} {:<8} {:>8.1f}   {}\n", name, fmt::format("exit {}", r.exit_code), r.seconds, r.error);
            continue;
        }
        const json& s = r.summary["simulation"];
        out += fmt::format("{:<28} {:<8} {:>8.1f} {:>7} {:>10} {:>12.4g} {:>12.4g}\n", name, "ok", r.seconds,
                           s["breaks"].get<size_t>(), s["fragments"].get<size_t>(), s["stored_energy_J"].get<double>(),
                           s["injected_energy_J"].get<double>());
    }
    for (const std::string& m : result.made) out += fmt::format("wrote:  {}\n", m);
    for (const std::string& p : result.problems) out += fmt::format("problem: {}\n", p);
    out += failed ? fmt::format("{} of {} runs FAILED (their console.log says why)\n", failed, result.runs.size())
                  : fmt::format("all {} runs succeeded\n", result.runs.size());
    return out;
}

}  // namespace shatter
