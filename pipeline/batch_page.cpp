#include "pipeline/batch_page.h"

#include <filesystem>

#include <fmt/format.h>

#include "core/html.h"
#include "pipeline/run_metrics.h"

namespace shatter {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// A cell of one value of a run's summary.json at a JSON pointer (see report_page.cpp's rows).
std::string value_cell(const json& summary, const char* pointer, const char* format) {
    const json::json_pointer p(pointer);
    const json v = summary.contains(p) ? summary.at(p) : json(nullptr);
    std::string text = "-";
    if (v.is_number_integer() || v.is_number_unsigned()) text = v.dump();
    else if (v.is_number_float()) text = fmt::format(fmt::runtime(format), v.get<double>());
    else if (!v.is_null()) text = v.dump();
    return fmt::format("<td class=\"num\" data-key=\"{}\" data-value=\"{}\">{}</td>", html_escape(pointer),
                       html_escape(v.dump()), html_escape(text));
}

std::string link(const fs::path& relative) { return url_path(relative.generic_string()); }

}  // namespace

std::string batch_page_html(const BatchFile& batch, const BatchResult& result) {
    const fs::path root(batch.output_dir);
    size_t failed = 0;
    for (const BatchRunResult& r : result.runs) failed += r.exit_code != 0;
    // A batch file, or shots and meshes given by name (no file: the output folder names the page).
    const bool named = batch.path.empty();
    std::string out = page_begin(
        named ? fs::path(batch.output_dir).filename().string() : fs::path(batch.path).stem().string(),
        fmt::format("<code>shatter batch {}</code>: {} jobs, {} runs, {}",
                    named ? fmt::format("FILE... ({} files)", batch.jobs.size()) : html_escape(batch.path),
                    batch.jobs.size(), result.runs.size(),
                    failed ? fmt::format("<span class=\"bad\">{} failed</span>", failed) : std::string("all succeeded")));
    size_t k = 0;
    for (const BatchJob& job : batch.jobs) {
        std::vector<const BatchRunResult*> runs, ok;
        for (size_t j = 0; j < job.runs.size(); ++j, ++k) {
            runs.push_back(&result.runs[k]);
            if (result.runs[k].exit_code == 0 && !result.runs[k].summary.is_null()) ok.push_back(&result.runs[k]);
        }
        const double when = strip_moment(job, ok);
        const fs::path job_dir = fs::path(job.output_dir).lexically_relative(root);
        out += fmt::format("<h2 id=\"{0}\">{0}</h2>\n<p class=\"muted\">shot <code>{1}</code>{2}{3}</p>\n",
                           html_escape(job.name), html_escape(job.shot),
                           job.sweep_keys.empty() ? "" : "; sweep over " + html_escape(fmt::format("{}", fmt::join(job.sweep_keys, ", "))),
                           ok.empty() ? std::string()
                                      : fmt::format("; thumbnails: the frame at t = {:.2f} s ({}), or a run's last frame when it "
                                                    "ends before", when, job.strip_time ? "the job's strip_time"
                                                                                        : "0.5 s after the latest first break"));
        out += "<table class=\"runs\">\n<tr><th></th><th>run</th><th>settings</th><th>status</th><th class=\"num\">breaks</th>"
               "<th class=\"num\">fragments</th><th class=\"num\">stored at breaks (J)</th><th class=\"num\">injected (J)</th>"
               "<th class=\"num\">KE 0.1 s after first break (J)</th><th class=\"num\">peak piece speed (m/s)</th></tr>\n";
        for (const BatchRunResult* r : runs) {
            const fs::path dir = fs::path(r->output_dir).lexically_relative(root);
            std::string settings;
            for (const std::string& o : job.runs[size_t(r - runs.front())].overrides)
                settings += (settings.empty() ? "" : "<br>") + ("<code>" + html_escape(o) + "</code>");
            const bool good = r->exit_code == 0 && !r->summary.is_null();
            std::string thumb;
            if (good)
                thumb = fmt::format("<a href=\"{0}\"><img class=\"thumb\" src=\"{1}\" alt=\"{2}\"></a>", link(dir / "report.html"),
                                    link(dir / frame_at(*r, when)), html_escape(r->caption));
            out += fmt::format("<tr data-run=\"{}\"><td>{}</td><td><a href=\"{}\">{}</a></td><td>{}</td>",
                               html_escape(r->job + "/" + r->label), thumb, link(dir / (good ? "report.html" : "console.log")),
                               html_escape(r->caption), settings.empty() ? "-" : settings);
            if (!good) {
                out += fmt::format("<td class=\"bad\" colspan=\"7\">exit {}: {} (<a href=\"{}\">console.log</a>)</td></tr>\n",
                                   r->exit_code, html_escape(r->error), link(dir / "console.log"));
                continue;
            }
            // The run's warnings (prescore's and simulate's), counted, with a link to where its page lists them.
            const size_t warned = summary_warnings(r->summary).size();
            const std::string warnings =
                warned == 0 ? "" : fmt::format("<br><a class=\"warned\" href=\"{}\">{} warning{}</a>", link(dir / "report.html") + "#warnings",
                                               warned, warned == 1 ? "" : "s");
            out += "<td class=\"ok\">ok" + warnings + "</td>" + value_cell(r->summary, "/simulation/breaks", "{}") +
                   value_cell(r->summary, "/simulation/fragments", "{}") +
                   value_cell(r->summary, "/simulation/stored_energy_J", "{:.4g}") +
                   value_cell(r->summary, "/simulation/injected_energy_J", "{:.4g}") +
                   value_cell(r->summary, "/simulation/kinetic_energy_after_first_break_J", "{:.4g}") +
                   value_cell(r->summary, "/simulation/peak_piece_speed_m_per_s", "{:.3g}") + "</tr>\n";
        }
        out += "</table>\n";
        if (job.runs.size() < 2) continue;
        // The sweep's strip, plot and table, when batch made them.
        auto made = [&](const std::string& suffix) {
            const std::string path = (fs::path(job.output_dir) / (job.name + suffix)).string();
            for (const std::string& m : result.made)
                if (m == path) return true;
            return false;
        };
        out += "<div class=\"grid\">\n";
        for (const auto& [suffix, what] : {std::pair<const char*, const char*>{".strip.png", "strip"}, {".energy.png", "kinetic energy"}}) {
            const fs::path file = job_dir / (job.name + suffix);
            if (made(suffix))
                out += fmt::format("<figure><a href=\"{0}\"><img src=\"{0}\" alt=\"{1}\"></a><figcaption>{1}: {2}</figcaption>"
                                   "</figure>\n", link(file), what, html_escape(file.generic_string()));
            else
                out += fmt::format("<p class=\"note\">No {} for this sweep (fewer than two runs succeeded, or it failed: see "
                                   "the batch's output).</p>\n", what);
        }
        out += "</div>\n";
        std::string tables;
        for (const char* suffix : {".table.md", ".table.csv"})
            if (made(suffix)) {
                const fs::path file = job_dir / (job.name + suffix);
                tables += fmt::format("{}<a href=\"{}\">{}</a>", tables.empty() ? "" : ", ", link(file),
                                      html_escape(file.generic_string()));
            }
        if (!tables.empty()) out += "<p>The sweep's table: " + tables + ".</p>\n";
    }
    if (!result.problems.empty()) {
        out += "<h2>Problems</h2>\n<ul>\n";
        for (const std::string& p : result.problems) out += "<li>" + html_escape(p) + "</li>\n";
        out += "</ul>\n";
    }
    return out + page_end();
}

}  // namespace shatter
