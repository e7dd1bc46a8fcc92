// Mass properties against closed forms: a cube and a box (exact), a spherical shell (within the
// discretisation), and a rotated, translated box (the tensor rotates as R I R^T).
#include "prescore/mass_properties.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "core/error.h"
#include "prescore/tet_test_meshes.h"

namespace shatter {
namespace {

TEST(MassProperties, TetrahedralizedCubeIsExact) {
    const double a = 0.5, rho = 800;
    const Vec3 origin(1, 2, 3);
    const TetMesh mesh = test::cube_grid(4, 4, 4, a / 4, origin);
    const MassProperties p = mass_properties(mesh, test::all_tets(mesh), rho);
    const double m = rho * a * a * a;
    EXPECT_NEAR(p.volume, a * a * a, 1e-14);
    EXPECT_NEAR(p.mass, m, 1e-11);
    EXPECT_LT((p.center - (origin + Vec3::Constant(a / 2))).norm(), 1e-13);
    EXPECT_LT((p.inertia - m * a * a / 6 * Mat3::Identity()).norm(), 1e-12 * m * a * a);
}

TEST(MassProperties, SphericalShellMatchesClosedFormWithinDiscretisation) {
    const double R = 1.2, r = 0.8, rho = 2500;
    const TetMesh mesh = test::spherical_shell(R, r, 4, 3, Vec3(0.3, -0.2, 0.1));
    const MassProperties p = mass_properties(mesh, test::all_tets(mesh), rho);
    const double volume = 4.0 / 3.0 * M_PI * (R * R * R - r * r * r);
    const double m = rho * volume;
    const double I = 0.4 * m * (std::pow(R, 5) - std::pow(r, 5)) / (R * R * R - r * r * r);
    EXPECT_NEAR(p.volume, volume, 0.01 * volume);
    EXPECT_NEAR(p.mass, m, 0.01 * m);
    EXPECT_LT((p.center - Vec3(0.3, -0.2, 0.1)).norm(), 1e-3 * R);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(p.inertia(i, i), I, 0.02 * I);
    EXPECT_LT((p.inertia - p.inertia.diagonal().asDiagonal().toDenseMatrix()).norm(), 0.01 * I);
}

TEST(MassProperties, RotatedTranslatedBoxGivesRotatedTensor) {
    const double rho = 1000, h = 0.1;
    const TetMesh box = test::cube_grid(4, 2, 1, h);  // 0.4 x 0.2 x 0.1 m
    const double a = 0.4, b = 0.2, c = 0.1, m = rho * a * b * c;
    const Mat3 local = m / 12 * Vec3(b * b + c * c, a * a + c * c, a * a + b * b).asDiagonal().toDenseMatrix();

    const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    const Vec3 shift(-5, 7, 2);
    TetMesh moved = box;
    for (Vec3& v : moved.vertices) v = R * v + shift;
    const MassProperties p = mass_properties(moved, test::all_tets(moved), rho);
    EXPECT_NEAR(p.mass, m, 1e-12 * m);
    EXPECT_LT((p.center - (R * Vec3(a / 2, b / 2, c / 2) + shift)).norm(), 1e-12);
    EXPECT_LT((p.inertia - R * local * R.transpose()).norm(), 1e-9 * local.norm());
}

TEST(MassProperties, SubsetOfTetsCountsOnlyThoseTets) {
    const TetMesh mesh = test::cube_grid(2, 1, 1, 1.0);  // cells emitted in order: tets 0-5 are x in [0,1]
    const MassProperties p = mass_properties(mesh, {0, 1, 2, 3, 4, 5}, 1.0);
    EXPECT_NEAR(p.volume, 1.0, 1e-14);
    EXPECT_LT((p.center - Vec3(0.5, 0.5, 0.5)).norm(), 1e-14);
}

TEST(MassProperties, EmptySetIsZeroAndBadDensityIsAnInputError) {
    const TetMesh mesh = test::cube_grid(1, 1, 1, 1.0);
    EXPECT_EQ(mass_properties(mesh, {}, 1000).mass, 0.0);
    EXPECT_THROW(mass_properties(mesh, {0}, 0.0), Error);
    EXPECT_THROW(mass_properties(mesh, {0}, -1.0), Error);
    EXPECT_THROW(mass_properties(mesh, {0}, NAN), Error);
}

}  // namespace
}  // namespace shatter
