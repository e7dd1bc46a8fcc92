// The smallest model that serves (docs/accuracy.md section 7).
//
// Unlike the other sections, this one reads the shipped shots (assets/<shot>.toml): its question
// is whether their model-size settings can be made smaller. Per shot, with the compared window
// set as [simulate] duration:
//   1. the reference: every model-size knob at its finest value (the finest the CFM guard admits);
//   2. an impact (a chaotic scene) is compared as an ensemble: every model is dropped 8 times,
//      from its own place and moved by up to 1 mm (an invisible change: up and down over a flat
//      ground, sideways over a sphere; Nudge says why), and the statistics of the 8 are
//      compared with the finest model's 8 (a two-sample test: the means within twice their
//      standard error, or within a floor a viewer would not see);
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
#include "core/fragments.h"
#include "core/shot.h"
#include "prescore/prescore.h"
#include "simulate/simulate.h"

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

// Which way an impact's drops are moved (by at most 1 mm, which a viewer cannot see).
enum class Nudge {
    // Up and down: for a flat ground, where a sideways move is a symmetry (tried: all 8 drops of
    // the demo bunny were one run, shifted).
    Vertical,
    // Sideways: for an object that lands on a sphere, where the move changes where it hits. Up and
    // down there moves the impact across the step's boundaries: the bunny met the sphere one 2 ms
    // step earlier from the lower drops, and the drops split into two outcomes (2.4 J against
    // 0.8 J of kinetic energy 0.1 s after the break) that no model-size knob changes.
    Sideways,
};

struct ShotSpec {
    std::string shot;   // assets/<shot>.toml
    double window;      // (unit: s) the simulated time compared; set as [simulate] duration
    Measure measure;
    std::vector<KnobSpec> knobs;
    // The trajectory is compared up to the reference's first break plus this (unit: s); after it,
    // the chain's recoil follows a kick direction that numerical noise picks (a pull along the
    // axis has tau x f ~ 0; docs/physics.md), so it is not comparable frame by frame.
    double compare_after_break = kInf;
    // Frames recorded per frame of the shot, the step unchanged (fps x k, substeps / k): an
    // impact's fragments part within tens of milliseconds, which the shot's 30 fps does not
    // resolve. Every value of the substeps knob must be a multiple of it.
    int record_more = 1;
    Nudge nudge = Nudge::Vertical;
};

// The bunny's knobs (both shots). The resolution re-draws the pieces (new tets, new seed tets for
// the partition): another set of fragments, not a finer version of the same ones, so it is swept
// around the shot's and not chosen. 16 substeps at resolution 30 is refused by the CFM guard.
// Substeps from 4: the runs are recorded at 4 frames per shot frame (2 substeps, which failed by
// 8 to 15 times the tolerance in the single-frame study, cannot be).
std::vector<KnobSpec> bunny_knobs() {
    return {{"resolution", "prescore.resolution", {10, 15, 20, 30}, false},
            {"constraints_per_pair", "prescore.constraints_per_pair", {4, 8, 16, 32, 0}},  // 0: all
            {"collision_parts", "prescore.collision_max_parts", {1, 2, 4, 8, 16, 32}},
            {"substeps", "simulate.substeps", {4, 8, 16}}};
}

std::vector<ShotSpec> shot_specs() {
    return {
        {"beam", 0.8, Measure::Trajectory,
         {{"constraints_per_side", "generate.constraints_per_side", {1, 2, 3, 4}, false},
          {"substeps", "simulate.substeps", {1, 2, 4, 8, 16, 32, 64, 128}}}},  // 32 did not snap it (assets/beam.toml)
        // constraints_per_side is the chain's joint type (1: a ball joint), not a resolution.
        {"chain", 0.6, Measure::Trajectory, {{"substeps", "simulate.substeps", {250, 500, 1000, 2000, 4000}}}, 0},
        // 3 x 3 per face at more than ~1,100 substeps is refused by the CFM guard.
        {"plate", 0.6, Measure::Statistics,
         {{"constraints_per_side", "generate.constraints_per_side", {1, 2, 3}},
          {"substeps", "simulate.substeps", {125, 250, 500, 1000}}},
         kInf, 5, Nudge::Sideways},  // recorded at 150 fps
        {"bunny", 4.0, Measure::Statistics, bunny_knobs(), kInf, 4},                           // 120 fps
        {"bunny_sphere", 2.0, Measure::Statistics, bunny_knobs(), kInf, 4, Nudge::Sideways},   // 120 fps
    };
}

