#include "simulate/bullet_shapes.h"

#include <LinearMath/btConvexHullComputer.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "simulate/bullet_convert.h"

namespace shatter {

double collision_margin(double volume) { return std::clamp(0.02 * std::cbrt(volume), 1e-4, 0.04); }

btConvexHullShape* make_part(const ConvexPart& part, const Mat3& principal, const Vec3& center, double margin) {
    std::vector<double> coords;
    for (const Vec3& p : part.points) {
        const Vec3 local = principal.transpose() * (p - center);
        coords.insert(coords.end(), {local.x(), local.y(), local.z()});
    }
    btConvexHullComputer hull;
    const btScalar shrunk = hull.compute(coords.data(), 3 * sizeof(double), int(part.points.size()), btScalar(margin),
                                         btScalar(0.25));
    auto* shape = new btConvexHullShape();
    if (shrunk >= 0 && hull.vertices.size() >= 4) {
        for (int i = 0; i < hull.vertices.size(); ++i) shape->addPoint(hull.vertices[i], false);
        shape->setMargin(shrunk);
    } else {  // too thin to shrink: the part as it is, with a tiny margin
        for (size_t i = 0; i < part.points.size(); ++i)
            shape->addPoint(btVector3(btScalar(coords[3 * i]), btScalar(coords[3 * i + 1]), btScalar(coords[3 * i + 2])),
                            false);
        shape->setMargin(btScalar(1e-4));
    }
    shape->recalcLocalAabb();
    return shape;
}

void principal_frame(const Mat3& inertia, Mat3* r, Vec3* moments) {
    Eigen::SelfAdjointEigenSolver<Mat3> eigen(inertia);
    *r = eigen.eigenvectors();
    *moments = eigen.eigenvalues();
    for (int c = 0; c < 3; ++c) {  // a sign that does not depend on the solver: largest component positive
        Eigen::Index k = 0;
        r->col(c).cwiseAbs().maxCoeff(&k);
        if ((*r)(k, c) < 0) r->col(c) = -r->col(c);
    }
    if (r->determinant() < 0) r->col(2) = -r->col(2);
}
}  // namespace shatter
