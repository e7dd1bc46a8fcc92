// fem_compare: the rigid method against the continuum reference (docs/accuracy.md section 8):
// first break, ties / constraints broken, fragments, and the pieces' kinetic energy and its
// spread about their common centre 0.1 s and 0.5 s after the first break, for the energized rigid
// method at alpha 0 to 1.5 and for the reference; the alpha that matches the reference best; the
// cost of each.
//
// --scene beam (default): the study's beam (bench/study_scenes.cpp's beam_case, the study's
//   defaults) against bench/fem_beam.h. Writes fem_beam.csv into --out.
// --scene chain: assets/chain.toml as shipped (70 GPa, 40 MPa, 1,000 substeps; --set overrides
//   it, e.g. simulate.joints=direct) against bench/fem_chain.h, the reference from 0.3 s (the ends
//   start to move) with steps of H to 10 ms after its first break and of H2 from then on; the
//   energies are the ten links' (the driven end cubes left out). Writes fem_chain.csv into --out.
//
//   fem_compare [--scene beam|chain] [--cells N] [--step H] [--step-after H2] [--after S] [--set KEY=VALUE]
//               [--out DIR]
//   (beam: 4 cells across, h = 2e-4 s; chain: 2 cells across, h = 2.5e-6 s, h2 = 2.5e-5 s, 0.5 s:
//   at h = 1e-5 s one end joint lets go, at 5e-6 s and 2.5e-6 s both, docs/accuracy.md section 8.2)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "bench/fem_beam.h"
#include "bench/fem_chain.h"
#include "bench/study.h"
#include "core/fragments.h"
#include "core/shot.h"
#include "prescore/prescore.h"

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

// The translational kinetic energy of pieces first to last about their common centre at frame f
// (core/fragments.h's spread_energy over a range of pieces).
double spread_of(const Model& model, const Trajectory& t, uint32_t f, uint32_t first, uint32_t last) {
    if (t.frames() < 3) return 0;
    f = std::clamp<uint32_t>(f, 1, t.frames() - 2);
    double mass = 0;
    Vec3 momentum = Vec3::Zero();
    std::vector<Vec3> v(t.pieces);
    for (uint32_t b = first; b <= last; ++b) {
        v[b] = (t.pose(f + 1, b).position - t.pose(f - 1, b).position).cast<double>() * (t.fps / 2);
        mass += model.pieces[b].mass.mass;
        momentum += model.pieces[b].mass.mass * v[b];
    }
    const Vec3 v_cm = momentum / mass;
    double e = 0;
    for (uint32_t b = first; b <= last; ++b) e += 0.5 * model.pieces[b].mass.mass * (v[b] - v_cm).squaredNorm();
    return e;
}

struct ChainRow {
    std::string method;
    double alpha = NAN, first_break = NAN, ke01 = NAN, ke05 = NAN, sp01 = NAN, sp05 = NAN, cpu = 0;
    size_t broken = 0, total = 0, fragments = 0;
    std::string joints;  // the joints that broke, in order of breaking, with their times
};

