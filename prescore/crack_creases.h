// How creased the crack faces of render surfaces are: per piece, its Fracture triangles welded by
// position (equal coordinates: one vertex); an edge with exactly two of them is an inner edge of
// the crack, and a crease when their normals differ by more than `degrees`.
//
//   density  the creases' length per unit of crack area, times the object's diagonal: about
//            4 x (diagonal / tet size) x share for cracks of tet facets, 0 for planes;
//   share    the fraction of inner edges that are creases.
//
// scripts/crack_creases.py measures the same from a run's .glb (its "fracture" materials);
// docs/render.md ("Faired cracks") has the figures. Degenerate triangles (area below 1e-12 of the
// diagonal squared) have no normal: their edges count in neither.
#pragma once

#include <cstddef>
#include <vector>

#include "core/model.h"

namespace shatter {

struct CrackCreases {
    double area = 0;          // the crack faces' area, both sides (unit: m^2)
    double crease_length = 0; // (unit: m)
    size_t inner_edges = 0;
    size_t creases = 0;
    double density = 0;       // crease_length / area x diagonal
    double share = 0;         // creases / inner_edges
};

CrackCreases crack_creases(const std::vector<RenderSurface>& surfaces, double diagonal, double degrees = 30);

}  // namespace shatter