double shot_value(const Shot& s, const std::string& key) {
    if (key == "generate.constraints_per_side") return s.generate ? s.generate->constraints_per_side : NAN;
    if (key == "prescore.resolution") return s.prescore.resolution;
    if (key == "prescore.constraints_per_pair") return s.prescore.constraints_per_pair;
    if (key == "prescore.collision_max_parts") return s.prescore.collision_max_parts;
    if (key == "simulate.substeps") return s.simulate.auto_substeps ? NAN : s.simulate.substeps;  // NaN: "auto"
    throw Error(ExitCode::Internal, "study: no shot value for " + key);
}

// What a run is scored by (docs/accuracy.md section 7).
struct Stats {
    size_t breaks = 0, fragments = 0;
    double first_break = NAN;      // (unit: s)
    double broken_fraction = 0;    // breaks / constraints
    double scatter = 0;            // (unit: m) mass-weighted RMS distance of the pieces from their centre, last frame
    // (unit: J) the pieces' kinetic energy at the recorded frame nearest to 0.1 s after the first
    // break: how hard the fragments leave (the column of docs/results/scenes.md's tables); NaN without a break
    double kinetic_after = NAN;
    // (unit: J) at the same frame, the part of it that is the fragments flying apart: translational
    // kinetic energy about the pieces' common centre of mass (core/fragments.h, the tables' column)
    double spread_after = NAN;
};

Stats stats_of(const Model& m, const SimulationResult& r) {
    Stats s;
    s.breaks = r.breaks.size();
    s.fragments = fragments(m, r);
    s.first_break = first_break(r);
    s.broken_fraction = m.constraints.empty() ? 0 : double(s.breaks) / double(m.constraints.size());
    if (!std::isnan(s.first_break)) {
        double best = kInf;
        for (const EnergySample& e : r.energy)
            if (std::abs(e.time - (s.first_break + 0.1)) < best)
                best = std::abs(e.time - (s.first_break + 0.1)), s.kinetic_after = e.kinetic;
        s.spread_after = spread_energy(m, r.trajectory, uint32_t(std::lround((s.first_break + 0.1) * r.trajectory.fps)));
    }
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
    ShotRunner(const std::string& shot, double window, int record_more)
        : path_(std::string(SHATTER_SOURCE_DIR) + "/assets/" + shot + ".toml"), window_(window),
          record_more_(record_more), base_(load_shot(path_)) {}
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
        // At the automatic step (a shot's own) the frames are only recorded more often: each is cut
        // into blocks of at most 1/480 s as the shot's are (at 150 fps, four of 1/600 s).
        const bool automatic = r.c.input.simulate.auto_substeps;
        if (!automatic && r.c.input.simulate.substeps % uint32_t(record_more_) != 0)
            throw Error(ExitCode::Internal, fmt::format("study: {} substeps cannot be recorded {} times per frame",
                                                        r.c.input.simulate.substeps, record_more_));
        r.c.input.simulate.fps *= record_more_;
        if (!automatic) r.c.input.simulate.substeps /= uint32_t(record_more_);
        r.o = run_case(r.c);
        r.s = stats_of(r.c.model, r.o.sim);
        return r;
    }

private:
    std::string path_;
    double window_;
    int record_more_;
    Shot base_;
    std::map<std::string, std::pair<Model, double>> models_;
};

// The drops an impact's ensemble is made of (unit: m, added to the object's position): the
// shot's own first. A deterministic shot (beam, chain) is compared run against run: one drop.
std::vector<Vec3> drop_offsets(const ShotSpec& spec) {
    if (spec.measure == Measure::Trajectory) return {Vec3::Zero()};
    std::vector<Vec3> o;
    if (spec.nudge == Nudge::Vertical) {
        for (double dy : {0.0, -1e-3, 1e-3, -0.75e-3, 0.75e-3, -0.5e-3, 0.5e-3, -0.25e-3}) o.emplace_back(0, dy, 0);
    } else {
        // 1 mm away, in directions 2.4 rad (about the golden angle) apart, so that no two coincide.
        o.push_back(Vec3::Zero());
        for (int i = 1; i < 8; ++i) o.emplace_back(1e-3 * std::cos(2.4 * i), 0, 1e-3 * std::sin(2.4 * i));
    }
    return o;
}

