// Faired cracks: the surface between two pieces drawn as a gently curved crack through the tets
// instead of the zigzag of tet faces it is made of (render surfaces only: the tets, and so the
// mass, collision parts and constraints, do not change).
//
// A smoothed piece field. Every tet-mesh vertex v gets a weight per piece,
//
//     chi_p(v) = sum over tets t of p near v of vol(t) G(|c_t - v|) / sum over all of them,
//     G(d) = exp(-d^2 / (2 sigma^2)),
//
// the share of piece p in a Gaussian neighbourhood of v (c_t: the tet's centre; the tets
// reached from v's own through their faces, so not across a gap, within 2 sigma), so that
// sum_p chi_p = 1. sigma is `width` mean tet edges: the tet-size zigzag of the interfaces is
// averaged out, a piece's extent stays. Inside a tet chi is linear (the vertices' values
// interpolated), and a point belongs to the piece whose chi is largest there (ties to the lower
// piece). So piece p's part of a tet is the convex polyhedron
//
//     { x in the tet : chi_p(x) >= chi_q(x) for every other piece q },
//
// the tet clipped by the planes chi_p = chi_q, and the crack between p and q is made of the
// polygons on those planes: planar within a tet, continuous across tets (chi is), smooth at the
// scale of sigma (the split tets below are tets here too). The smoothing moves volume from small
// and thin pieces to their neighbours (on the demo two pieces kept 3% and 14% of their tets'
// volume), so each piece's field is then
// scaled, chi_p -> s_p chi_p (still linear in a tet: nothing below changes), to fit its cell's
// volume to its tets': up to `fit_rounds` rounds, each multiplying s_p by the square root of
// (tets' volume / cell's), by at most e^0.4, for the pieces off by more than `fit_tolerance` (two
// rounds: each costs an arrangement, and on the demo, the cat and the horse more rounds left the
// cracks no smoother, docs/log.md). A
// piece that still keeps less than `keep` of its tets' volume is cut again with the field around
// it smoothed over sigma / 2, then sigma / 4, and last with the vertices inside it (whose tets are
// all its own) its alone, so that its cracks stay within the tets that touch them.
//
// Planar within a tet, the crack bends at the tets' faces, by the linear interpolation's error in
// chi's direction, which grows with the tet's size over sigma (and with its flatness). With
// `split_tets` (`[prescore] crack_split`; off by default for its cost) the last cut is made on the
// crack tets split 1:8 (crack_refinement.h): the tets where the largest piece is
// not the same at all four vertices or leads the next by less than 0.1 (0.05 left more of the crack
// tets' midpoints linear and bent the crack around a ball more, 0.2 and 0.4 gave the demo the same
// creases), each into eight at its edges' midpoints, where chi is the Gaussian sum itself at the
// midpoint's place (but a split edge of a whole tet gets the mean of its ends', so that a face
// between a split tet and a whole one is linear on both sides). The planes then span half a tet,
// and the bends between the crack's triangles halve (the demo's faired cells: creases within one
// interface 4.0 -> 1.9 by crack_creases.h's measure, docs/log.md). A midpoint is half of each of
// its ends, so every point's weights are still over the vertices of one tet of the mesh, and
// `place` follows any placement. The cut after the fit's last round is made on the split tets
// straight away, and its volumes decide the holds (a piece held is then cut again, on split tets
// too): the split cells keep their tets' volume as the whole ones do, and an arrangement of the
// whole tets first would be one more; when the fit settles earlier, its field is cut again on the
// split tets.
//
// Both sides of a crack are the same points. Each point of the arrangement is named by what
// defines it: the smallest tet-mesh simplex that holds it (a vertex, an edge, a face or a tet, by
// its sorted vertex ids) and the pieces tied there (as many as the simplex has vertices: two on
// an edge, three on a face, four inside a tet). Its weights over that simplex's vertices come
// from the name alone (solving sum w = 1, sum w_i (chi_l0 - chi_lj)(v_i) = 0), and every side
// test at it is made with its lowest tied piece: every tet and every piece that meets the point
// computes the same weights and takes the same decisions, so the pieces' cells share their crack
// polygons exactly and close up across tets. A crack polygon is split into triangles from its
// lowest-numbered point, which gives both sides the same triangles.
//
// Positions come last (`place`): a point is its weights times the vertices' positions, so the
// cells can be built for any placement of the tet vertices (render surfaces push the outer ones
// out by a margin) and follow it. Deterministic: tets in order (a split tet's eight in its
// place), pieces ascending, points numbered in first use, no hashing, one thread.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/geometry.h"
#include "core/model.h"
#include "prescore/tet_topology.h"

