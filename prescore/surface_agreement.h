// How closely render surfaces follow the input surface: distances from the input's vertices to
// the nearest render triangle, and on the input's smooth part (vertices whose faces all lie
// within `crease_degrees` of their mean normal) the angle between the input's vertex normal and
// the render surface's interpolated normal at that nearest point. Implementation:
// surface_agreement_cgal.cpp (a CGAL AABB tree, its own translation unit).
#pragma once

#include <vector>

#include "core/geometry.h"
#include "prescore/render_surface.h"

namespace shatter {

struct SurfaceAgreement {
    size_t samples = 0;            // input vertices
    double distance_p99 = 0;       // 99th percentile of the distances (unit: m)
    double distance_max = 0;       // (unit: m)
    size_t smooth_samples = 0;     // input vertices on the smooth part
    double normals_within = 0;     // share of those whose normal is within `normal_degrees`
};

SurfaceAgreement surface_agreement(const TriangleMesh& input, const std::vector<RenderSurface>& surfaces,
                                   double crease_degrees, double normal_degrees);

}  // namespace shatter
