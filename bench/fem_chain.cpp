// The study's chain on the continuum reference (bench/fem_chain.h).
#include "bench/fem_chain.h"

#include <chrono>
#include <cmath>

#include "bench/fem_box_mesh.h"
#include "bench/fem_contact.h"
#include "bench/fem_interfaces.h"

namespace shatter::fem {

FemChainResult run_fem_chain(uint32_t cells, double h, double h_after, double after, double t_end) {
    const auto t0 = std::chrono::steady_clock::now();
    FemChainResult r;
    r.cells = cells;
    const uint32_t links = 10;
    const double link = 0.03, side = 0.01, cell = side / cells, drive_speed = 0.03 / 2.7;
    const FemMaterial porcelain{2400, 70e9, 0.22};
    const Strength strength;  // 40 MPa
    // The model frame of scenes/paper_scenes.h's chain: x along the chain, centred; links on
    // y = 0; z centred. One box from the left cube's slab to the right's.
    const uint32_t along = links * 3 * cells + 2;
    TetMesh mesh = box_tet_mesh(Vec3(links * link + 2 * cell, side, side), along, cells, cells);
    for (Vec3& p : mesh.vertices) p += Vec3(-0.5 * links * link - cell, 0, -0.5 * side);
    std::vector<uint32_t> tet_piece(mesh.tets.size());
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        double x = 0;
        for (uint32_t q : mesh.tets[t]) x += mesh.vertices[q].x() / 4;
        const double u = (x + 0.5 * links * link) / link;  // in links from the chain's left end
        tet_piece[t] = u < 0 ? 0 : u > links ? links + 1 : uint32_t(u) + 1;
    }
    Interfaces in(split_pieces(mesh, tet_piece));
    const SplitMesh& split = in.split();
    r.tets = mesh.tets.size();
    r.ties = split.ties.size();
    FemSettings fs;
    fs.material = porcelain;
    fs.integrator = FemIntegrator::BackwardEuler;
    FemSolid solid(split.mesh, fs);
    std::vector<uint32_t> left, right;
    for (uint32_t v = 0; v < split.vertex_piece.size(); ++v) {
        if (split.vertex_piece[v] == 0) left.push_back(v);
        if (split.vertex_piece[v] == links + 1) right.push_back(v);
    }
    solid.drive(left, Vec3(-drive_speed, 0, 0));
    solid.drive(right, Vec3(drive_speed, 0, 0));
    in.apply(solid);
    ContactSettings cs;
    cs.ground_friction = 0.5;  // the links' 0.5 on the ground's 0.5 (simulate/surface_pair.h)
    attach_contact(solid, cs);
    // Still until 0.3 s (the links at rest on the ground, undeformed), then driven apart.
    const double t_start = 0.3;
    solid.set_time(t_start);
    r.predicted_break = t_start + strength.tensile * links * link / (porcelain.young * 2 * drive_speed);
    double elastic_before = 0, middle_before = 0, predicted_before = 0;
    bool have01 = false;
    r.joint_break_time.assign(links + 1, -1.0);
    while (solid.time() < t_end - 0.5 * h) {
        if (r.first_break < 0) {
            elastic_before = solid.elastic_energy();
            middle_before = 0;
            for (size_t i = 0; i < split.ties.size(); ++i)
                if (split.ties[i].piece_a == links / 2) {
                    double sigma, tau;
                    in.traction(solid, i, sigma, tau);
                    middle_before += sigma * split.ties[i].area;
                }
            predicted_before = porcelain.young * side * side * 2 * drive_speed * (solid.time() - t_start) / (links * link);
        }
        const bool late = r.first_break >= 0 && solid.time() > r.first_break + 0.01;
        solid.step(late ? h_after : h);
        ++r.steps;
        if (!std::isfinite(solid.kinetic_energy())) break;
        if (in.break_overloaded(solid, strength) > 0) {
            if (r.first_break < 0) {
                r.first_break = solid.time();
                r.elastic_at_break = elastic_before;
                r.middle_force_at_break = middle_before;
                r.middle_force_predicted = predicted_before;
                t_end = std::min(t_end, r.first_break + after + 0.5 * h);
            }
            r.last_break = solid.time();
        }
        if (r.first_break >= 0 && !have01 && solid.time() >= r.first_break + std::min(0.1, after) - 0.5 * h) {
            r.at_01 = piece_motion(solid, split.vertex_piece, 1, links);
            have01 = true;
        }
    }
    r.complete = std::isfinite(solid.kinetic_energy());
    r.at_05 = piece_motion(solid, split.vertex_piece, 1, links);
    for (uint32_t j = 0; j <= links; ++j) {
        bool all = true;
        double last = -1;
        for (const Tie& t : split.ties)
            if (t.piece_a == j && t.piece_b == j + 1) {
                all = all && t.broken;
                last = std::max(last, t.break_time);
            }
        if (all) {
            r.joints_broken.push_back(int(j));
            r.joint_break_time[j] = last;
            if (r.first_separation < 0 || last < r.first_separation) r.first_separation = last;
        }
    }
    tally_run(in, solid, t0, r);
    return r;
}

}  // namespace shatter::fem
