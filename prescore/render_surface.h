// Render surfaces: what a piece looks like, apart from what it simulates with (its tets, mass
// and collision parts). The input surface cut along the pieces' fracture faces:
//
//   cell     per piece, its tet boundary with every vertex on the object's outer boundary
//            pushed outward by `margin` along that vertex's outer normal (area-weighted over the
//            outer tet faces around it, the same for every piece that shares the vertex, so the
//            cells still meet face to face and tile the pushed-out tet volume); with faired
//            cracks (the default, crack_fairing.h) the cells are cut from the tets by a smoothed
//            piece field instead, the same points placed from the same pushed vertices, so that
//            neighbouring cells still share their crack faces exactly;
//   cut      CGAL's corefine_and_compute_intersection(input, cell) (exact predicates): the
//            input's faces inside the cell keep the input's vertices and smooth normals (creases
//            sharper than `crease_degrees` stay sharp); the cell's faces inside the input are
//            the piece's fracture and cavity faces, flat, with the cell face's kind;
//   fallback a piece whose cell does not bound a volume, self-intersects, or whose cut fails
//            or comes out empty keeps its cell, unpushed, as its surface (its tet surface, flat
//            normals; with faired cracks all pieces are made again from the tet faces first);
//   input    when the surface cut is an alpha wrap of the input, the outer faces are then
//            replaced by the input's own triangles (use_input_faces, below).
//
// The margin must exceed the largest distance from the input to the tet boundary, or the
// input's parts beyond it are lost (the pushed cell's own faces then show there, flat, as
// Outer); a large one folds cells over in concave parts. It is tried at 1, 0.7, 0.5 and 0.35
// times `margin`, keeping the first at which every cell is closed and free of
// self-intersections (else the one with the fewest bad cells). 0.15 tet sizes suits the demo. Deterministic: the pieces are cut on every core (core/workers.h), each on its own, output in CGAL's face order, vertices in first use.
// docs/render.md, "Render surfaces", gives the measurements.
#pragma once

#include <optional>
#include <vector>

#include "core/geometry.h"
#include "core/model.h"
#include "prescore/crack_fairing.h"

