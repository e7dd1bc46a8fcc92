// Repairing any triangle soup into a mesh Mesh_3 can fill: CGAL's 3D alpha wrapping
// (Portaneri, Rouxel-Labbé, Hemmer, Cohen-Steiner, Alliez, "Alpha Wrapping with an Offset",
// SIGGRAPH 2022; CGAL::alpha_wrap_3).
//
// The wrap is a new surface that encloses the input at distance `offset` and cannot pass
// through gaps narrower than about `alpha`: holes, cracks, self-intersections and non-manifold
// parts disappear. The price is shape: the result is inflated by about the offset and
// features smaller than alpha are filled. Measured (docs/physics.md): bunny, alpha = diag/50,
// offset = diag/1000: 1.5 s, +3.2% volume. Smaller alpha costs more time and more triangles.
#pragma once

#include "core/geometry.h"

namespace shatter {

// Wraps `soup` (any triangles: open, non-manifold, self-intersecting) into a closed,
// 2-manifold, outward-oriented triangle mesh. alpha: the narrowest gap the wrap can enter
// (unit: m, > 0; e.g. diagonal / 50); offset: the distance from the input to the wrap
// (unit: m, > 0; e.g. diagonal / 1000). Throws shatter::Error(BadInput) if alpha or offset is
// not finite and > 0, or the soup has no triangle with three distinct vertices.
TriangleMesh alpha_wrap(const TriangleMesh& soup, double alpha, double offset);

}  // namespace shatter
