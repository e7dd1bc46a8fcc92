// Energy plots by matplotlib.
//
// The CSVs are read and checked here (file:line errors for a bad one), and the numbers go to a
// built-in Python script as JSON on its stdin; the output path is an argv element. Nothing is
// ever formatted into code or a command string. The script draws with the Agg backend at a fixed
// size and DPI and saves without the "Software" text chunk (the only thing in matplotlib's PNG
// that names a version), so the same data gives the same bytes.
//
// Interpreter: Debian's /usr/bin/python3 first (python3-matplotlib installs there; the first
// python3 on PATH may be a pyenv or venv without it), then python3 on PATH. The script exits
// with kNoMatplotlib when it cannot import matplotlib, and the next interpreter is tried.
#include "pipeline/plot.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "pipeline/process.h"
#include "pipeline/tool_output.h"

namespace shatter {

namespace {

constexpr int kNoMatplotlib = 17;

constexpr const char* kScript = R"PY(
import sys
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
except ImportError as e:
    sys.stderr.write("cannot import matplotlib: %s\n" % e)
    sys.exit(17)
import json

def text(s):
    # plain text: no mathtext ($...$), and a leading "_" would hide a legend entry
    s = s.replace("$", r"\$")
    return " " + s if s.startswith("_") else s

data = json.load(sys.stdin)
curves = data["curves"]
fig, ax = plt.subplots(figsize=(8, 4.5), dpi=100)
if len(curves) == 1:
    c = curves[0]
    p0 = c["potential"][0]
    ax.plot(c["t"], c["kinetic"], color="C0", label="kinetic")
    ax.plot(c["t"], [p - p0 for p in c["potential"]], color="C1", label="potential (relative to t = 0)")
    ax.plot(c["t"], c["stored"], color="C2", label="stored (constraints' forces)")
    if c["elastic"]:
        ax.plot(c["t"], c["elastic"], color="C2", linestyle=":", label="elastic (constraints' stretch)")
    ax.plot(c["t"], c["injected"], color="C3", linestyle="--", label="injected (breaks)")
    if c["books"]:
        ax.plot(c["t"], c["lost"], color="C4", linestyle=":", label="taken by the joints' damping, contacts and the step's integration")
        if any(d != 0 for d in c["driven"]):
            ax.plot(c["t"], c["driven"], color="C5", linestyle="-.", label="given by driven pieces and props")
        b0 = c["books"][0]
        ax.plot(c["t"], [b - b0 for b in c["books"]], color="k", linewidth=0.8,
                label="books (every term, relative to t = 0): flat when all is counted")
    ax.legend(loc="best", fontsize="small")
else:
    for i, c in enumerate(curves):
        colour = "C%d" % (i % 10)
        ax.plot(c["t"], c["kinetic"], color=colour, label=text(c["label"]))
        ax.plot(c["t"], c["injected"], color=colour, linestyle="--")
    handles, labels = ax.get_legend_handles_labels()
    handles.append(Line2D([], [], color="0.4", linestyle="--"))
    labels.append("injected (dashed)")
    ax.legend(handles, labels, loc="best", title="kinetic energy")
ax.set_title(text(data["title"]))
ax.set_xlabel("time (s)")
ax.set_ylabel("energy (J)")
ax.grid(True, alpha=0.3)
fig.tight_layout()
fig.savefig(sys.argv[1], format="png", dpi=100, metadata={"Software": None})
)PY";

std::vector<std::string> split(const std::string& line, char sep) {
    std::vector<std::string> out(1);
    for (char c : line) {
        if (c == sep)
            out.emplace_back();
        else if (c != '\r')
            out.back() += c;
    }
    return out;
}

}  // namespace

