// A shot's scene on the continuum reference (bench/fem_scene.h).
#include "bench/fem_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>

#include "bench/fem_box_mesh.h"
#include "bench/fem_contact.h"
#include "simulate/surface_pair.h"

namespace shatter::fem {

void refine_tets(TetMesh& mesh, std::vector<uint32_t>& tet_piece) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    const auto midpoint = [&](uint32_t a, uint32_t b) {
        const auto key = std::minmax(a, b);
        const auto it = mid.find(key);
        if (it != mid.end()) return it->second;
        const uint32_t m = uint32_t(mesh.vertices.size());
        mesh.vertices.push_back(0.5 * (mesh.vertices[a] + mesh.vertices[b]));
        mid.emplace(key, m);
        return m;
    };
    std::vector<Tet> tets;
    std::vector<uint32_t> piece;
    tets.reserve(8 * mesh.tets.size());
    piece.reserve(8 * mesh.tets.size());
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet q = mesh.tets[t];
        const uint32_t m01 = midpoint(q[0], q[1]), m02 = midpoint(q[0], q[2]), m03 = midpoint(q[0], q[3]),
                       m12 = midpoint(q[1], q[2]), m13 = midpoint(q[1], q[3]), m23 = midpoint(q[2], q[3]);
        const Tet children[8] = {{q[0], m01, m02, m03}, {m01, q[1], m12, m13}, {m02, m12, q[2], m23},
                                 {m03, m13, m23, q[3]}, {m01, m02, m03, m13}, {m01, m12, m02, m13},
                                 {m02, m03, m13, m23},  {m02, m13, m12, m23}};
        for (Tet c : children) {
            if (tet_volume(mesh.vertices[c[0]], mesh.vertices[c[1]], mesh.vertices[c[2]], mesh.vertices[c[3]]) < 0)
                std::swap(c[2], c[3]);
            tets.push_back(c);
            piece.push_back(tet_piece[t]);
        }
    }
    mesh.tets = std::move(tets);
    tet_piece = std::move(piece);
}

void box_model_tets(const Model& model, uint32_t cells, TetMesh& mesh, std::vector<uint32_t>& tet_piece) {
    std::vector<Vec3> lo(model.pieces.size()), hi(model.pieces.size());
    Vec3 all_lo = Vec3::Constant(1e300), all_hi = Vec3::Constant(-1e300);
    double shortest = 1e300;
    for (size_t p = 0; p < model.pieces.size(); ++p) {
        lo[p] = Vec3::Constant(1e300), hi[p] = Vec3::Constant(-1e300);
        for (const Vec3& v : model.pieces[p].surface.vertices) lo[p] = lo[p].cwiseMin(v), hi[p] = hi[p].cwiseMax(v);
        all_lo = all_lo.cwiseMin(lo[p]), all_hi = all_hi.cwiseMax(hi[p]);
        shortest = std::min(shortest, (hi[p] - lo[p]).minCoeff());
    }
    const double cell = shortest / cells;
    const Vec3 size = all_hi - all_lo;
    const auto count = [&](double extent) { return uint32_t(std::max(1L, std::lround(extent / cell))); };
    TetMesh grid = box_tet_mesh(size, count(size.x()), count(size.y()), count(size.z()));
    for (Vec3& v : grid.vertices) v += all_lo;
    mesh.vertices = grid.vertices;
    mesh.tets.clear();
    tet_piece.clear();
    const double eps = 1e-6 * cell;
    for (const Tet& t : grid.tets) {
        Vec3 c = Vec3::Zero();
        for (uint32_t q : t) c += grid.vertices[q] / 4;
        for (size_t p = 0; p < model.pieces.size(); ++p)
            if ((c.array() > lo[p].array() - eps).all() && (c.array() < hi[p].array() + eps).all()) {
                mesh.tets.push_back(t);
                tet_piece.push_back(uint32_t(p));
                break;
            }
    }
}

