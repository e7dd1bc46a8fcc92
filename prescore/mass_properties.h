// Mass properties of a set of tets of uniform density, integrated exactly.
//
// For a tet with vertices v0..v3 (relative to a reference point), volume V and s = v0+v1+v2+v3:
//   integral of x dV     = V s / 4
//   integral of x x^T dV = V/20 (sum_i v_i v_i^T + s s^T)            (the covariance C)
// and the inertia tensor of a body with covariance C (about the centre of mass) and density rho is
//   I = rho (trace(C) Id - C).
// Sums are taken relative to the first vertex of the first tet to avoid cancellation far from
// the origin, then shifted to the centre of mass (parallel-axis theorem on C: C_c = C - V d d^T).
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry.h"
#include "core/model.h"

namespace shatter {

// Volume (m^3), mass (kg), centre of mass (m) and inertia about the centre of mass in model axes
// (kg m^2) of mesh.tets[t] for t in `tets`, at `density` (kg/m^3, finite and > 0; otherwise an
// input Error). An empty `tets` gives all zeros.
MassProperties mass_properties(const TetMesh& mesh, const std::vector<uint32_t>& tets, double density);

}  // namespace shatter
