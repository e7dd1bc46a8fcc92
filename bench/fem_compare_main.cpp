// fem_compare: the rigid method against the continuum reference on the study's beam
// (docs/accuracy.md section 8): first break, ties / constraints broken, fragments, and the
// pieces' kinetic energy and its spread about their common centre 0.1 s and 0.5 s after the
// first break, for the energized rigid method at alpha 0 to 1.5 (bench/study_scenes.cpp's
// beam_case, the study's defaults) and for the reference (bench/fem_beam.h); the alpha that
// matches the reference best; the cost of each. Writes fem_beam.csv into --out.
//
//   fem_compare [--cells N] [--step H] [--out DIR]     (default 4 cells across, h = 2e-4 s)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "bench/fem_beam.h"
#include "bench/study.h"
#include "core/fragments.h"

using namespace shatter;
using namespace shatter::study;

namespace {

struct Row {
    std::string method;
    double alpha = 0, first_break = NAN, ke01 = NAN, ke05 = NAN, sp01 = NAN, sp05 = NAN, cpu = 0;
    size_t broken = 0, total = 0, fragments = 0;
};

double nearest_kinetic(const SimulationResult& r, double t) {
    double best = 1e300, ke = NAN;
    for (const EnergySample& e : r.energy)
        if (std::abs(e.time - t) < best) best = std::abs(e.time - t), ke = e.kinetic;
    return ke;
}

double rel(double x, double ref) { return std::abs(x - ref) / ref; }

}  // namespace

int main(int argc, char** argv) {
    spdlog::set_level(spdlog::level::warn);
    uint32_t cells = 4;
    double h = 2e-4;
    std::string out = "bench/results/study";
    for (int i = 1; i + 1 < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--cells") cells = uint32_t(std::atoi(argv[++i]));
        else if (a == "--step") h = std::atof(argv[++i]);
        else if (a == "--out") out = argv[++i];
    }
    std::vector<Row> rows;
    for (double alpha : {0.0, 0.25, 0.5, 0.75, 1.0, 1.5}) {
        StudyCase c = beam_case();
        apply_method("energized", c.input);
        c.input.material.alpha = alpha;
        c.input.simulate.duration = 0.9;
        const RunOutcome o = run_timed(c, 1);
        Row r;
        r.method = "rigid";
        r.alpha = alpha;
        r.first_break = first_break(o.sim);
        r.broken = o.sim.breaks.size();
        r.total = c.model.constraints.size();
        r.fragments = fragments(c.model, o.sim);
        r.cpu = o.cpu_seconds;
        if (std::isfinite(r.first_break)) {
            const Trajectory& t = o.sim.trajectory;
            r.ke01 = nearest_kinetic(o.sim, r.first_break + 0.1);
            r.ke05 = nearest_kinetic(o.sim, r.first_break + 0.5);
            r.sp01 = spread_energy(c.model, t, uint32_t(std::lround((r.first_break + 0.1) * t.fps)));
            r.sp05 = spread_energy(c.model, t, uint32_t(std::lround((r.first_break + 0.5) * t.fps)));
        }
        rows.push_back(r);
        std::fprintf(stderr, "rigid alpha %g: %.2f s\n", alpha, o.wall_seconds);
    }
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    const fem::FemBeamResult f = fem::run_fem_beam(cells, h);
    Row ref;
    ref.method = fmt::format("fem {} cells, h {:g}", cells, h);
    ref.alpha = NAN;
    ref.first_break = f.first_break;
    ref.broken = f.broken;
    ref.total = f.ties;
    ref.fragments = f.fragments;
    ref.ke01 = f.at_01.rigid;
    ref.ke05 = f.at_05.rigid;
    ref.sp01 = f.at_01.spread;
    ref.sp05 = f.at_05.spread;
    ref.cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    std::fprintf(stderr, "fem: %.1f s, %ld steps, %zu tets\n",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), f.steps, f.tets);

    Csv csv(out, "fem_beam.csv",
            "method,alpha,first_break_s,broken,of,fragments,kinetic_01_J,kinetic_05_J,spread_01_J,spread_05_J,cpu_s,"
            "energy_error");
    std::printf("| method | alpha | first break (s) | broken | fragments | KE +0.1 s (J) | KE +0.5 s (J) | spread +0.1 s (J) | spread +0.5 s (J) | CPU (s) | energy error |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
    double best = 1e300, best_alpha = NAN;
    rows.push_back(ref);
    for (const Row& r : rows) {
        // The mean relative distance of the four energies from the reference's.
        const double err = (rel(r.ke01, ref.ke01) + rel(r.ke05, ref.ke05) + rel(r.sp01, ref.sp01) + rel(r.sp05, ref.sp05)) / 4;
        if (r.method == "rigid" && err < best) best = err, best_alpha = r.alpha;
        std::printf("| %s | %s | %.4f | %zu of %zu | %zu | %.4g | %.4g | %.4g | %.4g | %.2f | %.3g |\n", r.method.c_str(),
                    std::isnan(r.alpha) ? "-" : fmt::format("{:g}", r.alpha).c_str(), r.first_break, r.broken, r.total,
                    r.fragments, r.ke01, r.ke05, r.sp01, r.sp05, r.cpu, err);
        csv.row(fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}", r.method, fmt_double(r.alpha), fmt_double(r.first_break),
                            r.broken, r.total, r.fragments, fmt_double(r.ke01), fmt_double(r.ke05), fmt_double(r.sp01),
                            fmt_double(r.sp05), fmt_double(r.cpu), fmt_double(err)));
    }
    csv.close();
    std::printf("reference: elastic energy the step before the first break %.4g J; last break %.4f s\n", f.elastic_at_break,
                f.last_break);
    std::printf("best-matching alpha: %g (mean relative energy error %.3g)\n", best_alpha, best);
    return 0;
}
