// How the study scores a run (docs/accuracy.md defines each measure).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <limits>

#include "bench/study.h"
#include "core/error.h"

namespace shatter::study {

RunOutcome run_case(const StudyCase& c) {
    RunOutcome o;
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    try {
        o.sim = simulate(c.model, c.input, "study");
    } catch (const Error& e) {
        if (e.code() != ExitCode::BadInput) throw;
        o.refused = true;
        o.message = e.what();
        o.sim.complete = false;
    }
    o.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    o.cpu_seconds = double(std::clock() - c0) / CLOCKS_PER_SEC;
    return o;
}

RunOutcome run_timed(const StudyCase& c, int repeats) {
    RunOutcome best = run_case(c);
    for (int i = 1; i < repeats && !best.refused; ++i) {
        const RunOutcome o = run_case(c);
        best.wall_seconds = std::min(best.wall_seconds, o.wall_seconds);
        best.cpu_seconds = std::min(best.cpu_seconds, o.cpu_seconds);
    }
    return best;
}

namespace {

struct MaterialPoint {
    Vec3 x;          // model frame (unit: m)
    uint32_t piece;  // in the reference model
};

std::vector<MaterialPoint> material_points(const Model& m) {
    std::vector<MaterialPoint> out;
    for (uint32_t p = 0; p < m.pieces.size(); ++p) {
        const Piece& piece = m.pieces[p];
        const Vec3 c = piece.mass.center;
        out.push_back({c, p});
        Vec3 lo = c, hi = c;
        for (const Vec3& v : piece.surface.vertices) {
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
        }
        const Vec3 half = 0.5 * (hi - lo);
        for (int a = 0; a < 3; ++a)
            for (double s : {-0.4, 0.4}) out.push_back({c + s * half[a] * Vec3::Unit(a), p});
    }
    return out;
}

// The piece of `model` holding point x: the piece of the nearest tet centroid.
uint32_t piece_at(const Model& model, const Vec3& x) {
    double best = std::numeric_limits<double>::infinity();
    uint32_t piece = 0;
    for (size_t t = 0; t < model.mesh.tets.size(); ++t) {
        const Tet& tet = model.mesh.tets[t];
        Vec3 centroid = Vec3::Zero();
        for (uint32_t v : tet) centroid += model.mesh.vertices[v];
        const double d = (0.25 * centroid - x).squaredNorm();
        if (d < best) {
            best = d;
            piece = model.tet_piece[t];
        }
    }
    return piece;
}

Vec3 world_point(const Model& m, const Trajectory& t, uint32_t frame, uint32_t piece, const Vec3& x) {
    const BodyPose& pose = t.pose(frame, piece);
    const Vec3 local = x - m.pieces[piece].mass.center;
    return pose.rotation.cast<double>() * local + pose.position.cast<double>();
}

bool same_partition(const Model& a, const Model& b) {
    return a.pieces.size() == b.pieces.size() && a.mesh.tets.size() == b.mesh.tets.size() &&
           a.tet_piece == b.tet_piece;
}

// Calls add(a - b) for every material point of the reference and every frame from `from` to
// `until` (unit: s) that both trajectories have, a and b the point's world positions in the run
// and in the reference.
template <class Add>
void for_each_point_offset(const Model& run_model, const Trajectory& run, const Model& ref_model,
                           const Trajectory& ref, double from, double until, Add&& add) {
    const std::vector<MaterialPoint> points = material_points(ref_model);
    std::vector<uint32_t> run_piece(points.size());
    const bool same = same_partition(run_model, ref_model);
    for (size_t i = 0; i < points.size(); ++i) run_piece[i] = same ? points[i].piece : piece_at(run_model, points[i].x);
    const uint32_t frames =
        std::min({run.frames(), ref.frames(), uint32_t(std::floor(until * ref.fps + 1e-9)) + 1});
    for (uint32_t f = uint32_t(std::max(0.0, std::ceil(from * ref.fps - 1e-9))); f < frames; ++f)
        for (size_t i = 0; i < points.size(); ++i)
            add(world_point(run_model, run, f, run_piece[i], points[i].x) -
                world_point(ref_model, ref, f, points[i].piece, points[i].x));
}

}  // namespace

double trajectory_error(const Model& run_model, const Trajectory& run, const Model& ref_model, const Trajectory& ref,
                        double until) {
    if (!run.complete) return std::numeric_limits<double>::infinity();
    double sum = 0;
    size_t n = 0;
    for_each_point_offset(run_model, run, ref_model, ref, 0, until, [&](const Vec3& d) { sum += d.norm(), ++n; });
    return n ? sum / double(n) : 0.0;
}

double trajectory_rms(const Model& run_model, const Trajectory& run, const Model& ref_model, const Trajectory& ref,
                      double from, double until) {
    if (!run.complete) return std::numeric_limits<double>::infinity();
    double sum = 0;
    size_t n = 0;
    for_each_point_offset(run_model, run, ref_model, ref, from, until,
                          [&](const Vec3& d) { sum += d.squaredNorm(), ++n; });
    return n ? std::sqrt(sum / double(n)) : 0.0;
}

double first_break(const SimulationResult& r) {
    return r.breaks.empty() ? std::numeric_limits<double>::quiet_NaN() : r.breaks.front().time;
}

size_t fragments(const Model& model, const SimulationResult& r) { return count_fragments(model, r.breaks); }

double energy_identity_error(const SimulationResult& r, bool per_body) {
    double worst = 0;
    for (const BreakRecord& b : r.breaks) {
        double intended = given_back(b);
        if (per_body) intended = b.kicks.kick[0].energy + b.kicks.kick[1].energy;
        if (!(intended > 0)) continue;
        worst = std::max(worst, std::abs(b.injected_energy - intended) / intended);
    }
    return worst;
}

double energy_books_error(const SimulationResult& r) {
    double stored = 0, injected = 0, alpha = 0;
    for (const BreakRecord& b : r.breaks) {
        stored += b.kicks.stored_energy;
        injected += b.injected_energy + b.held_energy - b.released_energy;  // held energy counts as given
        alpha = b.alpha;
    }
    if (!(alpha * stored > 0)) return 0;
    return (injected - alpha * stored) / (alpha * stored);
}

double stiffness_identity_error(const StudyCase& c, const SimulationResult& r) {
    const double m = c.model.pieces[1].mass.mass, g = c.input.scene.gravity.norm();
    double area = 0;
    for (const Constraint& k : c.model.constraints) area += k.area;
    const double sag = (r.energy.front().potential - r.energy.back().potential) / (m * g);
    return (m * g / sag) / (c.input.material.stiffness * area) - 1;
}

const char* to_string(Stability s) {
    switch (s) {
        case Stability::Refused: return "refused";
        case Stability::NaN: return "nan";
        case Stability::EnergyGrowth: return "energy_growth";
        case Stability::Cascade: return "cascade";
        case Stability::FlyApart: return "fly_apart";
        case Stability::Stable: return "stable";
    }
    return "?";
}

namespace {

// Largest gap between a constraint's two pivots (each carried by its piece) before the first break.
double largest_gap_before_break(const StudyCase& c, const SimulationResult& r) {
    const Trajectory& t = r.trajectory;
    const double t_break = r.breaks.empty() ? INFINITY : r.breaks.front().time;
    double worst = 0;
    for (uint32_t f = 0; f < t.frames() && f / t.fps < t_break - 1e-12; ++f)
        for (const Constraint& k : c.model.constraints) {
            const Vec3 a = world_point(c.model, t, f, k.piece_a, k.pivot);
            const Vec3 b = world_point(c.model, t, f, k.piece_b, k.pivot);
            worst = std::max(worst, (a - b).norm());
        }
    return worst;
}

}  // namespace

Stability classify(const StudyCase& c, const RunOutcome& o, double* energy_growth) {
    *energy_growth = 0;
    if (o.refused) return Stability::Refused;
    const SimulationResult& r = o.sim;
    // A run that stopped: a NaN, or (simulate/instability.h) kinetic energy beyond the scene's budget.
    if (!r.complete) return r.stop_reason.find("NaN") != std::string::npos ? Stability::NaN : Stability::EnergyGrowth;
    const EnergyGrowthTest energy = energy_growth_test(c, r);
    *energy_growth = energy.largest;
    if (energy.grew) return Stability::EnergyGrowth;
    if (2 * most_breaks_within(r.breaks, 0.1) > c.model.constraints.size()) return Stability::Cascade;
    if (largest_gap_before_break(c, r) > 1e-3) return Stability::FlyApart;
    return Stability::Stable;
}

Csv::Csv(const std::string& dir, const std::string& name, const std::string& header) {
    std::filesystem::create_directories(dir);
    path_ = dir + "/" + name;
    tmp_ = path_ + ".tmp";
    f_ = std::fopen(tmp_.c_str(), "w");
    if (!f_) throw Error(ExitCode::Io, "study: cannot write " + tmp_);
    std::fprintf(f_, "%s\n", header.c_str());
}

Csv::~Csv() {
    if (f_) close();
}

void Csv::row(const std::string& line) {
    std::fprintf(f_, "%s\n", line.c_str());
    std::fflush(f_);
}

void Csv::close() {
    std::fclose(f_);
    f_ = nullptr;
    std::filesystem::rename(tmp_, path_);
}

std::string fmt_double(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

}  // namespace shatter::study