int compare_chain(uint32_t cells, double h, double h_after, double after, const std::vector<std::string>& sets,
                  const std::string& out) {
    std::vector<ChainRow> rows;
    const std::string path = std::string(SHATTER_SOURCE_DIR) + "/assets/chain.toml";
    Model model;
    for (double alpha : {0.0, 0.25, 0.5, 0.75, 1.0, 1.5}) {
        std::vector<std::string> overrides = sets;
        overrides.push_back("simulate.duration=" + fmt::format("{:g}", 0.31 + after + 0.05));
        const Shot shot = load_shot(path, overrides);
        StudyCase c;
        c.scene = "chain";
        if (model.pieces.empty()) model = prescore_shot(shot, nullptr);
        c.model = model;
        c.input = SimulationInput{shot.scene, shot.object, shot.material, shot.simulate};
        apply_method("energized", c.input);
        c.input.material.alpha = alpha;
        const RunOutcome o = run_timed(c, 1);
        ChainRow r;
        r.method = "rigid";
        r.alpha = alpha;
        r.first_break = first_break(o.sim);
        r.broken = o.sim.breaks.size();
        r.total = c.model.constraints.size();
        r.fragments = fragments(c.model, o.sim);
        r.cpu = o.cpu_seconds;
        for (const BreakRecord& b : o.sim.breaks)
            r.joints += fmt::format("{}{} ({:.4f})", r.joints.empty() ? "" : " ", b.piece_a, b.time);
        if (std::isfinite(r.first_break)) {
            const Trajectory& t = o.sim.trajectory;
            const uint32_t last = uint32_t(c.model.pieces.size()) - 2;
            r.ke01 = nearest_kinetic(o.sim, r.first_break + 0.1);
            r.ke05 = nearest_kinetic(o.sim, r.first_break + after);
            r.sp01 = spread_of(c.model, t, uint32_t(std::lround((r.first_break + 0.1) * t.fps)), 1, last);
            r.sp05 = spread_of(c.model, t, uint32_t(std::lround((r.first_break + after) * t.fps)), 1, last);
        }
        rows.push_back(r);
        std::fprintf(stderr, "rigid alpha %g: %.2f s\n", alpha, o.wall_seconds);
    }
    const std::clock_t c0 = std::clock();
    const fem::FemChainResult f = fem::run_fem_chain(cells, h, h_after, after);
    ChainRow ref;
    ref.method = fmt::format("fem {} cells, h {:g} / {:g}", cells, h, h_after);
    ref.first_break = f.first_break;
    ref.broken = f.broken;
    ref.total = f.ties;
    ref.fragments = f.fragments;
    ref.ke01 = f.at_01.rigid;
    ref.ke05 = f.at_05.rigid;
    ref.sp01 = f.at_01.spread;
    ref.sp05 = f.at_05.spread;
    ref.cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    for (size_t j = 0; j < f.joints_broken.size(); ++j)
        ref.joints += fmt::format("{}{} ({:.4f})", j ? " " : "", f.joints_broken[j], f.joint_break_time[size_t(f.joints_broken[j])]);
    std::fprintf(stderr, "fem: %.1f s, %ld steps (%ld halved, %ld unconverged), %zu tets, %zu ties\n", f.seconds, f.steps,
                 f.halved_steps, f.unconverged_steps, f.tets, f.ties);
    Csv csv(out, "fem_chain.csv",
            "method,alpha,first_break_s,broken,of,joints,fragments,kinetic_01_J,kinetic_after_J,spread_01_J,spread_after_J,"
            "cpu_s,energy_error");
    std::printf("| method | alpha | first break (s) | broken | joints broken (s) | fragments | KE +0.1 s (J) | KE +%g s (J) | spread +0.1 s (J) | spread +%g s (J) | CPU (s) | energy error |\n",
                after, after);
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
    double best = 1e300, best_alpha = NAN;
    rows.push_back(ref);
    // The links' kinetic energy when they move with a driven end: the scale below which a difference
    // is no difference (the reference's spread is ~0 when all links hang on one end).
    double links_mass = 0;
    for (size_t p = 1; p + 1 < model.pieces.size(); ++p) links_mass += model.pieces[p].mass.mass;
    const double floor = 0.5 * links_mass * std::pow(0.03 / 2.7, 2);
    const auto relf = [&](double x, double r) { return std::abs(x - r) / (r + floor); };
    for (const ChainRow& r : rows) {
        const double err = (relf(r.ke01, ref.ke01) + relf(r.ke05, ref.ke05) + relf(r.sp01, ref.sp01) + relf(r.sp05, ref.sp05)) / 4;
        if (r.method == "rigid" && err < best) best = err, best_alpha = r.alpha;
        std::printf("| %s | %s | %.5f | %zu of %zu | %s | %zu | %.4g | %.4g | %.4g | %.4g | %.2f | %.3g |\n", r.method.c_str(),
                    std::isnan(r.alpha) ? "-" : fmt::format("{:g}", r.alpha).c_str(), r.first_break, r.broken, r.total,
                    r.joints.c_str(), r.fragments, r.ke01, r.ke05, r.sp01, r.sp05, r.cpu, err);
        csv.row(fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}", r.method, fmt_double(r.alpha), fmt_double(r.first_break),
                            r.broken, r.total, r.joints, r.fragments, fmt_double(r.ke01), fmt_double(r.ke05),
                            fmt_double(r.sp01), fmt_double(r.sp05), fmt_double(r.cpu), fmt_double(err)));
    }
    csv.close();
    std::printf("reference: first joint separated at %.5f s (%+.2f ms from the quasi-static prediction)\n",
                f.first_separation, 1e3 * (f.first_separation - f.predicted_break));
    std::printf("reference: predicted first break (quasi-static) %.5f s, first tie %.5f s (%+.2f ms); links' elastic "
                "energy the step before %.4g J; middle joint's force then %.1f N, quasi-static %.1f N (ratio %.4f); last "
                "break %.5f s\n",
                f.predicted_break, f.first_break, 1e3 * (f.first_break - f.predicted_break), f.elastic_at_break,
                f.middle_force_at_break, f.middle_force_predicted, f.middle_force_at_break / f.middle_force_predicted,
                f.last_break);
    std::printf("best-matching alpha: %g (mean of |E - E_ref| / (E_ref + %.3g J) over the four energies: %.3g)\n",
                best_alpha, floor, best);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    spdlog::set_level(spdlog::level::warn);
    uint32_t cells = 0;
    double h = 0, h_after = 0, after = 0.5;
    std::string out = "bench/results/study", scene = "beam";
    std::vector<std::string> sets;  // the chain's rigid runs: overrides of assets/chain.toml
    for (int i = 1; i + 1 < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--cells") cells = uint32_t(std::atoi(argv[++i]));
        else if (a == "--step") h = std::atof(argv[++i]);
        else if (a == "--step-after") h_after = std::atof(argv[++i]);
        else if (a == "--after") after = std::atof(argv[++i]);
        else if (a == "--scene") scene = argv[++i];
        else if (a == "--set") sets.push_back(argv[++i]);
        else if (a == "--out") out = argv[++i];
    }
    if (scene == "chain")
        return compare_chain(cells ? cells : 2, h > 0 ? h : 2.5e-6, h_after > 0 ? h_after : 2.5e-5, after, sets, out);
    if (!cells) cells = 4;
    if (!(h > 0)) h = 2e-4;
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
    std::fprintf(stderr, "fem: %.1f s, %ld steps (%ld halved, %ld unconverged), %zu tets\n",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), f.steps, f.halved_steps,
                 f.unconverged_steps, f.tets);

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