// One model, run from every drop of its shot's ensemble.
struct Ensemble {
    std::vector<Run> runs;
    bool ok() const {
        for (const Run& r : runs)
            if (r.o.refused || !r.o.sim.complete) return false;
        return !runs.empty();
    }
    const Run& first() const { return runs.front(); }
    template <class F>
    std::vector<double> each(F f) const {
        std::vector<double> v;
        for (const Run& r : runs) v.push_back(f(r));
        return v;
    }
    double mean_cpu_seconds() const {
        double sum = 0;
        for (const Run& r : runs) sum += r.o.cpu_seconds;
        return runs.empty() ? 0 : sum / double(runs.size());
    }
};

// What a model's deviation from the finest is held to; the floors are what a viewer would not see.
struct Tolerance {
    double trajectory = kInf;       // (unit: m) RMS over the window
    double first_break = kInf;      // (unit: s)
    double broken_fraction = kInf;
    double fragments = kInf;
    double scatter_rel = kInf;
    double kinetic_rel = kInf;      // the kinetic energy 0.1 s after the first break, relative
    double spread_rel = kInf;       // its spread about the pieces' common centre, relative
    double early = kInf;            // (unit: m) RMS over the 0.1 s after the reference's first break
    // The joints' largest residual before the first break (unit: 1, of the strength), in any run:
    // a model whose solve left the joints' forces off their stretch does not serve, however close
    // its motion (its books miss the difference: docs/physics.md section 5a).
    double residual = kInf;
};

struct Deviation {
    double trajectory = NAN, first_break = NAN, broken_fraction = NAN, fragments = NAN, scatter_rel = NAN,
           kinetic_rel = NAN, spread_rel = NAN, early = NAN, residual = NAN;
    Tolerance tol;        // what each was held to (for an ensemble: the floor or the noise, the larger)
    double worst = kInf;  // largest deviation / tolerance; <= 1 passes
};

double break_gap(double a, double b) {
    if (std::isnan(a) && std::isnan(b)) return 0;
    if (std::isnan(a) || std::isnan(b)) return kInf;
    return std::abs(a - b);
}

double mean_of(const std::vector<double>& x) {
    double s = 0;
    for (double v : x) s += v;
    return x.empty() ? NAN : s / double(x.size());
}

// The squared standard error of the mean of x (0 for fewer than 2 values).
double mean_variance(const std::vector<double>& x) {
    if (x.size() < 2) return 0;
    const double m = mean_of(x);
    double s = 0;
    for (double v : x) s += (v - m) * (v - m);
    return s / double(x.size() - 1) / double(x.size());
}

// Two ensembles' means differ by what their noise explains: twice the standard error of the
// difference (about 95% of identical models pass), or the floor, whichever is larger.
double noise_tolerance(const std::vector<double>& a, const std::vector<double>& b, double floor) {
    return std::max(floor, 2 * std::sqrt(mean_variance(a) + mean_variance(b)));
}

