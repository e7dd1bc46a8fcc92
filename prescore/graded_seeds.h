// The density of seeds that grades the pieces by the impact (prescore/partition.h uses it):
//
//   w(d) = 1 + (ratio - 1) exp(-(d / radius)^2)
//
// d the distance of a tet's centroid from the nearest contact point that grades (model frame):
// `ratio` times the far density at the contact, falling to it over a few radii. With the
// partition's growth following the same density, a piece near the contact comes out about
// 1 / ratio of the volume of one far from it.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "core/geometry.h"
#include "core/scene_settings.h"
#include "core/settings.h"
#include "prescore/adapt.h"
#include "prescore/impact.h"
#include "prescore/tet_topology.h"

namespace shatter {

std::vector<double> impact_density(const TetMesh& mesh, const std::vector<Vec3>& contacts, double ratio,
                                   double radius);

// seeds = "impact": the object's first contacts in the shot's scene (impact.h) and the density
// they give each tet. Without a contact that closes (nothing hit within the horizon, or an
// object at rest) `density` is empty: uniform seeds, noted in `choices` with the reason.
struct GradedSeeds {
    Impact impact;
    std::vector<Contact> grading;  // the contacts the density is graded by
    double ratio = 1;              // as used (unit: 1)
    double radius = 0;             // as used (unit: m)
    std::vector<double> density;   // per tet; empty: uniform
    nlohmann::ordered_json record() const;  // for the model's settings ("impact")
};
GradedSeeds grade_by_impact(const TetMesh& mesh, const TetTopology& topology, const PrescoreSettings& settings,
                            const SceneSettings& scene, const ObjectSettings& object, double diagonal,
                            AutoChoices& choices);

}  // namespace shatter