double stiffness_length(const Model& model) {
    if (model.mesh.tets.empty()) {
        double shortest = 1e300;
        for (const Piece& p : model.pieces) {
            Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
            for (const Vec3& v : p.surface.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
            shortest = std::min(shortest, (hi - lo).minCoeff());
        }
        return shortest;
    }
    double sum = 0;
    for (const Tet& t : model.mesh.tets)
        for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) sum += (model.mesh.vertices[t[a]] - model.mesh.vertices[t[b]]).norm();
    return sum / (6.0 * double(model.mesh.tets.size()));
}

FemSceneSettings scene_settings(const Model& model, const MaterialSettings& material, double poisson) {
    FemSceneSettings s;
    s.material.density = material.density ? *material.density : model.density;
    s.material.young = material.youngs_modulus ? *material.youngs_modulus : material.stiffness * stiffness_length(model);
    s.material.poisson = poisson;
    s.strength.tensile = s.strength.shear = material.strength;
    s.friction = material.surface.friction;
    s.h = model.mesh.tets.empty() ? 1e-5 : 1e-4;
    s.h_after = 1e-4;
    return s;
}

namespace {

// How far a point may fall along the unit direction `down` before it touches the scene's ground
// or a sphere (infinite when it never does).
double fall_to_contact(const Vec3& x, const Vec3& down, const ContactSettings& cs) {
    double best = INFINITY;
    if (cs.ground && down.y() < 0) best = std::min(best, (x.y() - cs.ground_height) / -down.y());
    for (const ContactSphere& s : cs.spheres) {
        // |x + d down - c| = r: d^2 + 2 d (down . (x - c)) + |x - c|^2 - r^2 = 0, the smaller root.
        const Vec3 w = x - s.center;
        const double b = down.dot(w), c = w.squaredNorm() - s.radius * s.radius, disc = b * b - c;
        if (disc >= 0 && -b - std::sqrt(disc) >= 0) best = std::min(best, -b - std::sqrt(disc));
    }
    for (const ContactBox& b : cs.boxes) {
        const Vec3 c = b.center(0);
        // The slab method along `down`.
        double t0 = 0, t1 = INFINITY;
        for (int k = 0; k < 3; ++k) {
            const double lo = c[k] - b.half[k] - x[k], hi = c[k] + b.half[k] - x[k];
            if (std::abs(down[k]) < 1e-15) {
                if (lo > 0 || hi < 0) t0 = INFINITY;
                continue;
            }
            double a = lo / down[k], e = hi / down[k];
            if (a > e) std::swap(a, e);
            t0 = std::max(t0, a), t1 = std::min(t1, e);
        }
        if (t0 <= t1) best = std::min(best, t0);
    }
    return best;
}

}  // namespace