Deviation deviation(const Ensemble& run, const Ensemble& ref, const Tolerance& floor, double after_break = kInf) {
    Deviation dv;
    dv.tol = floor;
    if (!run.ok() || run.runs.size() != ref.runs.size()) return dv;
    const Run& r0 = ref.first();
    const double t0 = std::isnan(r0.s.first_break) ? 0 : r0.s.first_break;
    dv.residual = 0;
    for (const Run& r : run.runs) dv.residual = std::max(dv.residual, r.o.sim.residual_before_break.residual);
    auto rms = [&](const Run& a, const Run& b, double from, double until) {
        return trajectory_rms(a.c.model, a.o.sim.trajectory, b.c.model, b.o.sim.trajectory, from, until);
    };
    if (run.runs.size() == 1) {
        // Deterministic: the run against the reference, frame by frame.
        const Run& x = run.first();
        double until = r0.c.input.simulate.duration;
        if (!std::isnan(r0.s.first_break)) until = std::min(until, r0.s.first_break + after_break);
        dv.trajectory = rms(x, r0, 0, until);
        dv.early = rms(x, r0, t0, t0 + 0.1);
        dv.first_break = break_gap(x.s.first_break, r0.s.first_break);
        dv.broken_fraction = std::abs(x.s.broken_fraction - r0.s.broken_fraction);
        dv.fragments = std::abs(double(x.s.fragments) - double(r0.s.fragments));
        dv.scatter_rel = std::abs(x.s.scatter - r0.s.scatter) / std::max(r0.s.scatter, 1e-9);
    } else {
        // Chaotic: the ensembles' statistics. A run that does not break has no first break.
        auto first = [](const Run& r) { return r.s.first_break; };
        const std::vector<double> fb = run.each(first), fb_ref = ref.each(first);
        for (const std::vector<double>* v : {&fb, &fb_ref})
            for (double x : *v)
                if (std::isnan(x)) return dv;
        // A measure's means: their gap and its noise tolerance (floor: in the measure's unit), both
        // over `scale` (1 for the absolute measures, the finest model's mean for the relative ones).
        auto compare = [&](auto f, double floor_abs, double scale, double* gap, double* tol) {
            const std::vector<double> a = run.each(f), b = ref.each(f);
            *gap = std::abs(mean_of(a) - mean_of(b)) / scale;
            *tol = noise_tolerance(a, b, floor_abs) / scale;
        };
        auto compare_rel = [&](auto f, double floor_rel, double least_scale, double* gap, double* tol) {
            const double scale = std::max(mean_of(ref.each(f)), least_scale);
            compare(f, floor_rel * scale, scale, gap, tol);
        };
        compare(first, floor.first_break, 1, &dv.first_break, &dv.tol.first_break);
        compare([](const Run& r) { return r.s.broken_fraction; }, floor.broken_fraction, 1, &dv.broken_fraction,
                &dv.tol.broken_fraction);
        compare([](const Run& r) { return double(r.s.fragments); }, floor.fragments, 1, &dv.fragments,
                &dv.tol.fragments);
        compare_rel([](const Run& r) { return r.s.scatter; }, floor.scatter_rel, 1e-9, &dv.scatter_rel,
                    &dv.tol.scatter_rel);
        compare_rel([](const Run& r) { return r.s.kinetic_after; }, floor.kinetic_rel, 1e-12, &dv.kinetic_rel,
                    &dv.tol.kinetic_rel);
        compare_rel([](const Run& r) { return r.s.spread_after; }, floor.spread_rel, 1e-12, &dv.spread_rel,
                    &dv.tol.spread_rel);
        // Early trajectories: each run against the finest model's run from the same drop, against
        // how far the finest model's other drops land from its first (what a nudge alone does).
        std::vector<double> d, d_ref;
        for (size_t i = 0; i < run.runs.size(); ++i) d.push_back(rms(run.runs[i], ref.runs[i], t0, t0 + 0.1));
        for (size_t i = 1; i < ref.runs.size(); ++i) d_ref.push_back(rms(ref.runs[i], r0, t0, t0 + 0.1));
        dv.early = mean_of(d);
        dv.tol.early = std::max(floor.early, mean_of(d_ref) + 2 * std::sqrt(mean_variance(d) + mean_variance(d_ref)));
    }
    dv.worst = 0;
    for (auto [x, t] : {std::pair{dv.trajectory, dv.tol.trajectory}, {dv.first_break, dv.tol.first_break},
                        {dv.broken_fraction, dv.tol.broken_fraction}, {dv.fragments, dv.tol.fragments},
                        {dv.scatter_rel, dv.tol.scatter_rel}, {dv.kinetic_rel, dv.tol.kinetic_rel},
                        {dv.spread_rel, dv.tol.spread_rel}, {dv.early, dv.tol.early},
                        {dv.residual, dv.tol.residual}})
        if (std::isfinite(t) && !std::isnan(x)) dv.worst = std::max(dv.worst, x / t);
    return dv;
}

// The outermost Gauss-Legendre point of n points on [-1, 1].
double outer_gauss(int n) {
    static const double xi[] = {0, 0, 0.57735026918962576, 0.77459666924148338, 0.86113631159405258,
                                0.90617984593866399};
    if (n < 2 || n > 5) throw Error(ExitCode::Internal, "study: no Gauss point table for n = " + std::to_string(n));
    return xi[n];
}

// NaN is the automatic step (shot_value), the only knob value a shot can leave unnumbered.
std::string value_text(double v) { return std::isnan(v) ? "auto" : fmt::format("{:g}", v); }

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
    "shot,role,knob,value,settings,drops,refused,complete,prescore_s,cpu_s,cpu_per_sim_s,wall_per_sim_s,bodies,"
    "constraints,collision_parts,tets,substeps,breaks,first_break_s,fragments,broken_fraction,scatter_m,"
    "kinetic_after_J,spread_after_J,trajectory_rms_m,early_rms_m,d_first_break_s,d_broken_fraction,d_fragments,"
    "d_scatter_rel,d_kinetic_rel,d_spread_rel,tol_first_break_s,tol_broken_fraction,tol_fragments,tol_scatter_rel,"
    "tol_kinetic_rel,tol_spread_rel,tol_early_m,residual,tol_residual,worst_ratio,pass";

