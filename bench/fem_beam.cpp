// The study's beam scene on the continuum reference (bench/fem_beam.h).
#include "bench/fem_beam.h"

#include <chrono>
#include <cmath>

#include "bench/fem_box_mesh.h"
#include "bench/fem_contact.h"
#include "bench/fem_interfaces.h"
#include "core/scene_settings.h"
#include "simulate/surface_pair.h"

namespace shatter::fem {

PieceMotion piece_motion(const FemSolid& solid, const std::vector<uint32_t>& vertex_piece, uint32_t first,
                         uint32_t last) {
    const uint32_t pieces = last + 1;
    PieceMotion m;
    m.time = solid.time();
    m.kinetic = solid.kinetic_energy();
    const Eigen::VectorXd& x = solid.positions_const();
    const Eigen::VectorXd& v = solid.velocities_const();
    const Eigen::VectorXd& mass = solid.lumped_mass();
    std::vector<double> M(pieces, 0);
    std::vector<Vec3> P(pieces, Vec3::Zero()), C(pieces, Vec3::Zero());
    for (size_t i = 0; i < vertex_piece.size(); ++i) {
        const uint32_t p = vertex_piece[i];
        if (p < first || p > last) continue;
        M[p] += mass[3 * i];
        P[p] += mass[3 * i] * v.segment<3>(3 * i);
        C[p] += mass[3 * i] * x.segment<3>(3 * i);
    }
    std::vector<Vec3> L(pieces, Vec3::Zero());
    std::vector<Mat3> I(pieces, Mat3::Zero());
    for (uint32_t p = first; p < pieces; ++p) C[p] /= M[p];
    for (size_t i = 0; i < vertex_piece.size(); ++i) {
        const uint32_t p = vertex_piece[i];
        if (p < first || p > last) continue;
        const Vec3 r = x.segment<3>(3 * i) - C[p];
        L[p] += mass[3 * i] * r.cross(Vec3(v.segment<3>(3 * i)));
        I[p] += mass[3 * i] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
    }
    double Mt = 0;
    Vec3 Pt = Vec3::Zero();
    for (uint32_t p = first; p < pieces; ++p) {
        m.rigid += P[p].squaredNorm() / (2 * M[p]) + 0.5 * L[p].dot(I[p].ldlt().solve(L[p]));
        Mt += M[p];
        Pt += P[p];
    }
    const Vec3 Vt = Pt / Mt;
    for (uint32_t p = first; p < pieces; ++p) m.spread += 0.5 * M[p] * (P[p] / M[p] - Vt).squaredNorm();
    return m;
}

FemBeamResult run_fem_beam(uint32_t cells, double h, FemIntegrator integrator, double t_start, double t_end) {
    const auto t0 = std::chrono::steady_clock::now();
    FemBeamResult r;
    r.cells = cells;
    // The model frame of scenes/paper_scenes.h: x along the beam, centred; y up, lowest face on
    // y = 0; z centred. Piece 0 is x < 0.
    const Vec3 size(0.6, 0.03, 0.03);
    TetMesh mesh = box_tet_mesh(size, 20 * cells, cells, cells);
    for (Vec3& p : mesh.vertices) p += Vec3(-0.3, 0, -0.015);
    std::vector<uint32_t> tet_piece(mesh.tets.size());
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        double x = 0;
        for (uint32_t q : mesh.tets[t]) x += mesh.vertices[q].x() / 4;
        tet_piece[t] = x > 0 ? 1 : 0;
    }
    Interfaces in(split_pieces(mesh, tet_piece));
    r.tets = mesh.tets.size();
    r.ties = in.split().ties.size();
    FemSettings fs;
    fs.integrator = integrator;
    FemSolid solid(in.split().mesh, fs);
    in.apply(solid);
    // The study's beam scene (bench/study_scenes.cpp): posts and block keys, and the frictions of
    // its pairs: the beam's 0.4 against the ground's 0.3 and the posts' and block's 0.5.
    const SurfaceSettings prop;
    const double beam_friction = 0.4;
    ContactSettings cs;
    cs.ground_friction = pair_friction(beam_friction, 0.3);
    const double on_prop = pair_friction(beam_friction, prop.friction);
    const auto fixed = [](Vec3 c) { return [c](double) { return c; }; };
    cs.boxes.push_back({Vec3(0.02, 0.15, 0.02), fixed(Vec3(-0.2, 0.15, -0.0355)), on_prop});
    cs.boxes.push_back({Vec3(0.02, 0.15, 0.02), fixed(Vec3(0.2, 0.15, -0.0355)), on_prop});
    KinematicSettings block;
    block.shape.size = Vec3(0.08, 0.06, 0.06);
    block.keys = {{0, Vec3(0, 0.032, 0.1)}, {0.2, Vec3(0, 0.032, 0.046)}, {1.5, Vec3(0, 0.032, 0.02)}};
    cs.boxes.push_back({0.5 * block.shape.size, [block](double t) { return kinematic_position(block, t); }, on_prop});
    attach_contact(solid, cs);
    // Start at rest, undeformed, on the ground (it settles into the ground contact by m g / k,
    // micrometres, within the first milliseconds).
    solid.set_time(t_start);
    const Strength strength;  // 40 MPa
    PieceMotion before;
    double elastic_before = 0;
    bool have01 = false;
    while (solid.time() < t_end) {
        if (r.first_break < 0) {
            before = piece_motion(solid, in.split().vertex_piece, 0, in.split().pieces - 1);
            elastic_before = solid.elastic_energy();
        }
        solid.step(h);
        ++r.steps;
        if (!std::isfinite(solid.kinetic_energy())) break;
        if (in.break_overloaded(solid, strength) > 0) {
            if (r.first_break < 0) {
                r.first_break = solid.time();
                r.at_break = before;
                r.elastic_at_break = elastic_before;
                t_end = r.first_break + 0.5 + 0.5 * h;
            }
            r.last_break = solid.time();
        }
        if (r.first_break >= 0 && !have01 && solid.time() >= r.first_break + 0.1 - 0.5 * h) {
            r.at_01 = piece_motion(solid, in.split().vertex_piece, 0, in.split().pieces - 1);
            have01 = true;
        }
    }
    r.complete = std::isfinite(solid.kinetic_energy());
    if (r.first_break >= 0) r.at_05 = piece_motion(solid, in.split().vertex_piece, 0, in.split().pieces - 1);
    tally_run(in, solid, t0, r);
    return r;
}

}  // namespace shatter::fem
