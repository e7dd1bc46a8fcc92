// Filling a closed surface with tetrahedra: CGAL Mesh_3 (Delaunay refinement; Jamin, Alliez,
// Yvinec, Boissonnat, "CGALmesh: a generic framework for Delaunay mesh generation", ACM TOMS
// 2015) over a Polyhedral_mesh_domain_with_features_3: edges sharper than feature_angle are
// protected (sampled first and kept exact), so a box keeps its corners and its volume.
//
// Determinism: sequential refinement, the domain's fixed random seed (CGAL::Random(0)), and no
// optimisation passes (no Lloyd, ODT, perturb or exude: the default perturb/exude changed the
// tet count from run to run). The same mesh and settings give byte-identical output.
//
// Mesh_3 starts from points where rays shot from the centre of the surface's bounding box meet
// it. When those give it no facet to start from (a thin flat wall whose box's centre lies outside
// it: a frame around a hole, a concave plate, once given a thickness), it runs once more from
// points taken on up to 64 of the surface's faces, spread over it.
//
// The sizes are Mesh_3's: cell_size bounds each tet's circumradius, facet_size bounds the radius
// of each boundary facet's surface Delaunay ball, facet_distance bounds the distance between a
// boundary facet's circumcentre and the input surface.
#pragma once

#include <cstddef>

#include "core/error.h"
#include "core/geometry.h"

namespace shatter {

struct TetBudgetReached : Error {
    using Error::Error;
};

struct TetrahedralizeSettings {
    double cell_size = 0;               // max tet circumradius (unit: m, > 0)
    double facet_size = 0;              // max boundary-facet Delaunay-ball radius (unit: m, > 0)
    double facet_distance = 0;          // max boundary-facet distance to the surface (unit: m, > 0)
    double facet_angle = 25;            // min boundary-facet angle (unit: degrees, in (0, 30])
    double cell_radius_edge_ratio = 3;  // max tet circumradius / shortest edge (unitless, >= 2)
    double feature_angle = 60;          // creases whose face normals differ by more are kept exact (unit: degrees)
    double feature_min_length = 0;      // shorter creases are not protected (unit: m; the cell size applies too)
    bool protect_features = true;       // protect the sharp creases (false: follow the surface only)
    size_t max_vertices = 0;            // Mesh_3 stops at this many vertices and the call throws (0: no bound)
};

// The default resolution: the bunny (docs/physics.md) gets a few thousand tets. Measured on the
// glmark2 bunny (scale 1, diagonal 3.21 m; 2-core machine, times include building the domain):
//   R = 10: 929 tets, 0.08 s, volume -4.1%      R = 40: 16,339 tets, 0.25 s, -0.8%
//   R = 20: 3,323 tets, 0.13 s, -1.8%           R = 76: 98,406 tets, 1.2 s, -0.3%
//   R = 80: 113,890 tets, 1.3 s, -0.3%  (volume: tets' sum against the surface's)
constexpr double kDefaultTetResolution = 20;

// Settings for a mesh of bounding-box diagonal `diagonal` (unit: m) at resolution R
// (unitless, > 0): cell_size = facet_size = diagonal / R, facet_distance = cell_size / 10 (the
// surface is followed to a tenth of a cell), facet_angle 25, radius-edge ratio 3.
TetrahedralizeSettings tetrahedralize_settings_for(double diagonal, double resolution);

// Fills `closed_mesh` (closed, manifold, outward-oriented; see can_tetrahedralize) with tets.
// Output: only the cells inside the domain; vertices numbered in order of first use by the
// tets; every tet with tet_volume > 0. Throws shatter::Error(BadInput) for invalid settings, a
// mesh that is not a closed manifold surface, or a result without tets (the mesh is too thin
// for the cell size), and Error(Budget) when Mesh_3 reaches settings.max_vertices (a
// self-intersecting or very detailed surface can make its refinement run without end): then it
// throws TetBudgetReached, an Error(BadInput) that callers may catch to try another surface.
TetMesh tetrahedralize(const TriangleMesh& closed_mesh, const TetrahedralizeSettings& settings);

}  // namespace shatter
