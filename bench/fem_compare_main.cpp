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
// --scene plate | bunny | corpus: a dropped object against bench/fem_scene.h on the model's own
//   tets (the plate, which has none: Kuhn tets, --cells across a cube, and a second reference one
//   cell coarser, its row after the reference's; the others: prescore's, --refine 1:8
//   subdivisions). plate: assets/plate.toml; bunny: assets/bunny_sphere.toml (the
//   hollow bunny onto a sphere); corpus: the default shot of `shatter run` on glmark2's
//   asteroid-low.3ds with 4 pieces. Young's modulus is the shot's stiffness (N/m^3) times the
//   length it stands for (the plate's cube side; a prescored model's mean tet edge) unless
//   --young is given; Poisson's ratio 0.2 (--poisson). Writes fem_SCENE.csv into --out.
//
// --check: no reference run; the rigid rows only, scored against the committed comparison
//   (bench/results/study/fem_SCENE.csv and .md): exits 1 unless the best-matching alpha is the
//   committed one and its error within 10% of it (ctest Continuum.BestAlpha.*).
//
//   fem_compare [--scene beam|chain|plate|bunny|corpus] [--cells N] [--refine N] [--step H]
//               [--step-after H2] [--after S] [--young E] [--poisson NU] [--set KEY=VALUE] [--out DIR]
//               [--check]
//   (beam: 4 cells across, h = 2e-4 s; chain: 2 cells across, h = 2.5e-6 s, h2 = 2.5e-5 s, 0.5 s:
//   at h = 1e-5 s one end joint lets go, at 5e-6 s and 2.5e-6 s both, docs/accuracy.md section 8.2;
//   plate: 3 cells, h = 1e-5 s, h2 = 1e-4 s; bunny and corpus: h = h2 = 1e-4 s)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "bench/fem_beam.h"
#include "bench/fem_chain.h"
#include "bench/fem_scene.h"
#include "bench/study.h"
#include "core/fragments.h"
#include "core/shot.h"
#include "prescore/prescore.h"

using namespace shatter;
using namespace shatter::study;