FemSceneResult run_fem_scene(const Model& model, const SceneSettings& scene, const ObjectSettings& object,
                             const FemSceneSettings& s) {
    const auto t0 = std::chrono::steady_clock::now();
    FemSceneResult r;
    TetMesh mesh;
    std::vector<uint32_t> tet_piece;
    if (model.mesh.tets.empty()) {
        box_model_tets(model, s.box_cells, mesh, tet_piece);
    } else {
        mesh = model.mesh;
        tet_piece = model.tet_piece;
        for (uint32_t k = 0; k < s.refine; ++k) refine_tets(mesh, tet_piece);
    }
    if (!object.driven.empty() || !scene.kinematic.empty() || object.velocity.squaredNorm() > 0 ||
        object.angular_velocity.squaredNorm() > 0)
        throw std::invalid_argument("run_fem_scene: an object at rest in a static scene only");
    const Mat3 rot = rotation_matrix(object.pose.rotation_deg);
    const Vec3 shift = object_translation(model, object);
    for (Vec3& v : mesh.vertices) v = rot * v + shift;
    Interfaces in(split_pieces(mesh, tet_piece));
    const SplitMesh& split = in.split();
    r.tets = mesh.tets.size();
    r.vertices = split.mesh.vertices.size();
    r.ties = split.ties.size();
    r.pieces = split.pieces;
    for (const Tie& t : split.ties)
        if (r.pairs.empty() || r.pairs.back() != std::make_pair(t.piece_a, t.piece_b))
            r.pairs.emplace_back(t.piece_a, t.piece_b);

    ContactSettings cs;
    cs.stiffness = s.contact_stiffness;
    cs.ground = scene.ground;
    cs.ground_height = scene.ground_height;
    cs.ground_friction = pair_friction(s.friction, scene.ground_surface.friction);
    for (const ColliderSettings& c : scene.colliders) {
        if (c.shape.kind == ShapeKind::Sphere) {
            cs.spheres.push_back(
                {c.pose.position, c.shape.radius, pair_friction(s.friction, c.surface.friction)});
        } else if (c.shape.kind == ShapeKind::Box && c.pose.rotation_deg.squaredNorm() == 0) {
            const Vec3 centre = c.pose.position;
            cs.boxes.push_back({0.5 * c.shape.size, [centre](double) { return centre; },
                                pair_friction(s.friction, c.surface.friction)});
        } else {
            throw std::invalid_argument("run_fem_scene: colliders are spheres and axis-aligned boxes only");
        }
    }

    // Free fall to `lead` before the first contact.
    const double g = scene.gravity.norm();
    const Vec3 down = scene.gravity / g;
    double drop = INFINITY;
    for (const Vec3& v : split.mesh.vertices) drop = std::min(drop, fall_to_contact(v, down, cs));
    if (!std::isfinite(drop)) throw std::invalid_argument("run_fem_scene: the object falls onto nothing");
    const double fall = std::max(0.0, drop - s.lead);
    r.start_time = std::sqrt(2 * fall / g);
    r.contact_time = std::sqrt(2 * drop / g);
    double mass = 0;
    for (const Piece& p : model.pieces) mass += p.mass.volume * s.material.density;
    r.impact_energy = mass * g * drop;

    FemSettings fs;
    fs.material = s.material;
    fs.gravity = scene.gravity;
    fs.integrator = FemIntegrator::BackwardEuler;
    FemSolid solid(split.mesh, fs);
    in.apply(solid);
    attach_contact(solid, cs);
    for (uint32_t v = 0; v < solid.vertex_count(); ++v) {
        solid.positions().segment<3>(3 * v) += fall * down;
        solid.velocities().segment<3>(3 * v) = scene.gravity * r.start_time;
    }
    solid.set_time(r.start_time);

    double t_end = r.start_time + s.no_break_wait;
    double elastic_before = 0;
    bool have01 = false;
    while (solid.time() < t_end) {
        if (r.first_break < 0) elastic_before = solid.elastic_energy();
        const bool late = r.first_break >= 0 && solid.time() > r.first_break + s.fine_window;
        const double h = late ? s.h_after : s.h;
        solid.step(h);
        ++r.steps;
        if (!std::isfinite(solid.kinetic_energy())) break;
        if (in.break_overloaded(solid, s.strength) > 0) {
            if (r.first_break < 0) {
                r.first_break = solid.time();
                r.elastic_at_break = elastic_before;
                t_end = r.first_break + s.after - 0.5 * s.h_after;
            }
            r.last_break = solid.time();
        }
        if (s.progress && r.steps % 1000 == 0)
            std::fprintf(stderr, "fem: t = %.5f s, %ld steps, %zu of %zu ties broken, kinetic %.4g J, %.0f s\n", solid.time(),
                         r.steps, size_t(std::count_if(split.ties.begin(), split.ties.end(), [](const Tie& t) { return t.broken; })),
                         split.ties.size(), solid.kinetic_energy(),
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        if (r.first_break >= 0 && !have01 && solid.time() >= r.first_break + std::min(0.1, s.after) - 0.5 * h) {
            r.at_01 = piece_motion(solid, split.vertex_piece, 0, split.pieces - 1);
            have01 = true;
        }
    }
    r.complete = std::isfinite(solid.kinetic_energy());
    r.at_05 = piece_motion(solid, split.vertex_piece, 0, split.pieces - 1);
    std::map<std::pair<uint32_t, uint32_t>, bool> all_broken;
    for (const Tie& t : split.ties) {
        auto [it, fresh] = all_broken.emplace(std::make_pair(t.piece_a, t.piece_b), true);
        it->second = it->second && t.broken;
    }
    for (const auto& [pair, broken] : all_broken)
        if (broken) r.separated.push_back(pair);
    tally_run(in, solid, t0, r);
    return r;
}

}  // namespace shatter::fem
