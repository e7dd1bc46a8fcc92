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

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "pipeline/energy_csv.h"
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
        ax.plot(c["t"], c["joints_took"], color="C4", linestyle=":", label="taken by the joints (damping, and the stretch of broken ones)")
        ax.plot(c["t"], c["contacts_took"], color="C7", linestyle=":", label="taken by contacts and the step's integration")
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
                               {"joints_took", s.joints_took},
                               {"contacts_took", s.contacts_took},
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
