// The continuum reference's checks against beam and wave theory (bench/fem_checks.h).
#include "bench/fem_checks.h"

#include <chrono>
#include <cmath>

#include "bench/fem_box_mesh.h"

namespace shatter::fem {

namespace {

double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

constexpr double kPi = 3.14159265358979323846;

// Tributary weight of grid index i of n (0..n): half at the ends, so a uniform traction's nodal
// forces sum to it exactly.
double tributary(uint32_t i, uint32_t n) { return (i == 0 || i == n) ? 0.5 / n : 1.0 / n; }

struct Cantilever {
    TetMesh mesh;
    std::vector<uint32_t> root, tip;
    uint32_t cells = 0;
};

Cantilever make_cantilever(const CantileverGeometry& g, uint32_t cells) {
    Cantilever c;
    c.cells = cells;
    c.mesh = box_tet_mesh(Vec3(g.length, g.side, g.side), 10 * cells, cells, cells);
    const double eps = 1e-9 * g.length;
    c.root = select_vertices(c.mesh, [&](const Vec3& p) { return p.x() < eps; });
    c.tip = select_vertices(c.mesh, [&](const Vec3& p) { return p.x() > g.length - eps; });
    return c;
}

// Puts the tip load F (along -y) on the tip face's vertices by their tributary areas.
void load_tip(FemSolid& solid, const Cantilever& c, const CantileverGeometry& g, double F) {
    for (uint32_t v : c.tip) {
        const Vec3& p = c.mesh.vertices[v];
        const uint32_t j = uint32_t(std::lround(p.y() / g.side * c.cells)), k = uint32_t(std::lround(p.z() / g.side * c.cells));
        solid.set_load(v, Vec3(0, -F * tributary(j, c.cells) * tributary(k, c.cells), 0));
    }
}

double mean_tip_y(const FemSolid& solid, const Cantilever& c) {
    double s = 0;
    for (uint32_t v : c.tip) s += solid.position(v).y() - solid.rest()[3 * v + 1];
    return s / double(c.tip.size());
}

}  // namespace

StaticResult cantilever_static(const CantileverGeometry& g, uint32_t cells, double F) {
    const auto t0 = std::chrono::steady_clock::now();
    const Cantilever c = make_cantilever(g, cells);
    FemSettings s;
    s.material = g.material;
    s.gravity = Vec3::Zero();
    FemSolid solid(c.mesh, s);
    solid.clamp(c.root);
    load_tip(solid, c, g, F);
    solid.solve_static();
    StaticResult r;
    r.cells = cells;
    r.tets = c.mesh.tets.size();
    r.dofs = solid.free_dofs();
    r.deflection = -mean_tip_y(solid, c);
    const double E = g.material.young, nu = g.material.poisson, I = std::pow(g.side, 4) / 12, A = g.side * g.side;
    const double G = E / (2 * (1 + nu)), kappa = 10 * (1 + nu) / (12 + 11 * nu);
    r.euler_bernoulli = F * std::pow(g.length, 3) / (3 * E * I);
    r.timoshenko = r.euler_bernoulli + F * g.length / (kappa * G * A);
    r.seconds = since(t0);
    return r;
}

FrequencyResult cantilever_frequency(const CantileverGeometry& g, uint32_t cells, int periods, int steps_per_period,
                                     bool corotational) {
    const auto t0 = std::chrono::steady_clock::now();
    const Cantilever c = make_cantilever(g, cells);
    FemSettings s;
    s.material = g.material;
    s.gravity = Vec3::Zero();
    s.corotational = corotational;
    FemSolid solid(c.mesh, s);
    solid.clamp(c.root);
    FrequencyResult r;
    r.cells = cells;
    r.tets = c.mesh.tets.size();
    const double E = g.material.young, rho = g.material.density, I = std::pow(g.side, 4) / 12, A = g.side * g.side;
    r.euler_bernoulli = 1.875104 * 1.875104 / (2 * kPi * g.length * g.length) * std::sqrt(E * I / (rho * A));

    // Inverse iteration for the lowest eigenpair of K v = w^2 M v, from the shape gravity gives.
    const Eigen::SparseMatrix<double> K = solid.free_stiffness();
    r.dofs = size_t(K.rows());
    const Eigen::VectorXd m = solid.free_mass();
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(K);
    Eigen::VectorXd y = Eigen::VectorXd::Zero(K.rows());
    for (size_t q = 0; q < solid.free_index().size(); ++q)
        if (solid.free_index()[q] >= 0 && q % 3 == 1) y[solid.free_index()[q]] = -m[solid.free_index()[q]];
    double lambda = 0;
    for (int it = 0; it < 200; ++it) {
        y = ldlt.solve(m.cwiseProduct(y)).eval();
        y /= std::sqrt(y.dot(m.cwiseProduct(y)));
        const double l = y.dot(K * y);
        const bool done = it > 0 && std::abs(l - lambda) <= 1e-13 * l;
        lambda = l;
        if (done) break;
    }
    r.modal = std::sqrt(lambda) / (2 * kPi);

    if (periods > 0) {
        // Start from the first mode's shape (tip moved 0.1 mm), at rest, and time the tip's
        // upward zero crossings: a single mode, so no other mode's crossings are counted.
        const auto& fi = solid.free_index();
        double tip_mode = 0;
        for (uint32_t v : c.tip) tip_mode += y[fi[3 * v + 1]] / double(c.tip.size());
        const double scale = -1e-4 / tip_mode;
        for (size_t q = 0; q < fi.size(); ++q)
            if (fi[q] >= 0) solid.positions()[q] += scale * y[fi[q]];
        const double h = 1 / (r.euler_bernoulli * steps_per_period);
        const double e0 = solid.kinetic_energy() + solid.elastic_energy();
        double prev = mean_tip_y(solid, c), first = -1, last = -1, t_prev = 0;
        int crossings = 0;
        for (int i = 0; i < periods * steps_per_period + steps_per_period / 2; ++i) {
            solid.step(h);
            const double y_tip = mean_tip_y(solid, c);
            if (prev < 0 && y_tip >= 0) {
                const double t = t_prev + h * (-prev) / (y_tip - prev);
                if (first < 0) first = t;
                else ++crossings;
                last = t;
            }
            prev = y_tip;
            t_prev = solid.time();
            r.energy_drift = std::max(r.energy_drift, std::abs(solid.kinetic_energy() + solid.elastic_energy() - e0) / e0);
        }
        if (crossings > 0) r.dynamic = crossings / (last - first);
    }
    r.seconds = since(t0);
    return r;
}

WaveResult bar_wave_speed(const FemMaterial& mat, uint32_t cells, double steps_per_cell, double length, double side) {
    const auto t0 = std::chrono::steady_clock::now();
    const uint32_t along = 30 * cells;
    const TetMesh mesh = box_tet_mesh(Vec3(length, side, side), along, cells, cells);
    const double eps = 1e-9 * length;
    const auto near = select_vertices(mesh, [&](const Vec3& p) { return p.x() < eps; });
    const auto far = select_vertices(mesh, [&](const Vec3& p) { return p.x() > length - eps; });
    FemSettings s;
    s.material = mat;
    s.gravity = Vec3::Zero();
    s.solver = FemLinearSolver::CG;
    FemSolid solid(mesh, s);
    const double v0 = 1;
    solid.drive(near, Vec3(v0, 0, 0));
    WaveResult r;
    r.cells = cells;
    r.tets = mesh.tets.size();
    r.theory = std::sqrt(mat.young / mat.density);
    // Until 2 L / c the far end moves at 2 v0 behind the front, so its displacement is
    // u = 2 v0 (t - L / c) whatever the front's shape (its mean travels at the long-wave speed):
    // arrival = t - u / (2 v0). The front itself spreads (dispersion of the tets and of a 3D bar).
    const double h = length / along / r.theory / steps_per_cell;
    const double t_end = 2 * length / r.theory;
    while (solid.time() < t_end - 0.5 * h) solid.step(h);
    double u = 0;
    for (uint32_t v : far) u += solid.position(v).x() - solid.rest()[3 * v];
    u /= double(far.size());
    r.arrival = solid.time() - u / (2 * v0);
    r.speed = r.arrival > 0 ? length / r.arrival : 0;
    r.seconds = since(t0);
    return r;
}

TumbleResult tumbling_bar(bool corotational, double spin, double turns, int steps_per_turn) {
    const Vec3 size(0.1, 0.02, 0.02);
    TetMesh mesh = box_tet_mesh(size, 10, 2, 2);
    for (Vec3& p : mesh.vertices) p -= 0.5 * size;
    FemSettings s;
    s.gravity = Vec3::Zero();
    s.corotational = corotational;
    FemSolid solid(mesh, s);
    // Rigid spin about z plus a bending velocity along y (a parabola in x, zero mean).
    for (uint32_t v = 0; v < mesh.vertices.size(); ++v) {
        const Vec3& p = mesh.vertices[v];
        const double xi = p.x() / (0.5 * size.x());
        solid.velocities().segment<3>(3 * v) = Vec3(0, 0, spin).cross(p) + Vec3(0, 0.5 * (xi * xi - 1.0 / 3), 0);
    }
    TumbleResult r;
    r.initial_energy = solid.kinetic_energy() + solid.elastic_energy();
    const double h = 2 * kPi / spin / steps_per_turn;
    r.steps = int(turns * steps_per_turn);
    for (int i = 0; i < r.steps; ++i) {
        r.max_newton = std::max(r.max_newton, double(solid.step(h)));
        const double el = solid.elastic_energy();
        r.max_elastic = std::max(r.max_elastic, el);
        r.energy_drift = std::max(r.energy_drift, std::abs(solid.kinetic_energy() + el - r.initial_energy) / r.initial_energy);
    }
    return r;
}

}  // namespace shatter::fem

