// Checking a triangle mesh before it is tetrahedralized: topology (boundary, non-manifold and
// misoriented edges, non-manifold vertices, components), degeneracies, self-intersections, and
// measures (volume, area, bounding box).
//
// Definitions (edges are undirected vertex pairs; triangles with a repeated vertex index are
// counted as degenerate and left out of every topological count):
//   boundary edge        used by exactly one triangle;
//   non-manifold edge    used by more than two triangles;
//   misoriented edge     used by exactly two triangles that traverse it in the same direction;
//   non-manifold vertex  its incident triangles fall into more than one fan, a fan being a set
//                        of triangles around the vertex joined through edges at that vertex;
//   component            a set of triangles joined through shared edges;
//   degenerate triangle  a repeated vertex index, or zero area: |(b-a)x(c-a)| <= 1e-12 times
//                        the squared longest edge (the area is zero to rounding);
//   self-intersection    a pair of triangles that meet other than in the vertices and edge they
//                        share (counted with CGAL, self_intersections_cgal.cpp).
// The volume is the divergence-theorem sum of signed tet volumes (origin, a, b, c): exact for
// a closed, outward-oriented mesh, negative for an inside-out one.
#pragma once

#include <cstddef>
#include <string>

#include "core/geometry.h"

namespace shatter {

struct MeshCheck {
    size_t vertices = 0;
    size_t triangles = 0;
    size_t boundary_edges = 0;        // edges of one triangle
    size_t nonmanifold_edges = 0;     // edges of more than two triangles
    size_t nonmanifold_vertices = 0;  // incident triangles are not one edge-connected fan
    size_t degenerate_triangles = 0;  // repeated index or zero area
    size_t misoriented_edges = 0;     // two triangles traverse it in the same direction
    size_t components = 0;            // edge-connected sets of triangles
    size_t self_intersections = 0;    // intersecting triangle pairs (0 when not searched)
    double volume = 0;                // (unit: m^3) signed, divergence theorem
    double area = 0;                  // (unit: m^2)
    Vec3 bbox_min = Vec3::Zero();     // (unit: m)
    Vec3 bbox_max = Vec3::Zero();     // (unit: m)
    double diagonal = 0;              // |bbox_max - bbox_min| (unit: m)

    bool closed() const { return triangles > 0 && boundary_edges == 0; }
    bool manifold() const { return nonmanifold_edges == 0 && nonmanifold_vertices == 0; }
    bool oriented() const { return misoriented_edges == 0; }
};

// Measures `mesh`. Self-intersections cost ~0.1-0.2 s for 70k triangles; pass false to skip
// them (MeshCheck::self_intersections stays 0).
MeshCheck check_mesh(const TriangleMesh& mesh, bool find_self_intersections = true);

// The diagonal of the box around every vertex of `mesh` (MeshCheck::diagonal), without the rest
// of the check (whose edge sort takes seconds on millions of triangles); 0 for no vertices.
double bounding_diagonal(const TriangleMesh& mesh);

// Number of intersecting triangle pairs (CGAL::Polygon_mesh_processing::self_intersections).
// Degenerate triangles are not counted here (check_mesh counts them).
size_t count_self_intersections(const TriangleMesh& mesh);

// One line for people, e.g. "34835 vertices, 69666 triangles, closed, manifold, oriented,
// 1 component, 2 self-intersecting pairs, volume 0.0123 m^3, bbox 0.31 x 0.30 x 0.24 m".
std::string describe(const MeshCheck& check);

// Flips every triangle when the mesh's total signed volume is negative (an inside-out file).
// The whole mesh is flipped, not each component, so that a hollow object's inner shell (whose
// volume is negative by design) keeps its orientation relative to the outer shell. True when it
// flipped them.
bool orient_outward(TriangleMesh& mesh);

// A z-up file's points turned to shatter's y-up world ([mesh] up): (x, y, z) -> (x, z, -y), -90
// degrees about x, exactly (no rounding).
void stand_up(std::vector<Vec3>& points);

// True when Mesh_3 can fill the mesh with tets: closed, manifold, oriented, volume > 0 and no
// degenerate triangles. Otherwise false, and *why (if not null) says what is wrong and what to
// do (usually: repair with alpha_wrap). Self-intersections alone do not block: Mesh_3's
// polyhedral domain decides inside/outside by counting ray crossings through an AABB tree and
// only samples the surface, so a few crossing triangles (the bunny has two pairs) just make the
// surface locally ambiguous by at most their overlap. A heavily self-intersecting mesh still
// meshes, but badly; alpha_wrap it first.
bool can_tetrahedralize(const MeshCheck& check, std::string* why);

// A sheet: all points in a plane, or a closed surface that encloses nothing (a plane's two sides).
// Mesh_3 finds no inside; the repair wraps it (a sheet of twice the offset), and adapt then gives
// the walls a thickness the tets resolve (prescore/adapt.h), as it does for any thin wall. *why
// says so when it is one.
bool is_sheet(const MeshCheck& check, std::string* why);

// Self-intersecting pairs a mesh may have and still go to Mesh_3 as it is: 1% of its triangles
// (at least 8). A few crossing triangles (the bunny has two pairs) only blur the surface locally;
// many make Mesh_3 refine around the crossings without end.
size_t max_self_intersections(const MeshCheck& check);

// Whether prescore gives the mesh to Mesh_3 as it is, from its check (`input`, with its
// self-intersections searched) and the check of it turned outward (`oriented`: orient_outward
// changes only the volume's sign). Not a sheet, can_tetrahedralize, and (with `count_crossings`)
// no more crossing pairs than max_self_intersections. Else false, and *why says what the repair
// (alpha wrapping) is for.
bool meshes_as_it_is(const MeshCheck& input, const MeshCheck& oriented, bool count_crossings, std::string* why);

}  // namespace shatter
