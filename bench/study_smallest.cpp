// The smallest model that serves (issue 7, point 7; docs/accuracy.md section 7).
//
// Unlike the other sections, this one reads the shipped shots (assets/<shot>.toml): its question
// is whether their model-size settings can be made smaller. Per shot, with the compared window
// set as [simulate] duration:
//   1. the reference: every model-size knob at its finest value (the finest the CFM guard admits);
//   2. for an impact (a chaotic scene), the reference again with the drop height nudged by
//      -1, -0.5, +0.5, +1 mm: how far the finest model is from itself sets the tolerance;
//   3. one knob at a time down from the finest, the others at their finest;
//   4. per knob, the coarsest value that passes together with every finer value; then all
//      knobs at their chosen values together (if that fails, the knob furthest off is moved one
//      value finer, again and again);
//   5. the shot as shipped.
// Writes smallest.csv (every run) and smallest_summary.csv (per shot: tolerances and choices).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>

#include <spdlog/spdlog.h>

#include "bench/study_sections.h"
#include "core/error.h"
#include "core/shot.h"
#include "prescore/prescore.h"

namespace shatter::study {

namespace {

std::string d(double v) { return fmt_double(v); }
const double kInf = std::numeric_limits<double>::infinity();

struct KnobSpec {
    std::string name;            // for the CSV and the charts
    std::string key;             // the shot key, SECTION.KEY
    std::vector<double> values;  // coarse to fine; the last is the finest
    // false: not a resolution of the same physics (the outcome changes in kind): swept at every
    // value around the shot's own, which the reference keeps, and never chosen.
    bool choose = true;
};

enum class Measure { Trajectory, Statistics };

struct ShotSpec {
    std::string shot;   // assets/<shot>.toml
    double window;      // (unit: s) the simulated time compared; set as [simulate] duration
    Measure measure;
    std::vector<KnobSpec> knobs;
    // The trajectory is compared up to the reference's first break plus this (unit: s); after it,
    // the chain's recoil follows a kick direction that numerical noise picks (a pull along the
    // axis has tau x f ~ 0; docs/physics.md), so it is not comparable frame by frame.
    double compare_after_break = kInf;
};

// The bunny's knobs (both shots). The resolution re-draws the pieces (new tets, new seed tets for
// the partition): another set of fragments, not a finer version of the same ones, so it is swept
// around the shot's and not chosen. 16 substeps at resolution 30 is refused by the CFM guard.
std::vector<KnobSpec> bunny_knobs() {
    return {{"resolution", "prescore.resolution", {10, 15, 20, 30}, false},
            {"constraints_per_pair", "prescore.constraints_per_pair", {4, 8, 16, 32, 0}},  // 0: all
            {"collision_parts", "prescore.collision_max_parts", {1, 2, 4, 8, 16, 32}},
            {"substeps", "simulate.substeps", {2, 4, 8, 16}}};
}

std::vector<ShotSpec> shot_specs() {
    return {
        {"beam", 0.8, Measure::Trajectory,
         {{"constraints_per_side", "generate.constraints_per_side", {1, 2, 3, 4}, false},
          {"substeps", "simulate.substeps", {1, 2, 4, 8, 16, 32}}}},
        // constraints_per_side is the chain's joint type (1: a ball joint), not a resolution.
        {"chain", 0.6, Measure::Trajectory, {{"substeps", "simulate.substeps", {250, 500, 1000, 2000, 4000}}}, 0},
        // 3 x 3 per face at more than ~1,100 substeps is refused by the CFM guard.
        {"plate", 0.6, Measure::Statistics,
         {{"constraints_per_side", "generate.constraints_per_side", {1, 2, 3}},
          {"substeps", "simulate.substeps", {125, 250, 500, 1000}}}},
        {"bunny", 4.0, Measure::Statistics, bunny_knobs()},
        {"bunny_sphere", 2.0, Measure::Statistics, bunny_knobs()},
    };
}

double shot_value(const Shot& s, const std::string& key) {
    if (key == "generate.constraints_per_side") return s.generate ? s.generate->constraints_per_side : NAN;
    if (key == "prescore.resolution") return s.prescore.resolution;
    if (key == "prescore.constraints_per_pair") return s.prescore.constraints_per_pair;
    if (key == "prescore.collision_max_parts") return s.prescore.collision_max_parts;
    if (key == "simulate.substeps") return s.simulate.substeps;
    throw Error(ExitCode::Internal, "study: no shot value for " + key);
}

// What a run is scored by (docs/accuracy.md section 7).
struct Stats {
    size_t breaks = 0, fragments = 0;
    double first_break = NAN;      // (unit: s)
    double broken_fraction = 0;    // breaks / constraints
    double scatter = 0;            // (unit: m) mass-weighted RMS distance of the pieces from their centre, last frame
};

Stats stats_of(const Model& m, const SimulationResult& r) {
    Stats s;
    s.breaks = r.breaks.size();
    s.fragments = fragments(m, r);
    s.first_break = first_break(r);
    s.broken_fraction = m.constraints.empty() ? 0 : double(s.breaks) / double(m.constraints.size());
    const Trajectory& t = r.trajectory;
    if (t.frames() == 0) return s;
    const uint32_t f = t.frames() - 1;
    double mass = 0;
    Vec3 c = Vec3::Zero();
    for (uint32_t p = 0; p < t.pieces; ++p) {
        mass += m.pieces[p].mass.mass;
        c += m.pieces[p].mass.mass * t.pose(f, p).position.cast<double>();
    }
    c /= mass;
    double sum = 0;
    for (uint32_t p = 0; p < t.pieces; ++p)
        sum += m.pieces[p].mass.mass * (t.pose(f, p).position.cast<double>() - c).squaredNorm();
    s.scatter = std::sqrt(sum / mass);
    return s;
}

size_t collision_parts_of(const Model& m) {
    size_t n = 0;
    for (const Piece& p : m.pieces) n += p.collision.size();
    return n;
}

double diagonal_of(const Model& m) {
    Vec3 lo = Vec3::Constant(kInf), hi = -Vec3::Constant(kInf);
    for (const Piece& p : m.pieces)
        for (const Vec3& v : p.surface.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    return (hi - lo).norm();
}

struct Run {
    std::vector<std::string> overrides;
    StudyCase c;
    RunOutcome o;
    Stats s;
};

// Runs a shot with overrides, building each model once (keyed by its [prescore]/[generate] overrides).
class ShotRunner {
public:
    ShotRunner(const std::string& shot, double window)
        : path_(std::string(SHATTER_SOURCE_DIR) + "/assets/" + shot + ".toml"), window_(window),
          base_(load_shot(path_)) {}
    const Shot& base() const { return base_; }

    Run run(std::vector<std::string> overrides) {
        overrides.push_back(fmt::format("simulate.duration={}", window_));
        const Shot shot = load_shot(path_, overrides);
        std::string key;
        for (const std::string& o : overrides)
            if (o.rfind("prescore.", 0) == 0 || o.rfind("generate.", 0) == 0) key += o + ";";
        auto it = models_.find(key);
        if (it == models_.end()) {
            const auto t0 = std::chrono::steady_clock::now();
            Model m = prescore_shot(shot, nullptr);
            const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            it = models_.emplace(key, std::make_pair(std::move(m), s)).first;
        }
        Run r;
        r.overrides = overrides;
        r.c.scene = base_.path;
        r.c.model = it->second.first;
        r.c.prescore_seconds = it->second.second;
        r.c.input = SimulationInput{shot.scene, shot.object, shot.material, shot.simulate};
        r.o = run_case(r.c);
        r.s = stats_of(r.c.model, r.o.sim);
        return r;
    }

private:
    std::string path_;
    double window_;
    Shot base_;
    std::map<std::string, std::pair<Model, double>> models_;
};

struct Tolerance {
    double trajectory = kInf;       // (unit: m) RMS over the window
    double first_break = kInf;      // (unit: s)
    double broken_fraction = kInf;
    double fragments = kInf;
    double scatter_rel = kInf;
    double early = kInf;            // (unit: m) RMS over the 0.1 s after the reference's first break
};

struct Deviation {
    double trajectory = NAN, first_break = NAN, broken_fraction = NAN, fragments = NAN, scatter_rel = NAN, early = NAN;
    double worst = kInf;  // largest deviation / tolerance; <= 1 passes
};

double break_gap(double a, double b) {
    if (std::isnan(a) && std::isnan(b)) return 0;
    if (std::isnan(a) || std::isnan(b)) return kInf;
    return std::abs(a - b);
}

Deviation deviation(const Run& run, const Run& ref, const Tolerance& tol, double after_break = kInf) {
    Deviation dv;
    if (run.o.refused || !run.o.sim.complete) return dv;
    double until = ref.c.input.simulate.duration;
    if (!std::isnan(ref.s.first_break)) until = std::min(until, ref.s.first_break + after_break);
    dv.trajectory = trajectory_rms(run.c.model, run.o.sim.trajectory, ref.c.model, ref.o.sim.trajectory, 0, until);
    const double t0 = std::isnan(ref.s.first_break) ? 0 : ref.s.first_break;
    dv.early = trajectory_rms(run.c.model, run.o.sim.trajectory, ref.c.model, ref.o.sim.trajectory, t0, t0 + 0.1);
    dv.first_break = break_gap(run.s.first_break, ref.s.first_break);
    dv.broken_fraction = std::abs(run.s.broken_fraction - ref.s.broken_fraction);
    dv.fragments = std::abs(double(run.s.fragments) - double(ref.s.fragments));
    dv.scatter_rel = std::abs(run.s.scatter - ref.s.scatter) / std::max(ref.s.scatter, 1e-9);
    dv.worst = 0;
    for (auto [x, t] : {std::pair{dv.trajectory, tol.trajectory}, {dv.first_break, tol.first_break},
                        {dv.broken_fraction, tol.broken_fraction}, {dv.fragments, tol.fragments},
                        {dv.scatter_rel, tol.scatter_rel}, {dv.early, tol.early}})
        if (std::isfinite(t)) dv.worst = std::max(dv.worst, x / t);
    return dv;
}

// The outermost Gauss-Legendre point of n points on [-1, 1].
double outer_gauss(int n) {
    static const double xi[] = {0, 0, 0.57735026918962576, 0.77459666924148338, 0.86113631159405258,
                                0.90617984593866399};
    if (n < 2 || n > 5) throw Error(ExitCode::Internal, "study: no Gauss point table for n = " + std::to_string(n));
    return xi[n];
}

std::string value_text(double v) { return fmt::format("{:g}", v); }

std::vector<std::string> overrides_for(const ShotSpec& spec, const Shot& base, const std::vector<double>& values) {
    std::vector<std::string> o;
    for (size_t k = 0; k < spec.knobs.size(); ++k) {
        o.push_back(spec.knobs[k].key + "=" + value_text(values[k]));
        // The material keeps its Young's modulus: stiffness per area = E / l scales with 1 / tet size.
        if (spec.knobs[k].key == "prescore.resolution")
            o.push_back(fmt::format("material.stiffness={:.17g}",
                                    base.material.stiffness * values[k] / base.prescore.resolution));
        // The beam keeps its modulus of rupture: its strength is the stress at the outermost Gauss
        // point when the outer fibre breaks (assets/beam.toml), so it scales with that point's
        // place, xi_n. n = 1 (xi = 0) cannot carry a moment; it keeps the shot's strength.
        if (spec.shot == "beam" && spec.knobs[k].key == "generate.constraints_per_side" && values[k] > 1)
            o.push_back(fmt::format("material.strength={:.17g}",
                                    base.material.strength * outer_gauss(int(values[k])) /
                                        outer_gauss(int(base.generate->constraints_per_side))));
    }
    return o;
}

std::string join(const std::vector<std::string>& v, const char* sep) {
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "" : sep) + x;
    return s;
}

const char* kRunHeader =
    "shot,role,knob,value,settings,refused,complete,prescore_s,cpu_s,cpu_per_sim_s,wall_per_sim_s,bodies,constraints,"
    "collision_parts,tets,substeps,breaks,first_break_s,fragments,broken_fraction,scatter_m,trajectory_rms_m,"
    "early_rms_m,d_first_break_s,d_broken_fraction,d_fragments,d_scatter_rel,worst_ratio,pass";

std::string run_row(const std::string& shot, const std::string& role, const std::string& knob, const std::string& value,
                    const Run& r, const Deviation& dv) {
    const double w = r.c.input.simulate.duration;
    std::vector<std::string> settings;
    for (const std::string& o : r.overrides)
        if (o.rfind("simulate.duration", 0) != 0) settings.push_back(o);
    return fmt::format("{},{},{},\"{}\",\"{}\",{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}", shot,
                       role, knob, value, join(settings, " "), r.o.refused, r.o.sim.complete, d(r.c.prescore_seconds),
                       d(r.o.cpu_seconds), d(r.o.cpu_seconds / w), d(r.o.wall_seconds / w), r.c.model.pieces.size(),
                       r.c.model.constraints.size(), collision_parts_of(r.c.model), r.c.model.mesh.tets.size(),
                       r.c.input.simulate.substeps, r.s.breaks, d(r.s.first_break), r.s.fragments,
                       d(r.s.broken_fraction), d(r.s.scatter), d(dv.trajectory), d(dv.early), d(dv.first_break),
                       d(dv.broken_fraction), d(dv.fragments), d(dv.scatter_rel), d(dv.worst),
                       dv.worst <= 1 ? 1 : 0);
}

std::string values_text(const ShotSpec& spec, const std::vector<double>& v) {
    std::vector<std::string> s;
    for (size_t k = 0; k < spec.knobs.size(); ++k) s.push_back(spec.knobs[k].name + "=" + value_text(v[k]));
    return join(s, " ");
}

std::string size_text(const Run& r) {
    return fmt::format("{} bodies {} constraints {} collision parts {} tets", r.c.model.pieces.size(),
                       r.c.model.constraints.size(), collision_parts_of(r.c.model), r.c.model.mesh.tets.size());
}

// One shot: reference, tolerance, sweeps, choice, shipped.
void study_shot(const ShotSpec& spec, const Options& opt, Csv& runs, Csv& summary, Headlines& h) {
    spdlog::info("study: smallest {}", spec.shot);
    ShotRunner runner(spec.shot, spec.window);
    const Shot& base = runner.base();
    std::vector<double> finest, shipped;
    for (const KnobSpec& k : spec.knobs) {
        shipped.push_back(shot_value(base, k.key));
        finest.push_back(k.choose ? k.values.back() : shipped.back());
    }

    const Run ref = runner.run(overrides_for(spec, base, finest));
    if (ref.o.refused || !ref.o.sim.complete)
        throw Error(ExitCode::Internal, "study: the finest " + spec.shot + " model does not run: " + ref.o.message +
                                            ref.o.sim.stop_reason);
    const double fps = base.simulate.fps;
    Tolerance tol;
    tol.first_break = 1 / fps;
    const double one_percent = 0.01 * diagonal_of(ref.c.model);
    if (spec.measure == Measure::Trajectory) {
        tol.trajectory = one_percent;
    } else {
        // Floors, widened to how far the finest model lands from itself when dropped 0.5 or 1 mm
        // higher or lower (an invisible change).
        tol.broken_fraction = 0.05, tol.fragments = 1, tol.scatter_rel = 0.1, tol.early = one_percent;
        Tolerance none;
        for (double dy : {-1e-3, -0.5e-3, 0.5e-3, 1e-3}) {
            auto o = overrides_for(spec, base, finest);
            const Vec3 p = base.object.pose.position;
            o.push_back(fmt::format("object.position=[{:.17g}, {:.17g}, {:.17g}]", p.x(), p.y() + dy, p.z()));
            const Run r = runner.run(o);
            const Deviation dv = deviation(r, ref, none);
            runs.row(run_row(spec.shot, "nudged", "drop_height_mm", value_text(dy * 1e3), r, dv));
            if (r.o.refused || !r.o.sim.complete) continue;
            tol.first_break = std::max(tol.first_break, dv.first_break);
            tol.broken_fraction = std::max(tol.broken_fraction, dv.broken_fraction);
            tol.fragments = std::max(tol.fragments, dv.fragments);
            tol.scatter_rel = std::max(tol.scatter_rel, dv.scatter_rel);
            tol.early = std::max(tol.early, dv.early);
        }
    }
    runs.row(run_row(spec.shot, "reference", "-", "-", ref, deviation(ref, ref, tol)));

    // One knob at a time, the others at their finest.
    std::vector<double> chosen = finest;
    std::vector<std::vector<double>> worst(spec.knobs.size());
    if (!opt.quick) {
        for (size_t k = 0; k < spec.knobs.size(); ++k) {
            const KnobSpec& knob = spec.knobs[k];
            for (size_t i = 0; i < knob.values.size(); ++i) {
                if (knob.values[i] == finest[k]) {
                    worst[k].push_back(0);  // the reference
                    continue;
                }
                std::vector<double> v = finest;
                v[k] = knob.values[i];
                const Run r = runner.run(overrides_for(spec, base, v));
                const Deviation dv = deviation(r, ref, tol, spec.compare_after_break);
                worst[k].push_back(dv.worst);
                runs.row(run_row(spec.shot, knob.choose ? "sweep" : "variant", knob.name,
                                 value_text(knob.values[i]), r, dv));
            }
            if (!knob.choose) continue;
            size_t pick = knob.values.size() - 1;
            while (pick > 0 && worst[k][pick - 1] <= 1) --pick;
            chosen[k] = knob.values[pick];
        }
    } else {
        chosen = shipped;  // quick: only the shipped shot against the reference
    }

    // The shot as shipped (its own knob values; the resolution keeps the shot's stiffness).
    const Run ship = runner.run({});
    const Deviation ship_dv = deviation(ship, ref, tol, spec.compare_after_break);
    runs.row(run_row(spec.shot, "shipped", "-", values_text(spec, shipped), ship, ship_dv));

    // All knobs at their chosen values; refine the one furthest off until it passes.
    Run combined = ship;
    Deviation combined_dv = ship_dv;
    for (int attempt = 0; attempt < 8 && !opt.quick; ++attempt) {
        combined = chosen == shipped ? ship : runner.run(overrides_for(spec, base, chosen));
        combined_dv = deviation(combined, ref, tol, spec.compare_after_break);
        runs.row(run_row(spec.shot, "chosen", "-", values_text(spec, chosen), combined, combined_dv));
        if (combined_dv.worst <= 1) break;
        size_t move = spec.knobs.size();
        double far = -1;
        for (size_t k = 0; k < spec.knobs.size(); ++k) {
            const auto& vals = spec.knobs[k].values;
            const size_t i = size_t(std::find(vals.begin(), vals.end(), chosen[k]) - vals.begin());
            if (spec.knobs[k].choose && i + 1 < vals.size() && worst[k][i] > far) far = worst[k][i], move = k;
        }
        if (move == spec.knobs.size()) break;
        const auto& vals = spec.knobs[move].values;
        chosen[move] = *(std::find(vals.begin(), vals.end(), chosen[move]) + 1);
    }

    summary.row(fmt::format(
        "{},{},{},{},{},{},{},{},{},\"{}\",\"{}\",{},\"{}\",\"{}\",{},{},\"{}\",\"{}\",{},{},{},{}", spec.shot,
        spec.measure == Measure::Trajectory ? "trajectory" : "statistics", d(spec.window), d(tol.trajectory),
        d(tol.first_break), d(tol.broken_fraction), d(tol.fragments), d(tol.scatter_rel), d(tol.early),
        values_text(spec, finest), size_text(ref), d(ref.o.cpu_seconds / spec.window), values_text(spec, chosen),
        size_text(combined), d(combined.o.cpu_seconds / spec.window), d(combined_dv.worst), values_text(spec, shipped),
        size_text(ship), d(ship.o.cpu_seconds / spec.window), d(ship_dv.worst), ship_dv.worst <= 1 ? 1 : 0,
        chosen == shipped ? 1 : 0));
    h.smallest.push_back({spec.shot, ship_dv.worst, combined_dv.worst, chosen == shipped});
}

}  // namespace

bool section_smallest(const Options& opt, Headlines& h) {
    Csv runs(opt.out, "smallest.csv", kRunHeader);
    Csv summary(opt.out, "smallest_summary.csv",
                "shot,measure,window_s,tol_trajectory_m,tol_first_break_s,tol_broken_fraction,tol_fragments,"
                "tol_scatter_rel,tol_early_m,finest,finest_size,finest_cpu_per_sim_s,chosen,chosen_size,"
                "chosen_cpu_per_sim_s,chosen_worst_ratio,shipped,shipped_size,shipped_cpu_per_sim_s,"
                "shipped_worst_ratio,shipped_pass,chosen_is_shipped");
    for (const ShotSpec& spec : shot_specs()) {
        if (std::find(opt.shots.begin(), opt.shots.end(), spec.shot) == opt.shots.end()) continue;
        study_shot(spec, opt, runs, summary, h);
    }
    runs.close();
    summary.close();
    return true;
}

}  // namespace shatter::study