#include "bench/fem_interfaces.h"

namespace shatter::fem {

InterfaceStaticResult scored_cantilever(const CantileverGeometry& g, uint32_t cells, double x_score, double strength) {
    InterfaceStaticResult r;
    r.cells = cells;
    const Cantilever c = make_cantilever(g, cells);
    std::vector<uint32_t> tet_piece(c.mesh.tets.size());
    for (size_t t = 0; t < c.mesh.tets.size(); ++t) {
        Vec3 centre = Vec3::Zero();
        for (uint32_t v : c.mesh.tets[t]) centre += c.mesh.vertices[v] / 4;
        tet_piece[t] = centre.x() > x_score ? 1 : 0;
    }
    Interfaces in(split_pieces(c.mesh, tet_piece));
    r.ties = in.split().ties.size();
    const TetMesh& m = in.split().mesh;
    FemSettings s;
    s.material = g.material;
    s.gravity = Vec3::Zero();
    FemSolid solid(m, s);
    const double eps = 1e-9 * g.length;
    solid.clamp(select_vertices(m, [&](const Vec3& p) { return p.x() < eps; }));
    const auto tip = select_vertices(m, [&](const Vec3& p) { return p.x() > g.length - eps; });
    const double F = 100;
    for (uint32_t v : tip) {
        const Vec3& p = m.vertices[v];
        const uint32_t j = uint32_t(std::lround(p.y() / g.side * cells)), k = uint32_t(std::lround(p.z() / g.side * cells));
        solid.set_load(v, Vec3(0, -F * tributary(j, cells) * tributary(k, cells), 0));
    }
    in.apply(solid);
    solid.solve_static();
    double tip_y = 0;
    for (uint32_t v : tip) tip_y += solid.position(v).y() - m.vertices[v].y();
    r.deflection_split = -tip_y / double(tip.size());
    r.deflection_whole = cantilever_static(g, cells, F).deflection;
    for (size_t i = 0; i < in.split().ties.size(); ++i) {
        double sigma, tau;
        in.traction(solid, i, sigma, tau);
        r.max_sigma = std::max(r.max_sigma, sigma);
    }
    r.break_load = F * strength / r.max_sigma;
    const double I = std::pow(g.side, 4) / 12;
    r.beam_theory = strength * I / (0.5 * g.side * (g.length - x_score));
    return r;
}

TensionBreakResult bar_tension_break(uint32_t cells, double v, double h, double strength) {
    const auto t0 = std::chrono::steady_clock::now();
    const double L = 0.1, b = 0.01;
    const TetMesh mesh = box_tet_mesh(Vec3(L, b, b), 10 * cells, cells, cells);
    std::vector<uint32_t> tet_piece(mesh.tets.size());
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        double x = 0;
        for (uint32_t q : mesh.tets[t]) x += mesh.vertices[q].x() / 4;
        tet_piece[t] = x > L / 2 ? 1 : 0;
    }
    Interfaces in(split_pieces(mesh, tet_piece));
    const TetMesh& m = in.split().mesh;
    FemSettings s;
    s.gravity = Vec3::Zero();
    FemSolid solid(m, s);
    const double eps = 1e-9 * L;
    solid.clamp(select_vertices(m, [&](const Vec3& p) { return p.x() < eps; }));
    solid.drive(select_vertices(m, [&](const Vec3& p) { return p.x() > L - eps; }), Vec3(v, 0, 0));
    in.apply(solid);
    TensionBreakResult r;
    r.ties = in.split().ties.size();
    r.predicted = strength * L / (s.material.young * v);
    const Strength st{strength, 1e300};
    while (solid.time() < 2 * r.predicted) {
        solid.step(h);
        double lo = 1e300, hi = 0, mean = 0;
        for (size_t i = 0; i < r.ties; ++i) {
            double sigma, tau;
            in.traction(solid, i, sigma, tau);
            lo = std::min(lo, sigma);
            hi = std::max(hi, sigma);
            mean += sigma / double(r.ties);
        }
        const double spread = (hi - lo) / mean;
        if (in.break_overloaded(solid, st) > 0 && r.break_time == 0) r.break_time = solid.time();
        if (r.break_time == 0) r.sigma_spread = spread;
        if (r.break_time > 0 && solid.time() > r.break_time + 2 * L / std::sqrt(s.material.young / s.material.density))
            break;  // a wave has crossed the bar twice: the last ties have had their chance
    }
    for (const Tie& t : in.split().ties) r.broken += t.broken;
    r.fragments = in.fragments();
    r.seconds = since(t0);
    return r;
}

}  // namespace shatter::fem