// One model: its size and cost, the means of its drops, and its deviation from the finest.
std::string run_row(const std::string& shot, const std::string& role, const std::string& knob, const std::string& value,
                    const Ensemble& e, const Deviation& dv) {
    const Run& r = e.first();
    const double w = r.c.input.simulate.duration;
    std::vector<std::string> settings;
    for (const std::string& o : r.overrides)
        if (o.rfind("simulate.duration", 0) != 0) settings.push_back(o);
    bool refused = false, complete = true;
    double wall = 0;
    for (const Run& x : e.runs) {
        refused = refused || x.o.refused;
        complete = complete && x.o.sim.complete;
        wall += x.o.wall_seconds / double(e.runs.size());
    }
    const double cpu = e.mean_cpu_seconds();
    return fmt::format(
        "{},{},{},\"{}\",\"{}\",{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
        shot, role, knob, value, join(settings, " "), e.runs.size(), refused, complete, d(r.c.prescore_seconds), d(cpu),
        d(cpu / w), d(wall / w), r.c.model.pieces.size(), r.c.model.constraints.size(), collision_parts_of(r.c.model),
        r.c.model.mesh.tets.size(), r.c.input.simulate.substeps,
        d(mean_of(e.each([](const Run& x) { return double(x.s.breaks); }))),
        d(mean_of(e.each([](const Run& x) { return x.s.first_break; }))),
        d(mean_of(e.each([](const Run& x) { return double(x.s.fragments); }))),
        d(mean_of(e.each([](const Run& x) { return x.s.broken_fraction; }))),
        d(mean_of(e.each([](const Run& x) { return x.s.scatter; }))),
        d(mean_of(e.each([](const Run& x) { return x.s.kinetic_after; }))),
        d(mean_of(e.each([](const Run& x) { return x.s.spread_after; }))), d(dv.trajectory), d(dv.early),
        d(dv.first_break), d(dv.broken_fraction), d(dv.fragments), d(dv.scatter_rel), d(dv.kinetic_rel),
        d(dv.spread_rel), d(dv.tol.first_break), d(dv.tol.broken_fraction), d(dv.tol.fragments),
        d(dv.tol.scatter_rel), d(dv.tol.kinetic_rel), d(dv.tol.spread_rel), d(dv.tol.early), d(dv.residual),
        d(dv.tol.residual), d(dv.worst), dv.worst <= 1 ? 1 : 0);
}

std::string values_text(const ShotSpec& spec, const std::vector<double>& v) {
    std::vector<std::string> s;
    for (size_t k = 0; k < spec.knobs.size(); ++k) s.push_back(spec.knobs[k].name + "=" + value_text(v[k]));
    return join(s, " ");
}

std::string size_text(const Ensemble& e) {
    const Run& r = e.first();
    return fmt::format("{} bodies {} constraints {} collision parts {} tets", r.c.model.pieces.size(),
                       r.c.model.constraints.size(), collision_parts_of(r.c.model), r.c.model.mesh.tets.size());
}

// Runs one model from every drop of the shot's ensemble: `values` for the knobs, or the shot as
// shipped (its own knob values: the resolution keeps the shot's stiffness) when null.
Ensemble run_ensemble(ShotRunner& runner, const ShotSpec& spec, const std::vector<double>* values) {
    const Shot& base = runner.base();
    Ensemble e;
    for (const Vec3& dp : drop_offsets(spec)) {
        std::vector<std::string> o = values ? overrides_for(spec, base, *values) : std::vector<std::string>{};
        if (dp != Vec3::Zero()) {
            const Vec3 p = base.object.pose.position + dp;
            o.push_back(fmt::format("object.position=[{:.17g}, {:.17g}, {:.17g}]", p.x(), p.y(), p.z()));
        }
        e.runs.push_back(runner.run(o));
    }
    return e;
}