namespace shatter {

// What prescore uses (docs/render.md, "Render surfaces"): the margin in tet sizes (diagonal /
// resolution), and two budgets. Drawing: a surface of more than kRenderSurfaceTriangles is
// simplified to that many first (edge collapse), so that render keeps its frame rate (llvmpipe
// pays per triangle, in the shadow and the scene pass). The cut: each piece's cut corefines the
// whole surface, so its work grows as pieces x surface triangles (measured ~2 us per triangle
// and piece on the demo: 10 x 69,666 in 1.4 s): the surface is simplified further for many
// pieces, to what keeps pieces x triangles within kRenderSurfaceWork (about 8 s), but not below
// kRenderSurfaceFewest; beyond that the pieces keep their tet surfaces. CGAL's simplification
// costs ~20 us per triangle removed (2 million to 200,000 triangles: 41 s): a surface over
// kRenderSurfaceSimplifyLimit is first reduced to kRenderSurfaceReduced by meshoptimizer's (1.3 s
// for those 2 million), whose touching sheets and crossings simplify_surface mends. The
// simplification and the cut each run in a child process (core/isolated.h) with a deadline of
// kRenderSurfaceSeconds plus both's expected time: a crash inside CGAL (its repair of crossings
// is experimental) or a run past it leaves every piece its tet surface, noted as a choice.
inline constexpr double kRenderSurfaceMargin = 0.15;          // (unit: tet sizes)
inline constexpr double kRenderSurfaceSeconds = 20;           // (unit: s)
inline constexpr size_t kRenderSurfaceTriangles = 12000;      // most surface triangles cut
inline constexpr double kRenderSurfaceWork = 4e6;             // pieces x surface triangles
inline constexpr size_t kRenderSurfaceFewest = 1000;          // fewest kept for many pieces
inline constexpr size_t kRenderSurfaceSimplifyLimit = 500000; // larger surfaces are first reduced (reduce_surface)
inline constexpr size_t kRenderSurfaceReduced = 200000;       // to this many triangles
inline constexpr double kRenderSurfaceQuickFactor = 2.5;      // simplify_surface: meshoptimizer's down to this x the count

// The triangles a surface of `surface_triangles` is cut with for `pieces` pieces: at most
// kRenderSurfaceTriangles, fewer where that many pieces would pass kRenderSurfaceWork, but not
// fewer than kRenderSurfaceFewest (the work is then over the budget: tet surfaces).
size_t render_surface_triangles(size_t pieces, size_t surface_triangles);

// `surface` (closed, outward) with at most `max_triangles` triangles: meshoptimizer's edge
// collapse (reduce_surface) down to kRenderSurfaceQuickFactor x max_triangles, then CGAL's
// (Lindstrom-Turk), deterministic. CGAL's costs ~20 us per triangle removed, meshoptimizer's ~1
// us; but meshoptimizer keeps input vertices where CGAL places new ones, and all the way down it
// misses the input by more (glmark2's bunny at 12,000 triangles: p99 distance 0.075% of the
// diagonal against CGAL's 0.046%). Handed over at 3, 2.5, 2 and 1.5 times the count: 0.047,
// 0.0475, 0.0505 and 0.059% (the looks' tolerance is 0.05%) in 0.50, 0.43, 0.34 and 0.25 s, which
// is prescore's longest branch beside the check and the tets. Sheets that touch along an edge or
// at a vertex get their own copies of the shared vertices first (a border that leaves is closed
// with a patch); a result that crosses itself is repaired (CGAL's remove_self_intersections).
// Returned as it is when already within, or when it is not a closed polygon mesh.
TriangleMesh simplify_surface(const TriangleMesh& surface, size_t max_triangles);

// `surface` with at most `max_triangles` triangles, by meshoptimizer's edge collapse (quadric
// error: seconds for millions of triangles, where CGAL's takes minutes); the vertices it keeps,
// in their first use's order. It may stop short of the count (a vertex on a border or a seam is
// not moved). It checks neither manifoldness nor crossings: triangles it folds onto each other
// (two on the same three vertices) are dropped here; sheets it leaves touching along an edge and
// triangles that cross are left to simplify_surface. The first cut of a surface too large for
// simplify_surface.
TriangleMesh reduce_surface(const TriangleMesh& surface, size_t max_triangles);

// The first cut a surface gets before simplify_surface: reduce_surface to kRenderSurfaceReduced
// triangles when it has more than kRenderSurfaceSimplifyLimit; nullopt when it needs none.
std::optional<TriangleMesh> first_reduction(const TriangleMesh& surface);

struct RenderSurfaceSettings {
    double margin = 0;              // how far outer cell vertices move out, at most (unit: m); > 0
    double crease_degrees = 40;     // input edges with a dihedral angle above this stay sharp (unit: degrees)
    bool fair_cracks = true;        // cells from the tet vertices with the cracks faired (crack_fairing.h)
    bool split_cracks = false;      // their last cut on the crack tets split 1:8 (CrackFairingSettings::split_tets)
    double roughness = 0;           // the faired cracks' relief: amplitude (unit: m; 0: none)
    double roughness_scale = 1;     // and wavelength (unit: m)
    uint64_t roughness_seed = 1;
};

// The cells of the faired cracks between `model`'s pieces (crack_fairing.h); none when its
// pieces have fewer than kCrackFairingTetsPerPiece tets on average (logged).
// `split`: CrackFairingSettings::split_tets.
std::optional<CrackCells> faired_crack_cells(const Model& model, bool split);

// One render surface per model piece; `input` is the closed, outward surface the tets were
// made from (the alpha wrap when prescore wrapped the input).
// `retry`, when given, is the surface `input` was simplified from: a piece whose cut fails on
// `input` is cut again from it (a simplified surface may cross itself where it is cut).
// `faired`, when given, is faired_crack_cells(model), made beforehand (else it is made here,
// when settings.fair_cracks, beside the cut's index of `input`).
std::vector<RenderSurface> render_surfaces(const TriangleMesh& input, const Model& model,
                                           const RenderSurfaceSettings& settings,
                                           const TriangleMesh* retry = nullptr,
                                           const std::optional<CrackCells>* faired = nullptr);

// An input that prescore alpha-wrapped for its tets (open, crossing itself, an assembly of
// parts) and did not thicken: the wrap, cut as above, gives the pieces their fracture and cavity
// faces, and the input's own triangles their outer faces, so that the pieces show the input's
// detail instead of the wrap's (which bridges every gap narrower than its alpha and lies `offset`
// outside the input). Each input triangle goes to the piece whose tet holds its centre (outside
// every tet: the piece of the nearest boundary face of the tets); one whose corners lie in other
// pieces than its centre is split in four at its edges' midpoints, down to kInputFaceSplit tet
// sizes, level by level over all triangles while the parts number at most kInputFaceBudget times
// the input's triangles (or kRenderSurfaceTriangles, if more), so a piece's outer faces end within
// about that of its fracture faces. `double_sided` (an input that is not closed, whose triangles
// may face either way) adds every outer triangle turned over, with its normals negated: both
// sides are drawn and lit. The fracture and cavity faces end on the wrap, outside the input: the
// vertices they share with the wrap's outer faces move `rim_inset` (unit: m; a few times the
// wrap's offset) in along the wrap's normal, so that the intact object shows no seams. A piece
// that no input triangle lies in keeps its surface as it was. `only`, when given (one flag per
// piece), limits all this to the pieces flagged: the others keep their surfaces (prescore gives a
// closed input's triangles to the pieces whose cut failed, instead of their tet surfaces).
// Deterministic: input order, one thread.
inline constexpr double kInputFaceSplit = 0.25;  // smallest split triangle (unit: tet sizes)
inline constexpr size_t kInputFaceBudget = 3;     // most parts per input triangle (or per kRenderSurfaceTriangles)
inline constexpr double kInputFaceRimInset = 3;   // how far the fracture faces' rims move in (unit: wrap offsets)
// An input still over this many triangles after reduce_surface (which moves no vertex on a border
// or on an edge of three triangles: an assembly of many open parts may stay large) keeps the
// wrap's outer faces, so that render's cost stays bounded (prescore.cpp).
inline constexpr size_t kInputFaceMostTriangles = 60000;

struct InputFacesReport {
    size_t pieces = 0;  // pieces whose outer faces are now the input's
    size_t kept = 0;    // pieces no input triangle lies in (their surface unchanged)
    size_t split = 0;   // triangles split in four
    size_t leaves = 0;  // input triangles and split parts placed (each twice when double-sided)
};

InputFacesReport use_input_faces(std::vector<RenderSurface>& surfaces, const TriangleMesh& input, const Model& model,
                                 double tet_size, double crease_degrees, bool double_sided, double rim_inset,
                                 const std::vector<char>* only = nullptr);

// The piece's tet surface as a render surface: flat, three vertices per triangle.
RenderSurface flat_render_surface(const PieceSurface& surface);

// Per-corner normals of `mesh` that are smooth across edges whose faces differ by less than
// `crease_degrees` (area-weighted face normals); corner k of triangle t at [3 t + k].
std::vector<Vec3> corner_normals(const TriangleMesh& mesh, double crease_degrees);

}  // namespace shatter