EnergySeries parse_energy_csv(const std::string& text, const std::string& path) {
    std::vector<std::string> lines = split(text, '\n');
    if (!lines.empty() && lines.back().empty()) lines.pop_back();
    const char* fix = "give an energy CSV written by shatter simulate (OUT.energy.csv)";
    if (lines.empty()) throw_input_error(path, "empty energy CSV", fix);
    const std::vector<std::string> header = split(lines[0], ',');
    // The first five columns are needed; older files lack the later ones: elastic_J, then the
    // books' other four (read only when all of them are there), then integration_J (0 without).
    const char* names[] = {"time_s",    "kinetic_J", "potential_J",     "stored_J",   "injected_J", "elastic_J",
                           "removed_J", "joints_damped_J", "contacts_J", "driven_J", "integration_J"};
    constexpr int kNeeded = 5, kBooks = 10, kAll = 11;
    size_t column[kAll];
    int columns = kAll;
    for (int k = 0; k < kAll; ++k) {
        auto it = std::find(header.begin(), header.end(), names[k]);
        if (it == header.end() && k < kNeeded)
            throw_input_error(path + ":1", fmt::format("header '{}' has no column {}", lines[0], names[k]), fix);
        if (it == header.end()) {
            columns = k == kNeeded ? kNeeded : k < kBooks ? kNeeded + 1 : kBooks;
            break;
        }
        column[k] = size_t(it - header.begin());
    }
    EnergySeries s;
    std::vector<double>* series[] = {&s.t, &s.kinetic, &s.potential, &s.stored, &s.injected, &s.elastic};
    for (size_t i = 1; i < lines.size(); ++i) {
        const std::string where = fmt::format("{}:{}", path, i + 1);
        const std::vector<std::string> fields = split(lines[i], ',');
        if (fields.size() != header.size())
            throw_input_error(where, fmt::format("{} fields where the header has {}", fields.size(), header.size()),
                              fix);
        double v[kAll];
        for (int k = 0; k < columns; ++k) {
            const std::string& f = fields[column[k]];
            auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v[k]);
            if (ec != std::errc() || end != f.data() + f.size() || !std::isfinite(v[k]))
                throw_input_error(where, fmt::format("{} '{}' is not a finite number", names[k], f), fix);
            if (k <= kNeeded) series[k]->push_back(v[k]);
        }
        if (columns >= kBooks) {
            // kinetic + potential + elastic + removed + joints_damped + contacts + integration -
            // injected - driven
            const double integration = columns == kAll ? v[10] : 0.0;
            s.books.push_back(v[1] + v[2] + v[5] + v[6] + v[7] + v[8] + integration - v[4] - v[9]);
            s.lost.push_back(v[7] + v[8] + integration);
            s.driven.push_back(v[9]);
        }
    }
    if (s.t.empty()) throw_input_error(path, "the energy CSV has a header but no samples", fix);
    return s;
}

namespace {

EnergySeries read_energy_csv(const std::string& path) { return parse_energy_csv(read_file(path, "energy CSV"), path); }

std::string plot_input(const std::vector<EnergyCurve>& curves, const std::string& title) {
    nlohmann::json j = {{"title", title}, {"curves", nlohmann::json::array()}};
    for (const EnergyCurve& c : curves) {
        const EnergySeries s = read_energy_csv(c.csv_path);
        j["curves"].push_back({{"label", c.label},
                               {"t", s.t},
                               {"kinetic", s.kinetic},
                               {"potential", s.potential},
                               {"stored", s.stored},
                               {"injected", s.injected},
                               {"elastic", s.elastic},
                               {"books", s.books},
                               {"lost", s.lost},
                               {"driven", s.driven}});
    }
    return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::vector<std::string> interpreters() {
    std::vector<std::string> out;
    if (auto debian = find_program("/usr/bin/python3")) out.push_back(*debian);
    if (auto on_path = find_program("python3"); on_path && (out.empty() || *on_path != out[0])) out.push_back(*on_path);
    return out;
}

}  // namespace

void plot_energy(const std::vector<EnergyCurve>& curves, const std::string& title, const std::string& png_path) {
    if (curves.empty()) throw_input_error(png_path, "no energy curves to plot", "give at least one run");
    const std::string input = plot_input(curves, title);
    const std::vector<std::string> pythons = interpreters();
    const std::string fix = "install matplotlib for Debian's python3: make deps, or apt-get install python3-matplotlib";
    if (pythons.empty())
        throw Error(ExitCode::Tool,
                    png_path + ": python3 not found (/usr/bin/python3 or on PATH), cannot plot (fix: " + fix + ")");

    ToolOutput output(png_path, ".png");  // removed again unless committed
    ProcessOptions options;
    options.stdin_data = input;
    options.env = {{"MPLBACKEND", "Agg"}};
    std::string tried;
    for (const std::string& python : pythons) {
        const ProcessResult r = run_process({python, "-c", kScript, output.path()}, options);
        if (r.exit_code == kNoMatplotlib) {
            tried += (tried.empty() ? "" : ", ") + python;
            continue;
        }
        if (!r.ok())
            throw Error(ExitCode::Tool, fmt::format("{}: the energy plot failed in {} ({}):\n{}\n(fix: check that {} "
                                                    "imports matplotlib; {})",
                                                    png_path, python, r.describe(), last_lines(r.err, 12), python, fix));
        output.commit();
        return;
    }
    throw Error(ExitCode::Tool,
                fmt::format("{}: matplotlib is missing in {}, cannot plot (fix: {})", png_path, tried, fix));
}

}  // namespace shatter
