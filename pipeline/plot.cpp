// Energy plots, drawn in-process (pipeline/line_chart.h): no interpreter starts beside render.
// The CSVs are read and checked here (file:line errors for a bad one).
#include "pipeline/plot.h"

#include <algorithm>

#include "core/atomic_file.h"
#include "core/error.h"
#include "pipeline/energy_csv.h"
#include "pipeline/line_chart.h"
#include "render/png_io.h"

namespace shatter {

namespace {

EnergySeries read_energy_csv(const std::string& path) { return parse_energy_csv(read_file(path, "energy CSV"), path); }

ChartSeries series(const std::vector<double>& t, std::vector<double> y, Rgb colour, Dash dash, std::string label) {
    ChartSeries s;
    s.x = t, s.y = std::move(y), s.colour = colour, s.dash = dash, s.label = std::move(label);
    return s;
}

std::vector<double> relative(std::vector<double> v) {
    const double first = v.empty() ? 0.0 : v.front();
    for (double& x : v) x -= first;
    return v;
}

// One run: every term of the books that moves, and their sum, which stays flat when all is counted.
LineChart one_run(const EnergySeries& c) {
    LineChart chart;
    const auto& t = c.t;
    chart.series.push_back(series(t, c.kinetic, tab10(0), Dash::Solid, "kinetic"));
    chart.series.push_back(series(t, relative(c.potential), tab10(1), Dash::Solid, "potential (relative to t = 0)"));
    chart.series.push_back(series(t, c.stored, tab10(2), Dash::Solid, "stored (constraints' forces)"));
    if (!c.elastic.empty())
        chart.series.push_back(series(t, c.elastic, tab10(2), Dash::Dotted, "elastic (constraints' stretch)"));
    chart.series.push_back(series(t, c.injected, tab10(3), Dash::Dashed, "injected (breaks)"));
    if (!c.books.empty()) {
        chart.series.push_back(series(t, c.joints_took, tab10(4), Dash::Dotted,
                                      "taken by the joints (damping, and the stretch of broken ones)"));
        chart.series.push_back(
            series(t, c.contacts_took, tab10(7), Dash::Dotted, "taken by contacts and the step's integration"));
        if (std::any_of(c.driven.begin(), c.driven.end(), [](double d) { return d != 0; }))
            chart.series.push_back(series(t, c.driven, tab10(5), Dash::DashDot, "given by driven pieces and props"));
        ChartSeries books = series(t, relative(c.books), Rgb{0, 0, 0}, Dash::Solid,
                                   "books (every term, relative to t = 0): flat when all is counted");
        books.width = 0.8;
        chart.series.push_back(std::move(books));
    }
    return chart;
}

// Several runs: each one's kinetic energy in its colour, its injected energy dashed.
LineChart several_runs(const std::vector<EnergyCurve>& curves, const std::vector<EnergySeries>& data) {
    LineChart chart;
    chart.legend_title = "kinetic energy";
    chart.small_legend = false;
    for (size_t i = 0; i < data.size(); ++i) {
        chart.series.push_back(series(data[i].t, data[i].kinetic, tab10(i), Dash::Solid, curves[i].label));
        chart.series.push_back(series(data[i].t, data[i].injected, tab10(i), Dash::Dashed, ""));
    }
    chart.series.push_back(series({}, {}, Rgb{0x66, 0x66, 0x66}, Dash::Dashed, "injected (dashed)"));
    return chart;
}

}  // namespace

void plot_energy(const std::vector<EnergyCurve>& curves, const std::string& title, const std::string& png_path) {
    if (curves.empty()) throw_input_error(png_path, "no energy curves to plot", "give at least one run");
    std::vector<EnergySeries> data;
    for (const EnergyCurve& c : curves) data.push_back(read_energy_csv(c.csv_path));
    LineChart chart = curves.size() == 1 ? one_run(data[0]) : several_runs(curves, data);
    chart.title = title;
    chart.x_label = "time (s)";
    chart.y_label = "energy (J)";
    write_file_atomic(png_path, encode_png(draw_chart(chart)));
}

}  // namespace shatter
