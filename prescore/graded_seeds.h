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

#include <nlohmann/json_fwd.hpp>

#include "core/geometry.h"
#include "core/scene_settings.h"
#include "core/settings.h"
#include "prescore/adapt.h"
#include "prescore/impact.h"
#include "prescore/tet_topology.h"

namespace shatter {

std::vector<double> impact_density(const TetMesh& mesh, const std::vector<Vec3>& contacts, double ratio,
                                   double radius);

// impact_ratio and impact_radius = "auto" (the default): from the impact's damage number
//
//   D = rho v^2 / sigma
//
// (Johnson, "Impact Strength of Materials", 1972): rho the object's density, v the contact's
// closing speed, sigma the material's tensile strength; twice the kinetic energy per unit volume
// the impact brings over the energy per unit volume the material takes as stress. By energy
// balance (Grady, J. Appl. Phys. 53, 1982) fragments per unit volume grow as the strain rate
// squared, so with v: the density of seeds at the contact over far grows as D, and the zone it
// reaches as a Hertzian contact's radius does, as v^(2/5) = D^(1/5):
//
//   ratio  = 1 + kRatioPerDamage D, within [1, kMaxAutoRatio]
//   radius = kAutoRadius (D / kReferenceDamage)^(1/5) of the diagonal, within [kAutoRadius / 2, 2 kAutoRadius]
//
// The two constants are fitted, not derived: a 1.5 m fall of the default shot's 20 kPa,
// 1,100 kg/m^3 cast (D = 1.6) gets ratio 20 and radius 0.2 of the diagonal, the values that graded
// the bunny at 40 pieces to near / far mean volumes of 0.19 (docs/log.md). The demo's bunny, whose
// lowest point falls 1.40 m and closes at 5.24 m/s (D = 1.51), gets 19.1 and 0.198 of the diagonal
// (0.0636 m): 0.20 (docs/results/study.md, "Uniform and impact seeds"). An impact whose automatic
// ratio is under kMinAutoRatio (D < 1 / 12: the cast dropped less than 8 cm, glass or porcelain
// from 1.5 m, D = 0.0018) grades nothing: uniform seeds, noted (graded seeds grow by density, not
// by tets, so a ratio near 1 would still give other pieces than uniform seeds, for no grading).
inline constexpr double kRatioPerDamage = 12;
inline constexpr double kMinAutoRatio = 2;
inline constexpr double kMaxAutoRatio = 100;
inline constexpr double kAutoRadius = 0.2;       // (unit: of the diagonal)
inline constexpr double kReferenceDamage = 1.6;
struct AutoGrading {
    double damage = 0;  // D (unit: 1)
    double ratio = 1;   // (unit: 1)
    double radius = 0;  // (unit: m)
};
// `density` (unit: kg/m^3), `strength` (unit: Pa), `speed` (unit: m/s), `diagonal` (unit: m).
AutoGrading auto_grading(double density, double strength, double speed, double diagonal);

// seeds = "impact": the object's first contacts in the shot's scene (impact.h) and the density
// they give each tet. Without a contact that closes (nothing hit within the horizon, or an
// object at rest), or with an automatic ratio under kMinAutoRatio, `density` is empty: uniform
// seeds, noted in `choices` with the reason.
struct GradedSeeds {
    Impact impact;
    std::vector<Contact> grading;  // the contacts the density is graded by
    double ratio = 1;              // as used (unit: 1)
    double radius = 0;             // as used (unit: m)
    double damage = 0;             // the first grading contact's damage number D (unit: 1)
    bool auto_ratio = false, auto_radius = false;  // chosen from D
    std::vector<double> density;   // per tet; empty: uniform
    nlohmann::ordered_json record() const;  // for the model's settings ("impact")
};
GradedSeeds grade_by_impact(const TetMesh& mesh, const TetTopology& topology, const PrescoreSettings& settings,
                            const SceneSettings& scene, const ObjectSettings& object,
                            const MaterialSettings& material, double diagonal, AutoChoices& choices);

}  // namespace shatter