// One shot: reference, tolerance, sweeps, choice, shipped.
void study_shot(const ShotSpec& spec, const Options& opt, Csv& runs, Csv& summary, Headlines& h) {
    spdlog::info("study: smallest {}", spec.shot);
    ShotRunner runner(spec.shot, spec.window, spec.record_more);
    const Shot& base = runner.base();
    std::vector<double> finest, shipped;
    for (const KnobSpec& k : spec.knobs) {
        shipped.push_back(shot_value(base, k.key));
        finest.push_back(k.choose ? k.values.back() : shipped.back());
    }

    const Ensemble ref = run_ensemble(runner, spec, &finest);
    if (!ref.ok())
        throw Error(ExitCode::Internal, "study: the finest " + spec.shot + " model does not run from every drop: " +
                                            ref.first().o.message + ref.first().o.sim.stop_reason);
    // The floors: what a viewer would not see.
    Tolerance floor;
    floor.first_break = 1 / base.simulate.fps;
    floor.residual = kResidualTolerance;
    const double one_percent = 0.01 * diagonal_of(ref.first().c.model);
    if (spec.measure == Measure::Trajectory) {
        floor.trajectory = one_percent;
    } else {
        floor.broken_fraction = 0.05, floor.fragments = 1, floor.scatter_rel = 0.1, floor.kinetic_rel = 0.1;
        floor.spread_rel = 0.1;
        floor.early = one_percent;
    }
    auto compare = [&](const Ensemble& e) { return deviation(e, ref, floor, spec.compare_after_break); };
    runs.row(run_row(spec.shot, "reference", "-", "-", ref, compare(ref)));

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
                const Ensemble e = run_ensemble(runner, spec, &v);
                const Deviation dv = compare(e);
                worst[k].push_back(dv.worst);
                runs.row(run_row(spec.shot, knob.choose ? "sweep" : "variant", knob.name, value_text(knob.values[i]), e,
                                 dv));
            }
            if (!knob.choose) continue;
            size_t pick = knob.values.size() - 1;
            while (pick > 0 && worst[k][pick - 1] <= 1) --pick;
            chosen[k] = knob.values[pick];
        }
    } else {
        chosen = shipped;  // quick: only the shipped shot against the reference
    }

    const Ensemble ship = run_ensemble(runner, spec, nullptr);
    const Deviation ship_dv = compare(ship);
    runs.row(run_row(spec.shot, "shipped", "-", values_text(spec, shipped), ship, ship_dv));

    // All knobs at their chosen values; refine the one furthest off until it passes.
    Ensemble combined = ship;
    Deviation combined_dv = ship_dv;
    for (int attempt = 0; attempt < 8 && !opt.quick; ++attempt) {
        combined = chosen == shipped ? ship : run_ensemble(runner, spec, &chosen);
        combined_dv = compare(combined);
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

    // The tolerances written are those the shipped model was held to.
    const Tolerance& tol = ship_dv.tol;
    summary.row(fmt::format(
        "{},{},{},{},{},{},{},{},{},{},{},{},\"{}\",\"{}\",{},\"{}\",\"{}\",{},{},\"{}\",\"{}\",{},{},{},{}", spec.shot,
        spec.measure == Measure::Trajectory ? "trajectory" : "statistics", ref.runs.size(), d(spec.window),
        d(tol.trajectory), d(tol.first_break), d(tol.broken_fraction), d(tol.fragments), d(tol.scatter_rel),
        d(tol.kinetic_rel), d(tol.spread_rel), d(tol.early), values_text(spec, finest), size_text(ref), d(ref.mean_cpu_seconds() / spec.window),
        values_text(spec, chosen), size_text(combined), d(combined.mean_cpu_seconds() / spec.window),
        d(combined_dv.worst), values_text(spec, shipped), size_text(ship), d(ship.mean_cpu_seconds() / spec.window),
        d(ship_dv.worst), ship_dv.worst <= 1 ? 1 : 0, chosen == shipped ? 1 : 0));
    h.smallest.push_back({spec.shot, ship_dv.worst, combined_dv.worst, chosen == shipped});
}

}  // namespace

bool section_smallest(const Options& opt, Headlines& h) {
    Csv runs(opt.out, "smallest.csv", kRunHeader);
    Csv summary(opt.out, "smallest_summary.csv",
                "shot,measure,drops,window_s,tol_trajectory_m,tol_first_break_s,tol_broken_fraction,tol_fragments,"
                "tol_scatter_rel,tol_kinetic_rel,tol_spread_rel,tol_early_m,finest,finest_size,finest_cpu_per_sim_s,chosen,chosen_size,"
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
