// The seed density of graded_seeds.h.
#include "prescore/graded_seeds.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "meshio/mesh_load.h"

namespace shatter {

std::vector<double> impact_density(const TetMesh& mesh, const std::vector<Vec3>& contacts, double ratio,
                                   double radius) {
    assert(!contacts.empty() && radius > 0 && ratio >= 1);
    std::vector<double> w;
    w.reserve(mesh.tets.size());
    for (uint32_t t = 0; t < mesh.tets.size(); ++t) {
        const Vec3 c = tet_centroid(mesh, t);
        double d2 = std::numeric_limits<double>::infinity();
        for (const Vec3& p : contacts) d2 = std::min(d2, (c - p).squaredNorm());
        w.push_back(1 + (ratio - 1) * std::exp(-d2 / (radius * radius)));
    }
    return w;
}

AutoGrading auto_grading(double density, double strength, double speed, double diagonal) {
    AutoGrading a;
    a.damage = strength > 0 ? density * speed * speed / strength : std::numeric_limits<double>::infinity();
    a.ratio = std::clamp(1 + kRatioPerDamage * a.damage, 1.0, kMaxAutoRatio);
    a.radius = kAutoRadius * diagonal * std::clamp(std::pow(a.damage / kReferenceDamage, 0.2), 0.5, 2.0);
    return a;
}

namespace {

// The object's outer surface as the tets bound it (cavity faces too: they are inside).
TriangleMesh boundary(const TetMesh& mesh, const TetTopology& topology) {
    TriangleMesh out;
    std::vector<uint32_t> index(mesh.vertices.size(), UINT32_MAX);
    auto vertex = [&](uint32_t v) {
        if (index[v] == UINT32_MAX) index[v] = uint32_t(out.vertices.size()), out.vertices.push_back(mesh.vertices[v]);
        return index[v];
    };
    for (size_t t = 0; t < mesh.tets.size(); ++t)
        for (int f = 0; f < 4; ++f)
            if (topology.neighbour[t][f] < 0) {
                const auto& k = kTetFaces[f];
                out.triangles.push_back({vertex(mesh.tets[t][k[0]]), vertex(mesh.tets[t][k[1]]), vertex(mesh.tets[t][k[2]])});
            }
    return out;
}

nlohmann::ordered_json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

nlohmann::ordered_json GradedSeeds::record() const {
    nlohmann::ordered_json j;
    j["graded"] = !density.empty();
    if (!grading.empty()) {  // graded, or too gently (the ratio it would have had)
        j["ratio"] = ratio;
        j["radius_m"] = radius;
        j["damage_number"] = damage;
        j["ratio_auto"] = auto_ratio;
        j["radius_auto"] = auto_radius;
    }
    j["contacts"] = nlohmann::ordered_json::array();
    for (const Contact& c : impact.contacts) {
        bool grades = false;
        for (const Contact& g : grading) grades = grades || (g.with == c.with && g.time == c.time);
        j["contacts"].push_back({{"with", c.with}, {"time_s", c.time}, {"point_m", vec(c.point)},
                                 {"model_point_m", vec(c.model_point)}, {"normal", vec(c.normal)},
                                 {"speed_m_per_s", c.speed}, {"normal_speed_m_per_s", c.normal_speed},
                                 {"grades", grades}});
    }
    return j;
}

GradedSeeds grade_by_impact(const TetMesh& mesh, const TetTopology& topology, const PrescoreSettings& settings,
                            const SceneSettings& scene, const ObjectSettings& object,
                            const MaterialSettings& material, double diagonal, AutoChoices& choices) {
    GradedSeeds g;
    std::vector<TriangleMesh> collider_meshes(scene.colliders.size());
    for (size_t i = 0; i < scene.colliders.size(); ++i)
        if (const ShapeSettings& c = scene.colliders[i].shape; c.kind == ShapeKind::Mesh)
            collider_meshes[i] = load_mesh(c.mesh, c.mesh_scale);
    g.impact = find_impact(boundary(mesh, topology), scene, object, kContactTolerance * diagonal, &collider_meshes);
    g.grading = g.impact.grading();
    if (g.impact.spin_ignored) spdlog::info("impact: the object's spin is left out of the pre-pass's flight");
    if (g.impact.mesh_colliders_skipped > 0)
        spdlog::info("impact: {} mesh collider(s) not looked at by the pre-pass", g.impact.mesh_colliders_skipped);
    if (g.grading.empty()) {
        choices.note("seeds uniform",
                     g.impact.contacts.empty()
                         ? fmt::format("seeds = \"impact\", but the object hits nothing within {:g} s of its flight", kImpactHorizon)
                         : fmt::format("seeds = \"impact\", but the object's contacts close slower than {:g} m/s (it rests)",
                                       kMinImpactSpeed));
        return g;
    }
    const Contact& first = g.grading.front();
    const double density = material.density.value_or(settings.density);
    const AutoGrading a = auto_grading(density, material.strength, first.normal_speed, diagonal);
    g.damage = a.damage;
    g.auto_ratio = !settings.impact_ratio;
    g.auto_radius = !settings.impact_radius;
    g.ratio = settings.impact_ratio.value_or(a.ratio);
    g.radius = settings.impact_radius ? settings.impact_radius->resolve(diagonal) : a.radius;
    if (g.auto_ratio && g.ratio < kMinAutoRatio) {
        choices.note("seeds uniform",
                     fmt::format("seeds = \"impact\": the object first touches the {} at {:.2f} m/s, too gently to "
                                 "grade the seeds: the damage number rho v^2 / strength = {:.0f} kg/m^3 x ({:.2f} "
                                 "m/s)^2 / {:g} Pa = {:.3g} gives impact_ratio {:.3g}, under {:g} (a number given "
                                 "for impact_ratio is used as it is)",
                                 first.with, first.normal_speed, density, first.normal_speed, material.strength,
                                 g.damage, g.ratio, kMinAutoRatio));
        return g;
    }
    std::vector<Vec3> points;
    for (const Contact& c : g.grading) points.push_back(c.model_point);
    g.density = impact_density(mesh, points, g.ratio, g.radius);
    const std::string why =
        g.auto_ratio || g.auto_radius
            ? fmt::format(" ({} from the damage number rho v^2 / strength = {:.0f} kg/m^3 x ({:.2f} m/s)^2 / {:g} Pa "
                          "= {:.3g})",
                          g.auto_ratio && g.auto_radius ? "both" : g.auto_ratio ? "the ratio" : "the radius", density,
                          first.normal_speed, material.strength, g.damage)
            : "";
    choices.note(fmt::format("seeds graded by the impact on the {} at ({:.3f}, {:.3f}, {:.3f}) m: {:.3g} times denser, "
                             "over {:.3g} m",
                             first.with, first.point.x(), first.point.y(), first.point.z(), g.ratio, g.radius),
                 fmt::format("seeds = \"impact\": the object's rigid flight first touches the {} after {:.3f} s at "
                             "{:.2f} m/s; seeds {:.3g} times denser there, falling off over {:.3g} m{}, and the pieces "
                             "grow by density, not by tets{}",
                             first.with, first.time, first.speed, g.ratio, g.radius, why,
                             g.grading.size() > 1 ? fmt::format(" ({} contacts at once)", g.grading.size()) : ""));
    return g;
}

}  // namespace shatter