namespace {

using PairList = std::vector<std::pair<uint32_t, uint32_t>>;

// One row of a comparison: a rigid run at one alpha, or the reference (alpha NaN).
struct Row {
    std::string method;
    double alpha = NAN, first_break = NAN, ke01 = NAN, ke05 = NAN, sp01 = NAN, sp05 = NAN, cpu = 0;
    size_t broken = 0, total = 0, fragments = 0;
    std::string joints;  // the chain: the joints that broke, in order of breaking, with their times
    PairList separated;  // dropped scenes: the piece pairs whose every constraint / tie broke
};

// How a scene's table is laid out and scored.
struct Table {
    std::string csv_name;
    int break_digits = 4;        // first break's decimals
    bool joints = false;         // the chain's "joints broken" column
    bool pairs = false;          // the dropped scenes' separated pairs and their overlap with the reference's
    size_t pair_count = 0;       // touching pairs
    std::string csv_after = "05";  // the CSV's name for the late instant
    double after = 0.5;          // (unit: s)
    // The energy error is the mean over the four energies of |E - E_ref| / (E_ref + floor).
    double floor = 0;            // (unit: J)
};

double nearest_kinetic(const SimulationResult& r, double t) {
    double best = 1e300, ke = NAN;
    for (const EnergySample& e : r.energy)
        if (std::abs(e.time - t) < best) best = std::abs(e.time - t), ke = e.kinetic;
    return ke;
}

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

// The pairs of pieces every one of whose constraints broke.
PairList separated_pairs(const Model& model, const SimulationResult& sim) {
    std::map<std::pair<uint32_t, uint32_t>, long> left;  // constraints not (yet) broken per pair
    for (const Constraint& c : model.constraints) ++left[{c.piece_a, c.piece_b}];
    for (const BreakRecord& b : sim.breaks) --left[{std::min(b.piece_a, b.piece_b), std::max(b.piece_a, b.piece_b)}];
    PairList out;
    for (const auto& [pair, n] : left)
        if (n <= 0) out.push_back(pair);
    return out;
}

size_t shared_pairs(const PairList& a, const PairList& b) {
    const std::set<std::pair<uint32_t, uint32_t>> sb(b.begin(), b.end());
    size_t n = 0;
    for (const auto& p : a) n += sb.count(p);
    return n;
}

// The energized rigid method on case c at `alpha`: first break, breaks, fragments, and the
// energies of pieces first to last 0.1 s and `after` s after the first break.
Row rigid_row(StudyCase c, double alpha, double after, uint32_t first, uint32_t last, const Table& table) {
    apply_method("energized", c.input);
    c.input.material.alpha = alpha;
    const RunOutcome o = run_timed(c, 1);
    Row r;
    r.method = "rigid";
    r.alpha = alpha;
    r.first_break = first_break(o.sim);
    r.broken = o.sim.breaks.size();
    r.total = c.model.constraints.size();
    r.fragments = fragments(c.model, o.sim);
    r.cpu = o.cpu_seconds;
    if (table.joints)
        for (const BreakRecord& b : o.sim.breaks)
            r.joints += fmt::format("{}{} ({:.4f})", r.joints.empty() ? "" : " ", b.piece_a, b.time);
    if (table.pairs) r.separated = separated_pairs(c.model, o.sim);
    if (std::isfinite(r.first_break)) {
        const Trajectory& t = o.sim.trajectory;
        r.ke01 = nearest_kinetic(o.sim, r.first_break + 0.1);
        r.ke05 = nearest_kinetic(o.sim, r.first_break + after);
        r.sp01 = spread_of(c.model, t, uint32_t(std::lround((r.first_break + 0.1) * t.fps)), first, last);
        r.sp05 = spread_of(c.model, t, uint32_t(std::lround((r.first_break + after) * t.fps)), first, last);
    }
    std::fprintf(stderr, "rigid alpha %g: %.2f s\n", alpha, o.wall_seconds);
    return r;
}

std::vector<Row> rigid_rows(const StudyCase& c, double after, uint32_t first, uint32_t last, const Table& table) {
    std::vector<Row> rows;
    for (double alpha : {0.0, 0.25, 0.5, 0.75, 1.0, 1.5}) rows.push_back(rigid_row(c, alpha, after, first, last, table));
    return rows;
}

Row reference_row(const std::string& method, double first_break, size_t broken, size_t ties, size_t fragments,
                  const fem::PieceMotion& at01, const fem::PieceMotion& at05, double cpu) {
    Row r;
    r.method = method;
    r.first_break = first_break;
    r.broken = broken;
    r.total = ties;
    r.fragments = fragments;
    r.ke01 = at01.rigid;
    r.ke05 = at05.rigid;
    r.sp01 = at01.spread;
    r.sp05 = at05.spread;
    r.cpu = cpu;
    return r;
}

// The mean over the four energies of |E - E_ref| / (E_ref + floor).
double energy_error(const Row& r, const Row& ref, double floor) {
    const auto rel = [&](double x, double e) { return std::abs(x - e) / (e + floor); };
    return (rel(r.ke01, ref.ke01) + rel(r.ke05, ref.ke05) + rel(r.sp01, ref.sp01) + rel(r.sp05, ref.sp05)) / 4;
}

// --check: the committed comparison of a scene (bench/results/study/fem_SCENE.csv and .md, made by
// `make study`) read back: its reference's energies, the error's floor, the reference's start
// (dropped scenes), and the best-matching alpha and error of its rigid rows. The rigid rows are
// then run again (seconds) and scored against the committed reference, which is not (minutes).
struct Committed {
    Row reference;
    double floor = 0, start = 0, best_alpha = NAN, best_error = NAN;
};

Committed read_committed(const std::string& scene) {
    const std::string base = std::string(SHATTER_SOURCE_DIR) + "/bench/results/study/fem_" + scene;
    Committed c;
    std::ifstream csv(base + ".csv");
    std::string line;
    std::getline(csv, line);
    std::vector<std::string> header;
    for (std::stringstream h(line); std::getline(h, line, ',');) header.push_back(line);
    const auto column = [&](const std::string& name) {
        return size_t(std::find(header.begin(), header.end(), name) - header.begin());
    };
    const std::string late = column("kinetic_05_J") < header.size() ? "05" : "after";  // the chain's: "after"
    bool have_reference = false;
    for (std::string row; std::getline(csv, row);) {
        std::vector<std::string> f;
        for (std::stringstream cells(row); std::getline(cells, line, ',');) f.push_back(line);
        if (f.size() < header.size()) continue;
        const auto num = [&](const std::string& name) { return std::atof(f[column(name)].c_str()); };
        if (f[0] == "rigid") {
            const double err = num("energy_error");
            if (!(err >= c.best_error)) c.best_error = err, c.best_alpha = num("alpha");
        } else if (!have_reference && f[0].rfind("fem", 0) == 0) {
            have_reference = true;
            c.reference.ke01 = num("kinetic_01_J");
            c.reference.ke05 = num("kinetic_" + late + "_J");
            c.reference.sp01 = num("spread_01_J");
            c.reference.sp05 = num("spread_" + late + "_J");
        }
    }
    std::ifstream md(base + ".md");
    for (std::string l; std::getline(md, l);) {
        if (const size_t at = l.find("run from "); l.rfind("reference:", 0) == 0 && at != std::string::npos)
            c.start = std::atof(l.c_str() + at + 9);
        if (const size_t at = l.find("(E_ref + "); l.rfind("best-matching", 0) == 0 && at != std::string::npos)
            c.floor = std::atof(l.c_str() + at + 9);
    }
    if (!have_reference || std::isnan(c.best_alpha)) {
        std::fprintf(stderr, "fem_compare: %s.csv has no reference or no rigid row (fix: make study)\n", base.c_str());
        std::exit(2);
    }
    return c;
}

// The rigid rows run again against the committed reference: the same best-matching alpha, and
// its error within 10% of the committed one. Prints both; 0 when they agree, 1 when not.
int check_rows(const std::string& scene, const std::vector<Row>& rows, const Committed& c) {
    double best = 1e300, best_alpha = NAN;
    for (const Row& r : rows) {
        const double err = energy_error(r, c.reference, c.floor);
        std::printf("%s rigid alpha %g: first break %.5f s, %zu breaks, %zu fragments, energy error %.4g\n", scene.c_str(),
                    r.alpha, r.first_break, r.broken, r.fragments, err);
        if (err < best) best = err, best_alpha = r.alpha;
    }
    const bool same = best_alpha == c.best_alpha && std::abs(best - c.best_error) <= 0.1 * c.best_error;
    std::printf("%s %s: best-matching alpha %g (error %.4g); committed %g (%.4g)\n", same ? "ok  " : "FAIL", scene.c_str(),
                best_alpha, best, c.best_alpha, c.best_error);
    return same ? 0 : 1;
}

// Prints the markdown table and writes the CSV of the rigid rows and the reference (the last
// row), then of `coarser` references (their error against the reference: the mesh's own);
// returns the best-matching alpha and its error.
std::pair<double, double> report(std::vector<Row> rows, const Table& t, const std::string& out,
                                 const std::vector<Row>& coarser = {}) {
    const Row ref = rows.back();
    rows.insert(rows.end(), coarser.begin(), coarser.end());
    std::string header = "method,alpha,first_break_s,broken,of,";
    if (t.joints) header += "joints,";
    if (t.pairs) header += "separated_pairs,of_pairs,shared_with_reference,";
    header += fmt::format("fragments,kinetic_01_J,kinetic_{0}_J,spread_01_J,spread_{0}_J,cpu_s,energy_error", t.csv_after);
    Csv csv(out, t.csv_name, header);
    std::string md = "| method | alpha | first break (s) | broken |", rule = "| --- | --- | --- | --- |";
    if (t.joints) md += " joints broken (s) |", rule += " --- |";
    if (t.pairs) md += " separated pairs (shared with the reference) |", rule += " --- |";
    md += fmt::format(" fragments | KE +0.1 s (J) | KE +{0:g} s (J) | spread +0.1 s (J) | spread +{0:g} s (J) | CPU (s) | "
                      "energy error |",
                      t.after);
    rule += " --- | --- | --- | --- | --- | --- | --- |";
    std::printf("%s\n%s\n", md.c_str(), rule.c_str());
    double best = 1e300, best_alpha = NAN;
    for (const Row& r : rows) {
        const double err = energy_error(r, ref, t.floor);
        if (r.method == "rigid" && err < best) best = err, best_alpha = r.alpha;
        const std::string alpha = std::isnan(r.alpha) ? "-" : fmt::format("{:g}", r.alpha);
        std::string line = fmt::format("| {} | {} | {:.{}f} | {} of {} |", r.method, alpha, r.first_break, t.break_digits,
                                       r.broken, r.total);
        std::string method = r.method;  // no commas in a CSV field
        std::replace(method.begin(), method.end(), ',', ';');
        std::string row = fmt::format("{},{},{},{},{},", method, fmt_double(r.alpha), fmt_double(r.first_break), r.broken,
                                      r.total);
        if (t.joints) line += fmt::format(" {} |", r.joints), row += r.joints + ",";
        if (t.pairs) {
            const size_t shared = shared_pairs(r.separated, ref.separated);
            line += fmt::format(" {} of {} ({}) |", r.separated.size(), t.pair_count, shared);
            row += fmt::format("{},{},{},", r.separated.size(), t.pair_count, shared);
        }
        line += fmt::format(" {} | {:.4g} | {:.4g} | {:.4g} | {:.4g} | {:.2f} | {:.3g} |", r.fragments, r.ke01, r.ke05, r.sp01,
                            r.sp05, r.cpu, err);
        row += fmt::format("{},{},{},{},{},{},{}", r.fragments, fmt_double(r.ke01), fmt_double(r.ke05), fmt_double(r.sp01),
                           fmt_double(r.sp05), fmt_double(r.cpu), fmt_double(err));
        std::printf("%s\n", line.c_str());
        csv.row(row);
    }
    csv.close();
    return {best_alpha, best};
}

int compare_beam(uint32_t cells, double h, const std::string& out, bool check) {
    Table t;
    t.csv_name = "fem_beam.csv";
    StudyCase c = beam_case();
    c.input.simulate.duration = 0.9;
    std::vector<Row> rows = rigid_rows(c, 0.5, 0, uint32_t(c.model.pieces.size()) - 1, t);
    if (check) return check_rows("beam", rows, read_committed("beam"));
    const std::clock_t c0 = std::clock();
    const fem::FemBeamResult f = fem::run_fem_beam(cells, h);
    rows.push_back(reference_row(fmt::format("fem {} cells, h {:g}", cells, h), f.first_break, f.broken, f.ties, f.fragments,
                                 f.at_01, f.at_05, double(std::clock() - c0) / CLOCKS_PER_SEC));
    std::fprintf(stderr, "fem: %.1f s, %ld steps (%ld halved, %ld unconverged), %zu tets\n", f.seconds, f.steps,
                 f.halved_steps, f.unconverged_steps, f.tets);
    const auto [best_alpha, best] = report(rows, t, out);
    std::printf("reference: elastic energy the step before the first break %.4g J; last break %.4f s\n", f.elastic_at_break,
                f.last_break);
    std::printf("best-matching alpha: %g (mean relative energy error %.3g)\n", best_alpha, best);
    return 0;
}

int compare_chain(uint32_t cells, double h, double h_after, double after, const std::vector<std::string>& sets,
                  const std::string& out, bool check) {
    Table t;
    t.csv_name = "fem_chain.csv";
    t.break_digits = 5;
    t.joints = true;
    t.csv_after = "after";
    t.after = after;
    std::vector<std::string> overrides = sets;
    overrides.push_back("simulate.duration=" + fmt::format("{:g}", 0.31 + after + 0.05));
    const Shot shot = load_shot(std::string(SHATTER_SOURCE_DIR) + "/assets/chain.toml", overrides);
    StudyCase c;
    c.scene = "chain";
    c.model = prescore_shot(shot, nullptr);
    c.input = SimulationInput{shot.scene, shot.object, shot.material, shot.simulate};
    const Model& model = c.model;
    // The links' kinetic energy when they move with a driven end: the scale below which a difference
    // is no difference (the reference's spread is ~0 when all links hang on one end).
    double links_mass = 0;
    for (size_t p = 1; p + 1 < model.pieces.size(); ++p) links_mass += model.pieces[p].mass.mass;
    t.floor = 0.5 * links_mass * std::pow(0.03 / 2.7, 2);
    std::vector<Row> rows = rigid_rows(c, after, 1, uint32_t(model.pieces.size()) - 2, t);
    if (check) {
        Committed committed = read_committed("chain");
        committed.floor = t.floor;
        return check_rows("chain", rows, committed);
    }
    const std::clock_t c0 = std::clock();
    const fem::FemChainResult f = fem::run_fem_chain(cells, h, h_after, after);
    Row ref = reference_row(fmt::format("fem {} cells, h {:g} / {:g}", cells, h, h_after), f.first_break, f.broken, f.ties,
                            f.fragments, f.at_01, f.at_05, double(std::clock() - c0) / CLOCKS_PER_SEC);
    for (size_t j = 0; j < f.joints_broken.size(); ++j)
        ref.joints += fmt::format("{}{} ({:.4f})", j ? " " : "", f.joints_broken[j], f.joint_break_time[size_t(f.joints_broken[j])]);
    rows.push_back(ref);
    std::fprintf(stderr, "fem: %.1f s, %ld steps (%ld halved, %ld unconverged), %zu tets, %zu ties\n", f.seconds, f.steps,
                 f.halved_steps, f.unconverged_steps, f.tets, f.ties);
    const auto [best_alpha, best] = report(rows, t, out);
    std::printf("reference: first joint separated at %.5f s (%+.2f ms from the quasi-static prediction)\n",
                f.first_separation, 1e3 * (f.first_separation - f.predicted_break));
    std::printf("reference: predicted first break (quasi-static) %.5f s, first tie %.5f s (%+.2f ms); links' elastic "
                "energy the step before %.4g J; middle joint's force then %.1f N, quasi-static %.1f N (ratio %.4f); last "
                "break %.5f s\n",
                f.predicted_break, f.first_break, 1e3 * (f.first_break - f.predicted_break), f.elastic_at_break,
                f.middle_force_at_break, f.middle_force_predicted, f.middle_force_at_break / f.middle_force_predicted,
                f.last_break);
    std::printf("best-matching alpha: %g (mean of |E - E_ref| / (E_ref + %.3g J) over the four energies: %.3g)\n",
                best_alpha, t.floor, best);
    return 0;
}

struct SceneArgs {
    uint32_t cells = 3, refine = 0;
    double h = 0, h_after = 0, after = 0.5, young = 0, poisson = 0.2;
    std::vector<std::string> sets;
    bool check = false;
};

// A dropped object (plate, bunny, corpus) against bench/fem_scene.h.
int compare_dropped(const std::string& scene, const SceneArgs& a, const std::string& out) {
    std::vector<std::string> overrides = a.sets;
    Shot shot;
    if (scene == "plate") {
        shot = load_shot(std::string(SHATTER_SOURCE_DIR) + "/assets/plate.toml", overrides);
    } else if (scene == "bunny") {
        shot = load_shot(std::string(SHATTER_SOURCE_DIR) + "/assets/bunny_sphere.toml", overrides);
    } else {
        overrides.insert(overrides.begin(), "prescore.pieces=4");
        // The committed reference was made with pieces of about one size (the default shot's seeds
        // are now "impact"; with them the error moved from 0.87 to 0.78 at the same best alpha).
        overrides.insert(overrides.begin() + 1, "prescore.seeds=uniform");
        // ... and at the fixed step of 1/480 s the default shot then had (its errors at every alpha
        // lie within 0.82 to 0.87, so the automatic step moves the best alpha from 1.5 to 0).
        overrides.insert(overrides.begin() + 2, "simulate.substeps=16");
        shot = default_shot_for_mesh("/usr/share/glmark2/models/asteroid-low.3ds", overrides);
    }
    StudyCase c;
    c.scene = scene;
    c.model = prescore_shot(shot, nullptr);
    c.input = SimulationInput{shot.scene, shot.object, shot.material, shot.simulate};
    const Model& model = c.model;

    fem::FemSceneSettings fs = fem::scene_settings(model, shot.material, a.poisson);
    const double l = fem::stiffness_length(model);
    if (a.young > 0) fs.material.young = a.young;
    fs.box_cells = a.cells;
    fs.refine = a.refine;
    if (a.h > 0) fs.h = a.h;
    if (a.h_after > 0) fs.h_after = a.h_after;
    fs.after = a.after;
    fs.progress = true;
    std::fprintf(stderr, "%s: %zu pieces, %zu tets, %zu constraints; E = %.4g Pa (stiffness %.4g N/m^3 x %.4g m), nu %g, "
                 "rho %g, strength %.4g Pa\n",
                 scene.c_str(), model.pieces.size(), model.mesh.tets.size(), model.constraints.size(), fs.material.young,
                 shot.material.stiffness, l, fs.material.poisson, fs.material.density, fs.strength.tensile);
    if (a.check) {
        const Committed committed = read_committed(scene);
        Table t;
        c.input.simulate.auto_duration = false;
        c.input.simulate.duration = committed.start + 0.3 + a.after;
        return check_rows(scene, rigid_rows(c, a.after, 0, uint32_t(model.pieces.size()) - 1, t), committed);
    }
    const auto run = [&](const fem::FemSceneSettings& settings, const std::string& what, fem::FemSceneResult& f) {
        const std::clock_t c0 = std::clock();
        f = fem::run_fem_scene(model, shot.scene, shot.object, settings);
        const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
        std::fprintf(stderr, "fem: %.1f s, %ld steps (%ld halved, %ld unconverged), %zu tets, %zu ties, start %.4f s\n",
                     f.seconds, f.steps, f.halved_steps, f.unconverged_steps, f.tets, f.ties, f.start_time);
        Row r = reference_row(fmt::format("fem {}, h {:g} / {:g}", what, settings.h, settings.h_after), f.first_break,
                              f.broken, f.ties, f.fragments, f.at_01, f.at_05, cpu);
        r.separated = f.separated;
        return r;
    };
    const std::string what = model.mesh.tets.empty() ? fmt::format("{} cells", a.cells)
                                                     : a.refine ? fmt::format("prescore's tets / {}", 1 << (3 * a.refine))
                                                                : std::string("prescore's tets");
    fem::FemSceneResult f;
    const Row ref = run(fs, what, f);
    // A box model's reference also one cell coarser across a box: how far the mesh moves it.
    std::vector<Row> coarser;
    if (model.mesh.tets.empty() && a.cells > 1) {
        fem::FemSceneSettings c1 = fs;
        c1.box_cells = a.cells - 1;
        fem::FemSceneResult f1;
        coarser.push_back(run(c1, fmt::format("{} cells", c1.box_cells), f1));
    }

    Table t;
    t.csv_name = "fem_" + scene + ".csv";
    t.pairs = true;
    t.pair_count = f.pairs.size();
    t.after = a.after;
    // 1% of the free fall's kinetic energy at impact: below it, energies count as equal.
    t.floor = 0.01 * f.impact_energy;
    // The rigid runs to 0.3 s past the reference's first contact plus `after` (the first breaks
    // come within milliseconds of the impact).
    c.input.simulate.auto_duration = false;
    c.input.simulate.duration = f.start_time + 0.3 + a.after;
    std::vector<Row> rows = rigid_rows(c, a.after, 0, uint32_t(model.pieces.size()) - 1, t);
    rows.push_back(ref);
    const auto [best_alpha, best] = report(rows, t, out, coarser);
    std::printf("reference: %zu tets, %zu ties over %zu touching pairs; run from %.4f s (free fall), %ld steps (%ld halved, "
                "%ld unconverged); elastic energy the step before the first break %.4g J; last break %.4f s; impact "
                "energy %.4g J; complete %d\n",
                f.tets, f.ties, f.pairs.size(), f.start_time, f.steps, f.halved_steps, f.unconverged_steps,
                f.elastic_at_break, f.last_break, f.impact_energy, int(f.complete));
    std::printf("best-matching alpha: %g (mean of |E - E_ref| / (E_ref + %.3g J) over the four energies: %.3g)\n",
                best_alpha, t.floor, best);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    spdlog::set_level(spdlog::level::err);  // the rigid runs' warnings would go into the printed tables
    SceneArgs a;
    uint32_t cells = 0;
    std::string out = "bench/results/study", scene = "beam";
    bool check = false;
    for (int i = 1; i < argc; ++i)
        if (std::string(argv[i]) == "--check") check = a.check = true;
    for (int i = 1; i + 1 < argc; ++i) {
        const std::string k = argv[i];
        if (k == "--cells") cells = uint32_t(std::atoi(argv[++i]));
        else if (k == "--refine") a.refine = uint32_t(std::atoi(argv[++i]));
        else if (k == "--step") a.h = std::atof(argv[++i]);
        else if (k == "--step-after") a.h_after = std::atof(argv[++i]);
        else if (k == "--after") a.after = std::atof(argv[++i]);
        else if (k == "--young") a.young = std::atof(argv[++i]);
        else if (k == "--poisson") a.poisson = std::atof(argv[++i]);
        else if (k == "--scene") scene = argv[++i];
        else if (k == "--set") a.sets.push_back(argv[++i]);
        else if (k == "--out") out = argv[++i];
    }
    if (scene == "beam") return compare_beam(cells ? cells : 4, a.h > 0 ? a.h : 2e-4, out, check);
    if (scene == "chain")
        return compare_chain(cells ? cells : 2, a.h > 0 ? a.h : 2.5e-6, a.h_after > 0 ? a.h_after : 2.5e-5, a.after, a.sets,
                             out, check);
    if (scene == "plate" || scene == "bunny" || scene == "corpus") {
        if (cells) a.cells = cells;
        return compare_dropped(scene, a, out);
    }
    std::fprintf(stderr, "fem_compare: unknown scene '%s' (beam, chain, plate, bunny, corpus)\n", scene.c_str());
    return 2;
}