namespace shatter {

// Pieces of fewer tets than this on average are not faired (render surfaces keep the tet faces
// between them): a smoothing over 1.5 tet edges is most of such a piece, and many small pieces
// meet in tets shared by three or more, where cells can be left open (`CrackCells::open`).
inline constexpr size_t kCrackFairingTetsPerPiece = 100;

struct CrackFairingSettings {
    double width = 1.5;           // sigma, the field's smoothing (unit: mean tet edges)
    int fit_rounds = 2;           // most rounds of the volume fit (0: none)
    double fit_tolerance = 0.05;  // a cell within this share of its tets' volume is left as it is
    double keep = 0.75;           // least share of its tets' volume a piece's cell keeps before it is held
    bool split_tets = false;      // the last cut on the crack tets split 1:8 (crack_refinement.h)
};

// A point of the arrangement: weights over up to four tet-mesh vertices (ascending ids).
struct CrackPoint {
    std::array<uint32_t, 4> vertex{};
    std::array<double, 4> weight{};
    uint8_t count = 0;
};

// The pieces' cells cut from the tets by the smoothed field: per piece, closed and outward as its
// tets' surface is, its faces on the object's boundary (kind Outer or Cavity, as the tet face
// they lie on) and on the cracks (Fracture).
struct CrackCells {
    std::vector<CrackPoint> points;
    std::vector<std::vector<Tri>> triangles;    // per piece, indices into points
    std::vector<std::vector<FaceKind>> kinds;   // per piece, per triangle
    std::vector<std::vector<uint32_t>> across;  // per piece, per triangle: the piece on a crack's other side, else UINT32_MAX
    size_t degenerate = 0;   // points their name did not fix (placed within their tet alone; 0 on every model seen)
    size_t cut_tets = 0;     // tets shared by more than one piece's cell
    size_t fit_rounds = 0;   // rounds of the volume fit run
    size_t held = 0;         // pieces cut again, held (`keep`)
    size_t split_tets = 0;   // tets split 1:8 for the last cut (`split_tets`)
    size_t open = 0;         // cells that do not close (a tet shared by three or more pieces can leave one
                             // open; render surfaces then keep the tet cells for every piece)

    // The points placed with the tet-mesh vertices at `vertices`.
    std::vector<Vec3> place(const std::vector<Vec3>& vertices) const;
};

// `face_kind[t][i]`: what face i of tet t is when it is on the boundary (Outer or Cavity).
CrackCells crack_cells(const TetMesh& mesh, const TetTopology& topology, const std::vector<uint32_t>& tet_piece,
                       const std::vector<std::array<FaceKind, 4>>& face_kind, const CrackFairingSettings& settings = {});

// The faired cracks roughened: every point of `cells` on a crack (`placed`: its positions, as
// CrackCells::place gives them) moves by `amplitude` times crack_relief at its place, faded in
// over one wavelength from the object's boundary (times the distance to the nearest boundary
// point over `wavelength`, at most 1); boundary points stay. The move is a smooth function of
// position, so nearby points move alike and the cells, whose points can lie a hundredth of a tet
// apart, do not fold unless the relief is steep for its wavelength (moving each point along its
// own normal folded them at a tenth of a tet); the two sides of a crack are the same points, so
// they stay one surface.
void roughen_cracks(const CrackCells& cells, std::vector<Vec3>& placed, double amplitude, double wavelength,
                    uint64_t seed);

// The relief at `x`: three channels of gradient noise of `wavelength` plus one of half of it at
// half the height (each seeded, in [-1, 1]) over the square root of 3, so its length is at most 1.
Vec3 crack_relief(const Vec3& x, double wavelength, uint64_t seed);

// The mean length of the tets' edges (unit: m).
double mean_tet_edge(const TetMesh& mesh);

}  // namespace shatter
