// Mass properties of shapes tetrahedralized by Mesh_3 (not built by hand) against closed form:
// the "tetrahedralized cube and sphere shell" check, 1% for volume and mass, 2% for inertia.
#include <gtest/gtest.h>

#include <cmath>

#include "prescore/mass_properties.h"
#include "prescore/tetrahedralize.h"
#include "tet_test_meshes.h"

namespace shatter {
namespace {

std::vector<uint32_t> all(const TetMesh& m) {
    std::vector<uint32_t> t(m.tets.size());
    for (uint32_t i = 0; i < t.size(); ++i) t[i] = i;
    return t;
}

TEST(MeshedMassProperties, TetrahedralizedCubeMatchesClosedForm) {
    // A 0.2 m cube of glass (2500 kg/m^3) centred at (1, 2, 3).
    const double a = 0.2, rho = 2500;
    TriangleMesh cube;
    for (int i = 0; i < 8; ++i)
        cube.vertices.emplace_back(1 + a * ((i == 1 || i == 2 || i == 5 || i == 6) - 0.5),
                                   2 + a * ((i == 2 || i == 3 || i == 6 || i == 7) - 0.5), 3 + a * ((i >= 4) - 0.5));
    cube.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                      {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
    const TetMesh tets = tetrahedralize(cube, tetrahedralize_settings_for(a * std::sqrt(3.0), 10));
    const MassProperties mp = mass_properties(tets, all(tets), rho);
    const double m = rho * a * a * a;
    EXPECT_NEAR(mp.volume, a * a * a, 0.01 * a * a * a);
    EXPECT_NEAR(mp.mass, m, 0.01 * m);
    EXPECT_LT((mp.center - Vec3(1, 2, 3)).norm(), 1e-3 * a);
    const double i = m * a * a / 6;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(mp.inertia(k, k), i, 0.02 * i);
    EXPECT_LT((mp.inertia - Mat3(mp.inertia.diagonal().asDiagonal())).norm(), 0.02 * i);
}

TEST(MeshedMassProperties, TetrahedralizedSphereShellMatchesClosedForm) {
    // Outer radius 0.1 m, inner 0.08 m: the inner sphere turned inside out bounds the cavity.
    const double R = 0.1, r = 0.08, rho = 1000;
    TriangleMesh outer = test::icosphere(4), surface;
    for (const Vec3& v : outer.vertices) surface.vertices.push_back(R * v);
    surface.triangles = outer.triangles;
    const uint32_t base = uint32_t(surface.vertices.size());
    for (const Vec3& v : outer.vertices) surface.vertices.push_back(r * v);
    for (const Tri& t : outer.triangles) surface.triangles.push_back({base + t[0], base + t[2], base + t[1]});
    const TetMesh tets = tetrahedralize(surface, tetrahedralize_settings_for(2 * R * std::sqrt(3.0), 40));
    const MassProperties mp = mass_properties(tets, all(tets), rho);
    const double volume = 4.0 / 3.0 * M_PI * (R * R * R - r * r * r);
    const double m = rho * volume;
    const double i = 0.4 * m * (std::pow(R, 5) - std::pow(r, 5)) / (R * R * R - r * r * r);
    EXPECT_NEAR(mp.volume, volume, 0.01 * volume);
    EXPECT_NEAR(mp.mass, m, 0.01 * m);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(mp.inertia(k, k), i, 0.02 * i);
}

}  // namespace
}  // namespace shatter
